"""compare_models' parsimony rule and per-part errors (issue 17 item 7): a candidate with more
parameters wins only by a stated margin; each candidate's held-out error per held-out part,
over the affine map's, in Python (Comparison.parts) and on the command line."""

import json
import re

import numpy as np
import pytest
from _realdata_helpers import plant_log
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath import io
from tendonsheath._util import parsimony as _parsimony
from tendonsheath.apps import compare
from tendonsheath.apps.cli import app

FAST = {"maxiter": 10, "popsize": 8}


def rows(*specs):
    """Table rows as compare_models sorts them: (model, n_params, val_nrmse), all eligible."""
    out = [
        {"model": m, "n_params": n, "val_nrmse": e, "inv_nrmse": e, "eligible": True}
        for m, n, e in specs
    ]
    return sorted(out, key=lambda r: r["val_nrmse"])


def test_a_bigger_model_1_percent_better_loses_to_the_smaller_one():
    table = rows(("affine", 2, 0.50), ("Small", 4, 0.101), ("Big", 9, 0.100))
    index, why = _parsimony.choose(table, "prediction", 0.05)
    assert table[index]["model"] == "Small"
    assert why == (
        "Small wins: its held-out error is within 1.0 % of Big's with 4 parameters instead "
        "of 9 (parsimony 5 %)"
    )
    # the plain ranking (parsimony 0) keeps the lowest error, and says what would choose Small
    index, why = _parsimony.choose(table, "prediction", 0.0)
    assert table[index]["model"] == "Big"
    assert "Small has 4 parameters instead of 9 and is within 1.0 % of it" in why
    # the parsimony the hint names does choose Small
    named = float(re.search(r"a parsimony of (\d+) % would choose it", why).group(1)) / 100
    assert 0.01 <= named <= 0.02
    assert table[_parsimony.choose(table, "prediction", named)[0]]["model"] == "Small"
    # a parsimony just under the gap keeps Big, just over it chooses Small
    assert table[_parsimony.choose(table, "prediction", 0.0099)[0]]["model"] == "Big"
    assert table[_parsimony.choose(table, "prediction", 0.0101)[0]]["model"] == "Small"


def test_a_bigger_model_20_percent_better_wins():
    table = rows(("affine", 2, 0.50), ("Small", 4, 0.120), ("Big", 9, 0.100))
    index, why = _parsimony.choose(table, "prediction", 0.05)
    assert table[index]["model"] == "Big" and why == ""  # nothing smaller within 5 %


def test_the_fewest_parameters_within_the_margin_win_not_the_next_best():
    # three within 10 % of the best: the one with the fewest parameters wins, even if it is
    # not the second best; a tie in parameters goes to the lower error
    table = rows(("A", 12, 0.100), ("B", 9, 0.102), ("C", 4, 0.108), ("D", 4, 0.105))
    table.append({"model": "E", "n_params": 2, "val_nrmse": 0.101, "eligible": False})
    assert table[_parsimony.choose(table, "prediction", 0.1)[0]]["model"] == "D"
    # the objective's error ranks: by the inverse error, here equal to the forward one
    assert table[_parsimony.choose(table, "compensation", 0.1)[0]]["model"] == "D"


def test_random_tables_obey_the_rule():
    """Invariant over random tables: the winner is eligible, within (1 + p) of the best, and
    no eligible candidate within that margin has fewer parameters."""
    rng = np.random.default_rng(5)
    for _ in range(300):
        n = int(rng.integers(1, 8))
        specs = [
            (f"m{i}", int(rng.integers(2, 15)), float(rng.uniform(0.05, 0.2))) for i in range(n)
        ]
        table = rows(*specs)
        for r in table:
            r["eligible"] = bool(rng.random() < 0.8)
        table.sort(key=lambda r: (not r["eligible"], r["val_nrmse"]))
        p = float(rng.uniform(0, 0.3))
        w = table[_parsimony.choose(table, "prediction", p)[0]]
        ok = [r for r in table if r["eligible"]]
        if not ok:
            continue
        best = min(r["val_nrmse"] for r in ok)
        assert w["eligible"] and w["val_nrmse"] <= (1 + p) * best
        assert all(r["n_params"] >= w["n_params"] for r in ok if r["val_nrmse"] <= (1 + p) * best)


