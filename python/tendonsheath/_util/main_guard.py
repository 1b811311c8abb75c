"""The local engine's worker processes (forkserver or spawn) import the user's script again:
a script that starts a sweep at its top level, without an ``if __name__ == "__main__":``
guard, would start it again in every worker. Caught here before any process starts, and in
a worker that is re-running the script, each with a one-line reason."""

from __future__ import annotations

import ast
import multiprocessing
import sys
from pathlib import Path

ADVICE = (
    'put the sweep under `if __name__ == "__main__":` (worker processes import the script '
    'again), or use engine="serial"'
)


def unguarded_script() -> str | None:
    """The running script's path when it has no top-level ``if __name__ == "__main__":``
    block, else None (an interactive session, ``python -c``, a console script)."""
    path = getattr(sys.modules.get("__main__"), "__file__", None)
    if not path or not str(path).endswith(".py"):
        return None
    try:
        tree = ast.parse(Path(path).read_text(encoding="utf-8"))
    except (OSError, SyntaxError, UnicodeDecodeError, ValueError):
        return None
    return None if any(_is_main_guard(node) for node in tree.body) else str(path)


def _is_main_guard(node) -> bool:
    if not isinstance(node, ast.If):
        return False
    names = {n.id for n in ast.walk(node.test) if isinstance(n, ast.Name)}
    consts = {n.value for n in ast.walk(node.test) if isinstance(n, ast.Constant)}
    return "__name__" in names and "__main__" in consts


def in_bootstrapping_worker() -> bool:
    """True in a worker process that is importing the parent's script (spawn/forkserver)."""
    return bool(getattr(multiprocessing.current_process(), "_inheriting", False))


__all__ = ["ADVICE", "in_bootstrapping_worker", "unguarded_script"]
