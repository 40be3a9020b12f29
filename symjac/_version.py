"""The one source of symjac's version (read by the package, the CLI, generated headers and the build)."""

__all__ = ["__version__"]

__version__ = "0.1.0"
"""The package version (PEP 440)."""
