"""``python -m symjac``: the same as the ``symjac`` command."""

import sys

from symjac.cli.main import main

sys.exit(main())