def test_bad_parsimony_is_refused():
    t, x, y = plant_log(n=100)
    for bad in (-0.1, float("nan"), "5%", True):
        with pytest.raises(ValueError, match="parsimony must be a number >= 0"):
            ts.compare_models([(t, x, y)], models=["backlash"], validate=0.3, parsimony=bad)


@pytest.fixture(scope="module")
def linear_pair():
    """Two recordings of a straight line with a ripple: Backlash is worse than the affine
    map on both held-out parts (measured ratios 1.97 and 1.84)."""
    t = np.linspace(0, 4, 200)
    logs = [(t, a * np.sin(t), 2.0 * a * np.sin(t) + 0.3 + 1e-3 * np.cos(17 * t)) for a in (1, 0.7)]
    return logs, ts.compare_models(logs, models=["backlash"], validate=0.4, **FAST)


def test_parts_give_each_held_out_part_against_the_affine_map(linear_pair):
    logs, cmp = linear_pair
    parts = cmp.parts()
    assert parts["models"] == ["affine", "Backlash"]
    assert parts["rmse"].shape == parts["ratio_to_affine"].shape == (2, 2)
    # the affine map's per-part rmse computed here: least squares on the first 60 % of both
    # recordings in time, scored on the last 40 % of each
    cut = [int(np.searchsorted(t, 0.6 * t[-1])) for t, _, _ in logs]
    x = np.concatenate([lx[:k] for (_, lx, _), k in zip(logs, cut, strict=True)])
    y = np.concatenate([ly[:k] for (_, _, ly), k in zip(logs, cut, strict=True)])
    b, a = np.linalg.lstsq(np.column_stack([np.ones_like(x), x]), y, rcond=None)[0]
    expected = [
        np.sqrt(np.mean((a * lx[k:] + b - ly[k:]) ** 2))
        for (_, lx, ly), k in zip(logs, cut, strict=True)
    ]
    np.testing.assert_allclose(parts["rmse"][0], expected, rtol=1e-9)
    np.testing.assert_allclose(parts["ratio_to_affine"][0], [1.0, 1.0])
    np.testing.assert_allclose(
        parts["ratio_to_affine"][1], parts["rmse"][1] / parts["rmse"][0], rtol=1e-12
    )
    np.testing.assert_allclose(parts["rmse"][1], cmp.row("Backlash")["val_rmse_parts"])
    # Backlash is worse on both parts: marked, and it cannot win
    assert parts["worse_than_affine"].tolist() == [[False, False], [True, True]]
    assert "Backlash" in cmp.excluded() and cmp.winner_name == "affine"
    text = "\n".join(cmp.parts_text())
    assert "parts: 1 = recording 1 [" in text and "*" in text
    assert cmp.to_dict()["part_labels"] == parts["labels"]


def test_parsimony_chooses_the_affine_map_over_a_model_within_the_margin():
    t, x, y = plant_log(n=300)
    plain = ts.compare_models([(t, x, y)], models=["backlash"], validate=0.4, **FAST)
    assert plain.winner_name == "Backlash" and plain.choice == ""  # measured ratio 0.74
    ratio = plain.row("Backlash")["ratio_to_affine"]
    lenient = ts.compare_models(
        [(t, x, y)], models=["backlash"], validate=0.4, parsimony=1.0 / ratio, **FAST
    )
    assert lenient.winner_name == "affine" and isinstance(lenient.winner, ts.models.Polynomial)
    assert lenient.choice.startswith("affine wins: its held-out error is within")
    assert "with 2 parameters instead of" in lenient.choice
    # the table stays sorted by error: the winner is not its first row
    assert lenient.table[0]["model"] == "Backlash"


