"""Running documentation code as written: the Python blocks of a Markdown text, and a block
that is a script of its own (it has an ``if __name__ == "__main__":`` block) run in a fresh
interpreter with its run lengths shortened."""

import re
import subprocess
import sys
from pathlib import Path

MAIN_GUARD = 'if __name__ == "__main__":'


def python_blocks(markdown: str) -> list[str]:
    return re.findall(r"```python\n(.*?)```", markdown, flags=re.S)


def run_as_script(code: str, path: Path, shorter: dict[str, str], source: str) -> None:
    """Write ``code`` to ``path`` with each key of ``shorter`` (which must stand in it once)
    replaced by its value, and run it in its folder; ``source`` names the text in a failure."""
    for long, short in shorter.items():
        assert code.count(long) == 1, f"{source}'s script no longer holds {long!r}"
        code = code.replace(long, short)
    path.write_text(code)
    done = subprocess.run(
        [sys.executable, str(path)], capture_output=True, text=True, timeout=600, cwd=path.parent
    )
    assert done.returncode == 0, done.stderr[-3000:]
