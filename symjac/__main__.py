import sys

from symjac.cli import main

sys.exit(main())