def test_cli_prints_the_parts_and_the_parsimony_choice(tmp_path):
    t, x, y = plant_log(n=300)
    t2, x2, y2 = plant_log(n=300, amplitude=0.6)
    io.write_csv(tmp_path / "a.csv", {"time": t, "motor": x, "tip": y})
    io.write_csv(tmp_path / "b.csv", {"time": t2, "motor": x2, "tip": y2})
    args = ["compare", str(tmp_path / "a.csv"), str(tmp_path / "b.csv")]
    args += ["--time", "time", "--input", "motor", "--output", "tip", "--models", "backlash"]
    args += ["--holdout", "0.4", "--maxiter", "8", "--quiet"]
    runner = CliRunner()
    res = runner.invoke(app, [*args, "--parsimony", "100", "--report", str(tmp_path / "r")])
    assert res.exit_code == 0, res.output
    assert "part 1" in res.output and "part 2" in res.output
    assert "parts: 1 = a.csv [" in res.output and "2 = b.csv [" in res.output
    assert "winner: affine" in res.output and "affine wins: its held-out error is within" in (
        " ".join(res.output.split())
    )
    data = json.loads((tmp_path / "r" / "comparison.json").read_text())
    assert data["parsimony"] == 100 and data["winner"] == "affine"
    # --report: the page has the parts table too, and comparison.json its figures
    page = (tmp_path / "r" / "report.html").read_text()
    assert "<figcaption>Held-out rmse of each candidate on each held-out part" in page
    assert "1 = a.csv [" in page and data["parts"]["labels"][1].startswith("b.csv [")
    bad = runner.invoke(app, [*args, "--parsimony", "-1"])
    assert bad.exit_code == 2 and "--parsimony must be a number >= 0" in bad.output


def test_a_ratio_that_rounds_to_one_shows_which_side_of_one_it_is_on():
    assert compare._ratio_cell(1.0002, True) == "1.00020*"
    assert compare._ratio_cell(0.9998, False) == "0.99980"
    assert compare._ratio_cell(1.0, False) == "1.000"
    assert compare._ratio_cell(1.25, True) == "1.250*"
    assert compare._ratio_cell(float("nan"), False) == "-"


def test_cli_parts_past_twelve_show_each_candidates_best_and_worst(capsys):
    from tendonsheath.apps import cli

    k = cli.MAX_PART_COLUMNS + 1
    ratios = np.array([np.ones(k), np.linspace(0.5, 1.1, k)])

    class Result:  # what _print_parts reads of a Comparison
        def parts(self):
            return {
                "labels": [f"run{j}.csv" for j in range(k)],
                "models": ["affine", "Backlash"],
                "ratio_to_affine": ratios,
                "worse_than_affine": ratios > 1,
            }

    cli._print_parts(Result())
    out = capsys.readouterr().out
    assert "best part" in out and "worst part" in out and f"part {k}" not in out
    assert "0.500 (1)" in out and f"1.100* ({k})" in out
    assert f"{k} = run{k - 1}.csv" in out


