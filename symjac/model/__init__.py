"""The robot as data: joints, parameters and conventions, read from robot files, URDF and the catalog."""

__all__: list[str] = []
