"""The one source of symjac's version (read by the package, the CLI, generated headers and the build)."""

__version__ = "0.1.0"
