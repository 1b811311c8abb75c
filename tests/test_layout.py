"""Where code lives: the installed include tree is real-time only, and the package ships no
test references or stand-ins (issue 14, layout)."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CORE = ROOT / "include" / "tendonsheath"
PACKAGE = ROOT / "python" / "tendonsheath"

THREADS = re.compile(r"#\s*include\s*<(thread|future|mutex|condition_variable|shared_mutex)>")
FILE_IO = re.compile(r"\b(fopen|fread|fwrite|ifstream|ofstream|fstream)\b")


def lines_matching(files, pattern):
    return [
        f"{f.relative_to(ROOT)}:{i}"
        for f in files
        for i, line in enumerate(f.read_text().splitlines(), 1)
        if pattern.search(line)
    ]


def test_the_real_time_tree_spawns_no_threads():
    headers = sorted(CORE.rglob("*.hpp"))
    assert len(headers) > 20
    assert lines_matching(headers, THREADS) == []


def test_files_are_read_only_by_the_start_up_loader_in_io():
    # io/json.hpp reads a compensator file once, before the loop; nothing else in the
    # real-time tree touches files
    outside_io = [f for f in sorted(CORE.rglob("*.hpp")) if f.parent.name != "io"]
    assert lines_matching(outside_io, FILE_IO) == []


def test_the_package_ships_no_test_reference_or_stand_in():
    modules = sorted(PACKAGE.rglob("*.py"))
    names = [m.name for m in modules]
    assert not [n for n in names if n.startswith("_reference") or n == "example_runs.py"]
    imports_tests = re.compile(r"^\s*(from|import)\s+reference\b")
    assert lines_matching(modules, imports_tests) == []
