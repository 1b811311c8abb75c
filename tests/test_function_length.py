"""No function in the package is over 80 lines (issue 14: functions short enough to carry).

A function's length is its lines as ``ast`` gives them, signature and comments included,
less its docstring: the numpydoc Parameters/Returns sections the API walk asks for
(tests/test_api_walk.py) grow with the number of parameters, not with the logic to carry.
``STILL_LONG`` lists the functions other Step 11 branches are splitting; an entry is an
error once its function is short, so the list can only shrink.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "python" / "tendonsheath"
LIMIT = 80

# being split on other branches of issue 14 (identify as an estimator, the open bench,
# one simulate result type); remove an entry when its function is short
STILL_LONG = {
    "bench/run.py:run",
}


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
    long = {k: n for k, n in lengths.items() if n > LIMIT and k not in STILL_LONG}
    assert not long, f"functions over {LIMIT} lines (split them into named steps): {long}"


@pytest.mark.parametrize("name", sorted(STILL_LONG))
def test_a_listed_long_function_is_still_long(name, lengths):
    assert name in lengths, f"{name} is gone: remove it from STILL_LONG"
    assert lengths[name] > LIMIT, f"{name} is {lengths[name]} lines now: remove it from STILL_LONG"
