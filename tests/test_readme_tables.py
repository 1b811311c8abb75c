"""README.md's result tables are generated from the committed benchmarks/results/*.json by
tools/readme_tables.py: they must match, and a missing file or key must fail clearly."""

from __future__ import annotations

import importlib.util
import json
import shutil
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "readme_tables.py"


@pytest.fixture(scope="module")
def tables():
    spec = importlib.util.spec_from_file_location("readme_tables", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    try:
        spec.loader.exec_module(module)
        yield module
    finally:
        sys.modules.pop(spec.name, None)


def test_readme_tables_match_the_committed_results(tables, capsys):
    code = tables.main(["--check"])
    out = capsys.readouterr()
    assert code == 0, (
        "README.md's generated tables differ from benchmarks/results/*.json; "
        "run `python tools/readme_tables.py` (or `make results` to refresh the results)\n"
        + out.out
        + out.err
    )


def test_every_table_has_its_markers_and_result_files(tables):
    readme = (ROOT / "README.md").read_text()
    for table in tables.TABLES:
        assert readme.count(f"<!-- table:{table.name}:begin -->") == 1, table.name
        assert readme.count(f"<!-- table:{table.name}:end -->") == 1, table.name
        for name in table.files:
            assert (tables.RESULTS / name).is_file(), name


def _copy_results(tables, tmp_path: Path) -> Path:
    results = tmp_path / "results"
    results.mkdir()
    for path in tables.RESULTS.glob("*.json"):  # the tables' files and the quoted figures'
        shutil.copy(path, results / path.name)
    readme = tmp_path / "README.md"
    shutil.copy(ROOT / "README.md", readme)
    return results


def _one_line_error(tables, tmp_path, results, capsys) -> str:
    code = tables.main(
        ["--check", "--readme", str(tmp_path / "README.md"), "--results", str(results)]
    )
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert "\n" not in err and err.startswith("readme_tables: error: ")
    return err


def test_a_missing_result_file_is_named(tables, tmp_path, capsys):
    results = _copy_results(tables, tmp_path)
    (results / "plant.json").unlink()
    err = _one_line_error(tables, tmp_path, results, capsys)
    assert "plant.json" in err and "not found" in err


def test_a_missing_key_is_named_with_its_file(tables, tmp_path, capsys):
    results = _copy_results(tables, tmp_path)
    path = results / "demo-metrics.json"
    metrics = json.loads(path.read_text())
    comp = "shape-aware InverseFeedforward + EncoderLoop"
    del metrics["details"]["do2015"]["servo_summary"]["pid"][comp]["factor_fixed"]
    path.write_text(json.dumps(metrics))
    err = _one_line_error(tables, tmp_path, results, capsys)
    key = f"'details.do2015.servo_summary.pid.{comp}.factor_fixed'"
    assert "demo-metrics.json" in err and key in err


def test_a_non_number_is_named(tables, tmp_path, capsys):
    results = _copy_results(tables, tmp_path)
    path = results / "demo-metrics.json"
    metrics = json.loads(path.read_text())
    metrics["robustness"]["runs"] = None
    path.write_text(json.dumps(metrics))
    err = _one_line_error(tables, tmp_path, results, capsys)
    assert "demo-metrics.json" in err and "'robustness.runs'" in err and "not a number" in err


def test_a_drift_is_reported_as_a_diff(tables, tmp_path, capsys):
    results = _copy_results(tables, tmp_path)
    readme = tmp_path / "README.md"
    begin = "<!-- table:scenarios:begin -->\n"
    readme.write_text(readme.read_text().replace(begin, begin + "| hand-edited |\n"))
    code = tables.main(["--check", "--readme", str(readme), "--results", str(results)])
    out = capsys.readouterr().out
    assert code == 1
    assert "-| hand-edited |" in out and "+++" in out
    assert tables.main(["--readme", str(readme), "--results", str(results)]) == 0
    assert tables.main(["--check", "--readme", str(readme), "--results", str(results)]) == 0


def test_three_significant_digits(tables):
    fmt = tables.fmt
    assert [fmt(0.0158), fmt(8.2815e-5), fmt(1257.3), fmt(9.996), fmt(0.5), fmt(0.0)] == [
        "0.0158",
        "8.28e-5",
        "1260",
        "10.0",
        "0.500",
        "0",
    ]
    assert fmt(0.0012, trim=True) == "0.0012" and fmt(1e-4, trim=True) == "1e-4"
    assert fmt(float("nan")) == "n/a"


def test_the_figures_the_prose_quotes_are_the_results(tables):
    """README.md's and the docs pages' ``<!-- result: FILE KEY ~ FIGURE -->`` markers: each
    figure is its result's, rounded as quoted (the check `--check` runs on README.md)."""
    pages = {"README.md": ROOT / "README.md"}
    pages.update({p.relative_to(ROOT).as_posix(): p for p in (ROOT / "docs").rglob("*.md")})
    wrong, count = [], 0
    for name, path in pages.items():
        text = path.read_text()
        count += len(tables.RESULT.findall(text))
        wrong += tables.figures_wrong(text, tables.RESULTS, name)
    assert wrong == []
    assert count >= 50  # the markers are read (a changed syntax would find none)


def test_a_stale_quoted_figure_fails_the_check(tables, tmp_path, capsys):
    results = _copy_results(tables, tmp_path)
    path = results / "tool5_sessions.json"
    data = json.loads(path.read_text())
    data["summary"]["recalibrated_over_own"]["median"] = 1.5  # the README quotes 1.62
    path.write_text(json.dumps(data))
    readme = tmp_path / "README.md"
    code = tables.main(["--check", "--readme", str(readme), "--results", str(results)])
    out = capsys.readouterr().out
    assert code == 1 and "summary.recalibrated_over_own.median is 1.5; the text quotes 1.62" in out
    # a figure the prose no longer quotes (the marker left behind) fails too
    text = readme.read_text().replace("is 1.62x a model", "is 1.7x a model")
    assert tables.figures_wrong(text, tables.RESULTS)[0].endswith("no longer quotes 1.62")
    assert tables.rounds_to(0.1349, "0.135") and not tables.rounds_to(0.1349, "0.14")
    assert tables.rounds_to(8.5626e-2, "8.56e-2") and tables.rounds_to(30.7, "31")
