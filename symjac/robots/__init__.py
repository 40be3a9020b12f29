"""The built-in robot catalog: one TOML robot file per robot (data, not code)."""

__all__ = []
