"""The report opens with a summary that names every missed claim and every loop that
oscillated or saturated."""

from types import SimpleNamespace

from test_limit_cycle import _adaptive_run

from tendonsheath.bench.scenarios.common import target
from tendonsheath.report.summary import executive_summary


def _result(runs, targets):
    return SimpleNamespace(name="do2015", runs=runs, targets=targets)


def test_the_summary_names_missed_claims_and_chattering_loops_only():
    calm, chattering = _adaptive_run(4.0), _adaptive_run(8.0)
    targets = [
        target("TipLoop reduction", ">= 500x", 581.0, True, "x"),
        target("AdaptiveController reduction", ">= 500x", 94.0, False, "x", "saturated"),
    ]
    text = executive_summary([_result({"calm": calm, "chattering": chattering}, targets)])
    assert "1 of 2 paper claims met" in text
    assert (
        "Not met: do2015: AdaptiveController reduction: 94 x (target &gt;= 500x); saturated" in text
    )
    assert "TipLoop reduction" not in text
    assert "do2015, chattering: limit cycle near" in text
    assert "do2015, calm" not in text
    assert "No shown run had" not in text


def test_a_clean_report_says_so_and_a_robustness_limit_cycle_is_named():
    calm = _adaptive_run(4.0)
    clean = executive_summary([_result({"calm": calm}, [target("c", ">= 1x", 2.0, True, "x")])])
    assert "1 of 1 paper claims met" in clean and "No shown run had" in clean
    study = (
        "robustness",
        "Robustness",
        "",
        {
            "runs": 200,
            "compensators": {
                "AdaptiveController": {"limit_cycle_share": 1.0},
                "none": {"limit_cycle_share": 0.0},
            },
        },
    )
    text = executive_summary([_result({"calm": calm}, [])], [study])
    assert "robustness, AdaptiveController: a limit cycle in 100 % of 200 perturbed plants" in text
    assert "robustness, none" not in text
