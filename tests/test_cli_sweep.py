"""`tendonsheath sweep sweep.toml --out DIR`: files, summary, errors before any work."""

import json

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from tendonsheath.apps.cli import app
from tendonsheath.sweep import Integers, LatinHypercube, Normal, Relative, Seed
from tendonsheath.sweep.toml import read_sweep_file

runner = CliRunner()

TOML = """
[run]
function = "reference.stand_in_study:compensator_study"

[sweep]
design = "lhs"
n = 6
seed = 3
workers = 2

[parameters]
friction = { relative = [0.1, 0.3] }
pretension = { relative = [10.0, 0.3] }
route_angle = { uniform = [1.5, 4.5] }
route_seed = { seed = true }
route_pieces = 2
elements = 12
samples = 150

[report]
bound = { mse = 1e-4 }
"""


def write(tmp_path, text, name="sweep.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_sweep_command_writes_table_summary_and_figures(tmp_path):
    cfg = write(tmp_path, TOML)
    out = tmp_path / "out"
    result = runner.invoke(app, ["sweep", str(cfg), "--out", str(out), "--no-figures"])
    assert result.exit_code == 0, result.output
    table = pd.read_parquet(out / "table.parquet")
    assert len(table) == 6 * 3 and set(table["compensator"]) == {
        "none",
        "curve_angle",
        "inverse_backlash",
    }
    pd.testing.assert_frame_equal(pd.read_csv(out / "table.csv"), table)
    meta = json.loads((out / "summary.json").read_text())
    assert meta["design"] == "lhs" and meta["seed"] == 3 and meta["bound"] == {"mse": 1e-4}
    # the fraction within the bound, per compensator, counted here from the written table
    fractions = {
        r["compensator"]: r["within_bound"] for r in meta["summary"] if r["metric"] == "mse"
    }
    counted = {c: float(np.mean(g["mse"] <= 1e-4)) for c, g in table.groupby("compensator")}
    assert fractions == pytest.approx(counted, abs=1e-9)  # summary.json keeps 10 digits
    assert meta["sensitivity"]
    assert "mse over 6 runs" in result.output and "table.parquet" in result.output
    # the same file again: the same table (reproducible from the seed)
    again = runner.invoke(app, ["sweep", str(cfg), "--out", str(tmp_path / "again"),
                                "--no-figures", "--workers", "1"])  # fmt: skip
    assert again.exit_code == 0, again.output
    pd.testing.assert_frame_equal(pd.read_parquet(tmp_path / "again" / "table.parquet"), table)


def test_figures(tmp_path):
    cfg = write(tmp_path, TOML.replace("workers = 2", "workers = 1"))
    result = runner.invoke(app, ["sweep", str(cfg), "--out", str(tmp_path / "o")])
    assert result.exit_code == 0, result.output
    for name in ("hist_mse.png", "mse_vs_parameters.png", "sensitivity.png"):
        assert (tmp_path / "o" / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_saltelli_file_gives_sobol_indices(tmp_path):
    text = TOML.replace('design = "lhs"', 'design = "saltelli"').replace("n = 6", "n = 4")
    text = text.replace("route_seed = { seed = true }\n", "").replace("workers = 2", "workers = 1")
    cfg = write(tmp_path, text)
    result = runner.invoke(app, ["sweep", str(cfg), "--out", str(tmp_path / "o"), "--no-figures"])
    assert result.exit_code == 0, result.output
    meta = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert meta["runs"] == 4 * (3 + 2)
    assert {r["method"] for r in meta["sensitivity"]} == {"sobol"}
    assert {"S1", "ST", "ST_conf"} <= set(meta["sensitivity"][0])


def test_file_format_maps_to_distributions(tmp_path):
    spec = read_sweep_file(write(tmp_path, TOML))
    assert isinstance(spec.design, LatinHypercube)
    d = spec.design.distributions
    assert d["friction"] == Relative(0.1, 0.3) and isinstance(d["route_seed"], Seed)
    assert spec.design.fixed == {"route_pieces": 2, "elements": 12, "samples": 150}
    text = TOML.replace('design = "lhs"', 'design = "random"').replace(
        "route_pieces = 2", "route_pieces = { integers = [1, 3] }\nload = { mean = 1.0, std = 0.2 }"
    )
    spec = read_sweep_file(write(tmp_path, text))
    assert spec.design.distributions["route_pieces"] == Integers(1, 3)
    assert spec.design.distributions["load"] == Normal(1.0, 0.2)
    grid = "[run]\nfunction = 'reference.stand_in_study:compensator_study'\n"
    grid += "[sweep]\ndesign = 'grid'\n[parameters]\n"
    grid += "friction = { linspace = [0.05, 0.15, 3] }\nload = [0.0, 1.0]\nelements = 12\n"
    spec = read_sweep_file(write(tmp_path, grid))
    assert spec.design.size == 6


@pytest.mark.parametrize(
    "edit, message",
    [
        (("friction = {", "frction = {"), "unknown parameter name(s) ['frction']"),
        (("[0.1, 0.3]", "[0.1, 0.0]"), "friction: Relative: fraction must be > 0"),
        (("[1.5, 4.5]", "[4.5, 4.5]"), "route_angle: Uniform: empty range"),
        (("{ seed = true }", "{ triangular = [0, 1] }"), "unknown distribution 'triangular'"),
        (
            ('function = "reference.stand_in_study:compensator_study"', 'scenario = "nope"'),
            "unknown scenario 'nope'",
        ),
        (('design = "lhs"', 'design = "sobol"'), "design must be one of"),
        (("n = 6", "n = 0"), "n must be a positive integer"),
        (("seed = 3", "seeed = 3"), "unknown [sweep] key(s) ['seeed']"),
        (("[report]", "[reprot]"), "unknown section(s) ['reprot']"),
    ],
)
def test_bad_files_fail_with_one_line_before_any_run(tmp_path, edit, message):
    cfg = write(tmp_path, TOML.replace(*edit))
    result = runner.invoke(app, ["sweep", str(cfg), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert message in " ".join(result.output.split()), result.output
    assert not (tmp_path / "o").exists()


def test_unreachable_scheduler(tmp_path):
    cfg = write(tmp_path, TOML)
    result = runner.invoke(
        app, ["sweep", str(cfg), "--out", str(tmp_path / "o"), "--scheduler", "tcp://127.0.0.1:1"]
    )
    assert result.exit_code == 2
    assert "cannot reach the Dask scheduler at tcp://127.0.0.1:1" in result.output
    assert not (tmp_path / "o").exists()


def test_missing_file(tmp_path):
    result = runner.invoke(app, ["sweep", str(tmp_path / "none.toml")])
    assert result.exit_code == 2 and "no such file" in result.output
