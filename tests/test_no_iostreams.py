"""The C++ core and the bindings use no iostreams (issue 15: `std::ostringstream << double`
crashed when another libstdc++ was loaded); numbers are formatted with std::to_chars."""

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IOSTREAM_HEADERS = re.compile(
    r"#\s*include\s*<(iostream|[io]?stream|sstream|[io]?fstream|iomanip)>"
)
IOSTREAM_NAMES = re.compile(r"std::(ostringstream|istringstream|stringstream|cout|cerr|clog)\b")


def test_no_iostreams_in_the_library():
    files = sorted((ROOT / "include").rglob("*.hpp")) + sorted((ROOT / "src").rglob("*.[ch]pp"))
    assert len(files) > 20
    offenders = [
        f"{f.relative_to(ROOT)}:{i}"
        for f in files
        for i, line in enumerate(f.read_text().splitlines(), 1)
        if IOSTREAM_HEADERS.search(line) or IOSTREAM_NAMES.search(line)
    ]
    assert offenders == []
