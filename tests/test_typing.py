"""The package is typed (PEP 561): the marker ships, and the C++ extension's stubs, written by
nanobind's stub generator at build time, describe the extension that is installed."""

from __future__ import annotations

import ast
from pathlib import Path

import tendonsheath as ts
from tendonsheath import _core

PACKAGE = Path(ts.__file__).parent


def _stub_names(text: str) -> set[str]:
    """The top-level classes, functions and assignments a stub file declares."""
    names = set()
    for node in ast.parse(text).body:
        if isinstance(node, ast.ClassDef | ast.FunctionDef):
            names.add(node.name)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names


def test_the_package_is_marked_typed():
    assert (PACKAGE / "py.typed").is_file()


def test_the_extension_stubs_name_everything_it_exports():
    stub = Path(_core.__file__).with_name("_core.pyi")
    assert stub.is_file(), "no _core.pyi beside the extension"
    exported = {n for n in dir(_core) if not n.startswith("_")}
    missing = exported - _stub_names(stub.read_text())
    assert not missing, f"_core.pyi lacks {sorted(missing)}: stale stubs"
    assert len(exported) > 50  # the real extension, not an empty module


def test_the_stub_check_can_fail():
    text = "class Route:\n    def angle_at(self, s: float) -> float: ...\n\nX: int\n"
    assert _stub_names(text) == {"Route", "X"}
