"""``python -m symjac``: the same as the ``symjac`` command."""

from symjac.cli.main import run

run()
