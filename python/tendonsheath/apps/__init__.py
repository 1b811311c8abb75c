"""The applications built on the library's layers: the command line, the demo, model comparison,
sessions, the C++ exporters. Their public functions are on ``tendonsheath`` itself."""

__all__: list[str] = []