def test_the_report_shows_the_parts_table_and_comparison_json_holds_it(linear_pair, tmp_path):
    """report.html carries the per-part table the CLI prints (issue 27 item 1): a row per
    candidate, a column per held-out part, each part's rmse over the affine map's there with
    a * where it is worse, and a caption naming the parts and the *; comparison.json holds
    the same figures."""
    from html.parser import HTMLParser

    _, cmp = linear_pair
    page = cmp.report(tmp_path / "r").read_text()

    class Tables(HTMLParser):  # the cells of each <table> and the caption below it, as text
        def __init__(self):
            super().__init__()
            self.tables, self.cell = [], None

        def handle_starttag(self, tag, attrs):
            if tag == "table":
                self.tables.append({"rows": [], "caption": ""})
            elif tag == "tr":
                self.tables[-1]["rows"].append([])
            elif tag in ("td", "th", "figcaption"):
                self.cell = tag

        def handle_endtag(self, tag):
            if tag in ("td", "th", "figcaption"):
                self.cell = None

        def handle_data(self, data):
            if self.cell == "figcaption":
                self.tables[-1]["caption"] += data
            elif self.cell:
                self.tables[-1]["rows"][-1].append(data)

    parser = Tables()
    parser.feed(page)
    assert len(parser.tables) == 2  # the candidates' table, then the parts'
    parts_table = parser.tables[1]
    head, *body = parts_table["rows"]
    assert head == ["model", "part 1", "part 2"]
    # the ratios computed here from the per-part rmse (Backlash's measured 1.97 and 1.84:
    # three decimals, marked worse; the affine map's own row is 1.000)
    rmse = cmp.parts()["rmse"]
    backlash = [f"{q:.3f}*" for q in rmse[1] / rmse[0]]
    assert body == [["affine", "1.000", "1.000"], ["Backlash", *backlash]]
    labels = cmp.parts()["labels"]
    caption = " ".join(parts_table["caption"].split())
    assert f"1 = {labels[0]}, 2 = {labels[1]}" in caption
    assert "A part is one held-out recording, or one held-out block of a recording" in caption
    assert "*: worse than the affine map on that part (the candidate cannot win)" in caption
    data = json.loads((tmp_path / "r" / "comparison.json").read_text())
    assert data["parts"]["labels"] == labels and data["parts"]["models"] == ["affine", "Backlash"]
    np.testing.assert_allclose(data["parts"]["rmse"], rmse, rtol=1e-15)
    np.testing.assert_allclose(data["parts"]["ratio_to_affine"][1], rmse[1] / rmse[0], rtol=1e-12)
    assert data["parts"]["worse_than_affine"] == [[False, False], [True, True]]
    np.testing.assert_allclose(data["parts"]["inv_rmse"], cmp.parts()["inv_rmse"], rtol=1e-15)


def test_the_report_parts_table_marks_a_ratio_that_rounds_to_one():
    nan = float("nan")
    parts = {
        "labels": ["a.csv [0, 10)", "b.csv <x>"],
        "models": ["affine", "Backlash"],
        "rmse": np.array([[0.5, 0.5], [0.5001, 0.4999]]),
        "ratio_to_affine": np.array([[1.0, 1.0], [1.0002, 0.9998]]),
        "worse_than_affine": np.array([[False, False], [True, False]]),
        "inv_rmse": np.array([[0.5, 0.5], [nan, nan]]),
        "inv_ratio_to_affine": np.array([[1.0, 1.0], [nan, nan]]),
    }
    html = compare._parts_html(parts)
    assert "<td>1.00020*</td><td>0.99980</td>" in html
    assert "2 = b.csv &lt;x&gt;" in html  # a label is text, not markup
    one_part = {k: v[:1] if k == "labels" else v[:, :1] for k, v in parts.items() if k != "models"}
    assert compare._parts_html({**one_part, "models": parts["models"]}) == ""
    # comparison.json: a missing figure (no inverse) is null, as JSON has no NaN
    data = json.loads(json.dumps(compare._parts_json(parts), allow_nan=False))
    assert data["inv_rmse"] == [[0.5, 0.5], [None, None]]
    assert data["worse_than_affine"] == [[False, False], [True, False]]


def test_the_table_shows_each_candidates_spread_over_the_parts(linear_pair):
    _, cmp = linear_pair
    ratios = cmp.parts()["ratio_to_affine"][1]  # Backlash's, one per held-out part
    spread = cmp.fold_spread()
    assert spread["Backlash"] == f"{ratios.min():.2f}-{ratios.max():.2f}"
    assert spread["affine"] == "1.00-1.00"
    backlash_line = next(ln for ln in cmp.text().splitlines() if ln.startswith("Backlash "))
    assert spread["Backlash"] in backlash_line
