"""No function in the package, src/ or include/ is over 80 lines (issue 14: functions short
enough to carry). The C++ functions are measured by lizard, the Python ones by ``ast``.

A function's length is its lines as ``ast`` gives them, signature and comments included,
less its docstring: the numpydoc Parameters/Returns sections the API walk asks for
(tests/test_api_walk.py) grow with the number of parameters, not with the logic to carry.
"""

from __future__ import annotations

import ast
from pathlib import Path

import lizard
import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "python" / "tendonsheath"
LIMIT = 80


def function_lengths(root: Path) -> dict[str, int]:
    """The number of lines of every function (nested ones too) in the .py files below
    ``root``, less its docstring, by "file:function"."""
    out = {}
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                key = f"{path.relative_to(root).as_posix()}:{node.name}"
                n = node.end_lineno - node.lineno + 1
                if ast.get_docstring(node, clean=False) is not None:
                    doc = node.body[0]
                    n -= doc.end_lineno - doc.lineno + 1
                out[key] = max(out.get(key, 0), n)
    return out


def test_the_counter_sees_a_long_function(tmp_path):
    body = "\n".join(f"    x{i} = {i}" for i in range(LIMIT))
    (tmp_path / "m.py").write_text(f"def long():\n{body}\n\n\ndef short():\n    return 1\n")
    doc = '    """One line.\n\n    More lines.\n    """\n'
    (tmp_path / "m.py").write_text(
        f"def long():\n{body}\n\n\ndef short():\n    return 1\n\n\n"
        f"def documented():\n{doc}    return 1\n"
    )
    assert function_lengths(tmp_path) == {
        "m.py:long": LIMIT + 1,
        "m.py:short": 2,
        "m.py:documented": 2,
    }


@pytest.fixture(scope="module")
def lengths() -> dict[str, int]:
    return function_lengths(PACKAGE)


def test_no_function_is_over_80_lines(lengths):
    long = {k: n for k, n in lengths.items() if n > LIMIT}
    assert not long, f"functions over {LIMIT} lines (split them into named steps): {long}"


def cpp_function_lengths(*roots: Path) -> dict[str, int]:
    """Lines of every C++ function (comments included) below ``roots``, by "path:name"."""
    out = {}
    for root in roots:
        for path in sorted([*root.rglob("*.cpp"), *root.rglob("*.hpp")]):
            for f in lizard.analyze_file(str(path)).function_list:
                out[f"{path.as_posix()}:{f.name}"] = f.length
    return out


def test_the_cpp_counter_sees_a_long_function(tmp_path):
    body = "\n".join(f"  x += {i};" for i in range(LIMIT))
    (tmp_path / "m.cpp").write_text(f"int long_one(int x) {{\n{body}\n  return x;\n}}\n")
    assert cpp_function_lengths(tmp_path) == {f"{tmp_path.as_posix()}/m.cpp:long_one": LIMIT + 3}


def test_no_cpp_function_is_over_80_lines():
    lengths = cpp_function_lengths(ROOT / "src", ROOT / "include")
    assert len(lengths) > 300  # the walk found the bindings and the headers
    long = {k: n for k, n in lengths.items() if n > LIMIT}
    assert not long, f"C++ functions over {LIMIT} lines (split them): {long}"
