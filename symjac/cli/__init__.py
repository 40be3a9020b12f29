"""The ``symjac`` command: parse the arguments, call the API, build the document, render it."""

__all__: list[str] = []
