"""Every numbered Python example runs and writes what it says."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

# the quickest of the built-in scenarios (tests/test_scenarios.py runs every one)
EXTRA_ARGS = {"05_virtual_bench_report.py": ["--scenario", "sun2015"]}
EXAMPLES = sorted((Path(__file__).resolve().parent.parent / "examples").glob("[0-9]*.py"))


def announced_files(stdout: str, cwd: Path) -> list[Path]:
    """The files an example says it wrote: 'wrote A [and B]' and 'figure: A' lines."""
    paths = []
    for line in stdout.splitlines():
        m = re.match(r"\s*(?:wrote|figure:)\s+(.+)$", line)
        if m:
            paths += [Path(p.strip()) for p in m.group(1).split(" and ")]
    return [p if p.is_absolute() else cwd / p for p in paths]


@pytest.mark.parametrize("script", EXAMPLES, ids=lambda p: p.name)
def test_example_runs(script, tmp_path):
    args = [sys.executable, str(script)]
    text = script.read_text()
    if "--out" in text:
        args += ["--out", str(tmp_path)]
    if "--scale" in text:
        args += ["--scale", "0.2"]
    if '"--n"' in text:  # a sweep's size: a handful of draws shows it runs
        args += ["--n", "8"]
    args += EXTRA_ARGS.get(script.name, [])
    result = subprocess.run(args, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert result.returncode == 0, result.stderr[-3000:]
    # every file it announces exists, is not empty, and lies in its output folder; an
    # example that takes --out announces at least one
    written = announced_files(result.stdout, tmp_path)
    if "--out" in text:
        assert written, result.stdout[-2000:]
    for path in written:
        assert path.is_file() and path.stat().st_size > 0, (path, result.stdout[-2000:])
        assert path.resolve().is_relative_to(tmp_path.resolve()), path


def test_the_cpp_examples_are_paired_with_python_by_number():
    # as pantor/ruckig lays them out: examples/NN_task.py and examples/cpp/NN_task.cpp do the
    # same task; a number without a C++ file is Python-only (identification, reports, sweeps)
    root = Path(__file__).resolve().parent.parent / "examples"
    cpp = sorted(p.stem for p in (root / "cpp").glob("[0-9]*.cpp"))
    python = [p.stem for p in EXAMPLES]
    assert len(cpp) >= 5
    assert [s for s in cpp if s not in python] == []
    numbers = [s.split("_", 1)[0] for s in python]
    assert len(set(numbers)) == len(numbers), "two Python examples share a number"
