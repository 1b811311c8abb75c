"""SweepResult: sensitivity against known answers, files and figures."""

import json

import numpy as np
import pandas as pd
import pytest

import tendonsheath as ts
from tendonsheath.sweep import Choice, LatinHypercube, Normal, Saltelli, Seed, Uniform


def linear(params):
    """y = 3 a - b (+ 0 c); z = a; per "compensator" A and B (B doubles y)."""
    y = 3 * params["a"] - params["b"]
    return {"A": {"y": y, "z": params["a"]}, "B": {"y": 2 * y, "z": params["a"]}}


def additive(params):
    return {"y": params["a"] + 2 * params["b"]}


def test_src_ranks_a_known_linear_model():
    spec = {"a": Uniform(0, 1), "b": Uniform(0, 1), "c": Normal(0, 1), "s": Seed(), "k": 1}
    res = ts.sweep(linear, LatinHypercube(spec), n=200, seed=4, engine="serial")
    sens = res.sensitivity(metrics="y")
    assert set(sens["parameter"]) == {"a", "b", "c"}  # a seed is not ranked
    for comp in ("A", "B"):
        s = sens[sens["compensator"] == comp].set_index("parameter")
        assert s.loc["a", "rank"] == 1 and s.loc["b", "rank"] == 2
        # exact linear model: SRC = coefficient * std(x) / std(y), about 3 and -1 / sqrt(10)
        t = res.table[res.table["compensator"] == comp]
        sy = t["y"].std() / (1 if comp == "A" else 2)  # B doubles y
        assert s.loc["a", "coefficient"] == pytest.approx(3 * t["a"].std() / sy, abs=1e-9)
        assert s.loc["b", "coefficient"] == pytest.approx(-t["b"].std() / sy, abs=1e-9)
        assert s.loc["a", "coefficient"] == pytest.approx(3 / np.sqrt(10), abs=0.05)
        assert abs(s.loc["c", "coefficient"]) < 0.01 and s.loc["a", "r2"] == pytest.approx(1.0)
    srrc = res.sensitivity(method="srrc", metrics="y")
    assert srrc.iloc[0]["parameter"] == "a"


def test_sobol_indices_of_an_additive_model():
    res = ts.sweep(additive, Saltelli({"a": Uniform(0, 1), "b": Uniform(0, 1)}), n=512, seed=2,
                   engine="serial")  # fmt: skip
    sens = res.sensitivity().set_index("parameter")
    assert (sens["method"] == "sobol").all()
    # Var(a) : Var(2 b) = 1 : 4, additive: S1 = ST
    assert sens.loc["b", "S1"] == pytest.approx(0.8, abs=0.05)
    assert sens.loc["a", "ST"] == pytest.approx(0.2, abs=0.05)
    assert sens.loc["b", "rank"] == 1
    with pytest.raises(ValueError, match="Saltelli"):
        ts.sweep(additive, {"a": Uniform(0, 1), "b": Uniform(0, 1)}, n=8, seed=1,
                 engine="serial").sensitivity(method="sobol")  # fmt: skip


def test_save_writes_tables_summary_and_figures(tmp_path):
    spec = {"a": Uniform(0, 1), "b": Uniform(1, 2), "tag": Choice(["p", "q"])}
    res = ts.sweep(linear, spec, n=30, seed=1, engine="serial")
    written = res.save(tmp_path, bound={"y": 1.0})
    names = {p.name for p in written}
    assert {"table.csv", "table.parquet", "summary.csv", "summary.json"} <= names
    assert {"hist_y.png", "y_vs_parameters.png", "sensitivity.png"} <= names
    for p in written:
        if p.suffix == ".png":
            assert p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    back = pd.read_parquet(tmp_path / "table.parquet")
    pd.testing.assert_frame_equal(back, res.table)
    pd.testing.assert_frame_equal(pd.read_csv(tmp_path / "table.csv"), res.table)
    meta = json.loads((tmp_path / "summary.json").read_text())
    assert meta["seed"] == 1 and meta["compensators"] == ["A", "B"]
    rows = {(r["compensator"], r["metric"]): r for r in meta["summary"]}
    y = res.table[res.table["compensator"] == "A"]["y"]
    assert rows["A", "y"]["within_bound"] == pytest.approx(float(np.mean(y <= 1.0)))
    assert rows["A", "y"]["median"] == pytest.approx(float(y.median()))
    with pytest.raises(ValueError, match="unknown metric"):
        res.summary(bound={"nope": 1.0})


def test_robustness_study_for_the_report(tmp_path, monkeypatch):
    from reference.stand_in_study import compensator_study
    from tendonsheath.sweep import robustness_section, robustness_study
    from tendonsheath.sweep.studies import robustness_design

    design = robustness_design(elements=12, samples=150)
    res = robustness_study(compensator_study, n=10, seed=1, engine="serial", design=design)
    assert res.n_runs == 10 and res.compensators == ["none", "curve_angle", "inverse_backlash"]
    f = res.table["friction"]
    assert f.between(0.07, 0.13).all() and res.table["route_pieces"].between(1, 4).all()
    section = robustness_section(res, tmp_path, bound=1e-4)
    assert set(section["compensators"]) == set(res.compensators)
    # the section's numbers against the table, computed here from the runs
    for comp, numbers in section["compensators"].items():
        mse = res.table.loc[res.table["compensator"] == comp, "mse"].to_numpy()
        assert len(mse) == 10
        assert numbers["q05"] == pytest.approx(np.quantile(mse, 0.05), rel=1e-12)
        assert numbers["median"] == pytest.approx(np.median(mse), rel=1e-12)
        assert numbers["q95"] == pytest.approx(np.quantile(mse, 0.95), rel=1e-12)
        assert numbers["max"] == pytest.approx(mse.max(), rel=1e-12)
        assert numbers["within_bound"] == np.count_nonzero(mse <= 1e-4) / 10
    assert (tmp_path / "robustness_mse.png").read_bytes()[:4] == b"\x89PNG"
    json.dumps(section)
    # in a report in degrees the figure's axis and bound are in deg^2, the numbers in rad^2
    from tendonsheath.sweep import studies

    drawn = []
    monkeypatch.setattr(studies, "save_figure", lambda fig, path, **kw: drawn.append(fig))
    in_deg = robustness_section(res, tmp_path, bound=1e-4, angle_unit="deg")
    assert in_deg["compensators"] == section["compensators"]
    ax = drawn[0].axes[0]
    assert ax.get_ylabel() == "mse [deg^2]"
    bound_line = [ln for ln in ax.lines if ln.get_label().startswith("bound")][0]
    assert bound_line.get_ydata()[0] == pytest.approx(1e-4 * (180 / np.pi) ** 2, rel=1e-12)
