"""compare_models for Step 9: cross-validation, no refit on the same data, the CLI's
--validate with several files, messages (issue 18 items 3-5, issue 12 item 5)."""

import numpy as np
import pytest
from _realdata_helpers import plant_log
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath import io
from tendonsheath.apps import compare
from tendonsheath.apps.cli import app
from tendonsheath.identify import Identifier
from tendonsheath.identify.data import make_recordings

FAST = {"maxiter": 10, "popsize": 8}


def test_held_out_logs_reuse_the_winners_fit(monkeypatch):
    """Issue 18 item 3: with held-out logs the winner was refitted on exactly the data it
    had been fitted on (one more fit of the slowest candidate, same answer)."""
    calls = []
    real = Identifier.fit_data

    def counting(self, *args, **kwargs):
        calls.append(compare.model_name(self.model))
        return real(self, *args, **kwargs)

    monkeypatch.setattr(Identifier, "fit_data", counting)
    t, x, y = plant_log(n=300)
    t2, x2, y2 = plant_log(n=300, amplitude=0.6)
    cmp = ts.compare_models(
        [(t, x, y)], models=["backlash", "bwb"], validate=[(t2, x2, y2)], **FAST
    )
    assert sorted(calls) == ["Backlash", "BoucWenBacklash"]  # one fit each, no refit
    assert cmp.winner is cmp.fits[cmp.winner_name].model


def test_cross_validation_scores_every_sample_once():
    t, x, y = plant_log(n=360)
    cmp = ts.compare_models([(t, x, y)], models=["backlash"], **FAST)
    assert cmp.mode.startswith("cross-validation: 3 contiguous blocks")
    # every sample from the input's first reversal on (before it the state is unknown)
    assert sum(v["y"].size for v in cmp.validation) == t.size - compare._settle(x)
    assert len(cmp.fits["Backlash"]) == 3  # one fit per fold
    assert cmp.winner_fit is not None and cmp.winner_fit.n_samples == t.size  # all the data
    row = cmp.row("Backlash")
    assert row["seconds"] > 0 and row["ratio_to_affine"] < 1.0
    # several recordings: leave one recording out
    logs = [plant_log(n=200, amplitude=a) for a in (0.5, 0.7, 0.9)]
    cmp = ts.compare_models(logs, models=["backlash"], **FAST)
    folds = "cross-validation: leave one recording out (3 folds)"
    assert cmp.mode == f"{folds}; {compare.SETTLE_NOTE}"
    assert [v["y"].size for v in cmp.validation] == [200 - compare._settle(r[1]) for r in logs]
    with pytest.raises(ValueError, match="too few for 3 folds"):
        ts.compare_models([plant_log(n=50)], models=["backlash"], **FAST)
    with pytest.raises(ValueError, match="validate: 'cv'"):
        ts.compare_models(logs, models=["backlash"], validate="kfold", **FAST)


def test_unknown_model_lists_only_candidates():
    with pytest.raises(ValueError, match="unknown model") as err:
        compare.parse_model("nope")
    text = str(err.value)
    assert "BoucWenBacklash" in text and "GeneralizedPrandtlIshlinskii" in text
    for wrong in ("AngleDependent", "Chain", "Polynomial", "Inverse", "HysteresisModel"):
        assert wrong not in text
    with pytest.raises(ValueError, match="unknown model 'Polynomial'"):
        compare.parse_model("Polynomial")


def _csv(path, t, x, y):
    io.write_csv(path, {"time": t, "motor": x, "tip": y})
    return str(path)


COLS = ["--time", "time", "--input", "motor", "--output", "tip", "--maxiter", "5"]


def test_cli_validate_takes_every_file_after_it(tmp_path):
    """Issue 18 item 4: `--validate A B` trained on B silently; now both are held out."""
    train = _csv(tmp_path / "train.csv", *plant_log(n=200))
    a = _csv(tmp_path / "a.csv", *plant_log(n=200, amplitude=0.6))
    b = _csv(tmp_path / "b.csv", *plant_log(n=200, amplitude=0.7))
    runner = CliRunner()
    res = runner.invoke(app, ["compare", train, *COLS, "--models", "backlash", "--validate", a, b])
    assert res.exit_code == 0, res.output
    assert "2 validation recording(s)" in res.output
    # the training file after the held-out ones would be held out too: no training file
    res = runner.invoke(app, ["compare", *COLS, "--validate", a, train])
    assert res.exit_code == 2 and "Missing argument" in res.output
    res = runner.invoke(app, ["compare", train, *COLS, "--holdout", "0.3", "--validate", a])
    assert res.exit_code == 2 and "exclude each other" in res.output


def test_cli_prints_data_notes_before_fitting_with_the_flag(tmp_path):
    """Issue 18 item 5: the notes came after all the fitting and advised `resample=`."""
    t, x, y = plant_log(n=300)
    t = t + 0.002 * np.sin(np.arange(t.size))  # irregular sampling
    path = _csv(tmp_path / "irregular.csv", t, x, y)
    res = CliRunner().invoke(app, ["compare", path, *COLS, "--models", "backlash"])
    assert res.exit_code == 0, res.output
    out = " ".join(res.output.split())
    assert "irregular sampling" in out and "--resample RATE (Hz)" in out
    assert "resample=" not in out
    assert out.index("irregular sampling") < out.index("fitted Backlash")


def test_blocked_folds_fit_after_the_block_from_its_start():
    """The part after a held-out block is simulated from the block's start (its input is
    known) and counted only after it: no held-out output enters a fit."""
    t, x, y = plant_log(n=300)
    rec = make_recordings(t, x, y)
    splits, _ = compare._folds(rec, 3)
    train, [(_, a, b)] = splits[1]
    assert [(r.n, r.skip) for r in train] == [(a, 0), (300 - a, b - a)]
    y_bad = y.copy()
    y_bad[a:b] = 1e3  # a wild held-out block changes nothing in the fit
    bad = make_recordings(t, x, y_bad)
    train_bad, _ = compare._folds(bad, 3)[0][1]
    opts = {"maxiter": 10, "popsize": 8, "progress": False}
    m1 = ts.identify(ts.models.Backlash, recordings=train, **opts).model
    m2 = ts.identify(ts.models.Backlash, recordings=train_bad, **opts).model
    assert m1 == m2
