"""Material for the classroom: the errata sheet of the course notes and the exercises."""

__all__: list[str] = []
