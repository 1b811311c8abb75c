"""The built-in scenarios at reduced length: the rankings and the seed-level factors."""

import math

import numpy as np


def test_do2015_ranking_and_factors(scenario_results):
    r = scenario_results["do2015"]
    mse = {k: v.metrics["mse"] for k, v in r.runs.items()}  # with random route changes
    assert mse["AdaptiveController"] < mse["InverseFeedforward"] < mse["none"]
    assert mse["none"] / mse["AdaptiveController"] >= 190  # Do et al.: 0.0158 -> 8.28e-5
    fixed = {k: v["mse"] for k, v in r.extra["fixed_route"].items()}
    assert fixed["none"] / fixed["InverseFeedforward"] >= 13  # Do et al.: 0.0158 -> 0.0012
    assert fixed["none"] / fixed["AdaptiveController"] >= 190
    assert len(r.route_schedule) >= 2  # the route did change during the run
    assert all(row["paper_mse"] > 0 for row in r.table)


def test_sun2015_curve_angle_feedforward_follows_the_route(scenario_results):
    r = scenario_results["sun2015"]
    rmse = {k: v.metrics["rmse"] for k, v in r.runs.items()}
    assert rmse["CurveAngleFeedforward"] < rmse["fixed feedforward"] < rmse["none"]
    per = r.extra["per_condition"]
    assert len(per) == 15  # five curve angles x three loads
    for condition, m in per.items():
        assert m["CurveAngleFeedforward"]["rmse"] <= m["none"]["rmse"] * 1.01, condition
        assert m["CurveAngleFeedforward"]["rmse"] <= m["fixed feedforward"]["rmse"] * 1.01, (
            condition
        )


def test_lau2015_exact_feedforward_meets_the_papers_claim(scenario_results):
    r = scenario_results["lau2015"]
    exact = r.runs["ContinuumFeedforward (exact)"].metrics
    assert exact["percent_error"] < 5.0
    assert exact["percent_error"] < r.runs["none"].metrics["percent_error"]
    span = np.ptp(r.runs["none"].reference)
    assert math.isclose(span, math.pi, rel_tol=1e-3)  # +/-90 deg
    fr = r.frequency["none"]
    assert fr.frequencies.min() <= 0.05 + 1e-9 and fr.frequencies.max() >= 2.0 - 1e-9
    assert 0.3 < fr.bandwidth_3db < 2.0  # the 1.2 Hz motor lag sets the roll-off
    assert fr.gain_db[-1] < -3.0
