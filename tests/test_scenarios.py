"""The built-in scenarios at reduced length: the rankings and the seed-level factors."""

import math

import numpy as np


def test_do2015_ranking_and_factors(scenario_results):
    r = scenario_results["do2015"]
    # Measured at scale 0.25, seed 0. With random route changes: MSE none 6.60e-3,
    # InverseFeedforward 2.68e-5, AdaptiveController 2.20e-5 (the ranking's narrowest gap:
    # 1.22x between the two compensators).
    mse = {k: v.metrics["mse"] for k, v in r.runs.items()}  # with random route changes
    assert mse["AdaptiveController"] < mse["InverseFeedforward"] < mse["none"]
    # Do et al.: 0.0158 -> 8.28e-5 (190x); measured 300x, 1.6x above the paper's factor
    assert mse["none"] / mse["AdaptiveController"] >= 190
    fixed = {k: v["mse"] for k, v in r.extra["fixed_route"].items()}
    # Do et al.: 0.0158 -> 0.0012 (13x); measured 239x, 18x above
    assert fixed["none"] / fixed["InverseFeedforward"] >= 13
    # Do et al.: 190x; measured 662x, 3.5x above
    assert fixed["none"] / fixed["AdaptiveController"] >= 190
    assert len(r.route_schedule) >= 2  # the route did change during the run


def test_sun2015_curve_angle_feedforward_follows_the_route(scenario_results):
    r = scenario_results["sun2015"]
    rmse = {k: v.metrics["rmse"] for k, v in r.runs.items()}
    assert rmse["CurveAngleFeedforward"] < rmse["fixed feedforward"] < rmse["none"]
    per = r.extra["per_condition"]
    assert len(per) == 15  # five curve angles x three loads
    # Measured worst ratios over the 15 conditions: CurveAngleFeedforward / none 1.000 (at
    # Theta = 0 with no load both sit at the sensor floor, 5.72e-3 rad, and are equal) and
    # CurveAngleFeedforward / fixed 0.994 (at pi, where the fixed inverse was calibrated);
    # the 1 % allows for that tie, not for a loss.
    for condition, m in per.items():
        assert m["CurveAngleFeedforward"]["rmse"] <= m["none"]["rmse"] * 1.01, condition
        assert m["CurveAngleFeedforward"]["rmse"] <= m["fixed feedforward"]["rmse"] * 1.01, (
            condition
        )


def test_lau2015_exact_feedforward_meets_the_papers_claim(scenario_results):
    r = scenario_results["lau2015"]
    exact = r.runs["ContinuumFeedforward (exact)"].metrics
    # Lau et al. claim under 5 %; measured 2.04 % (2.5x below). The uncompensated run also
    # stays under 5 % here (3.53 %), so the claim alone does not show the compensation works:
    # the comparison with none does (2.04 % vs 3.53 %, 1.7x).
    assert exact["percent_error"] < 5.0
    assert exact["percent_error"] < r.runs["none"].metrics["percent_error"]
    span = np.ptp(r.runs["none"].reference)
    assert math.isclose(span, math.pi, rel_tol=1e-3)  # +/-90 deg
    fr = r.frequency["none"]
    assert fr.frequencies.min() <= 0.05 + 1e-9 and fr.frequencies.max() >= 2.0 - 1e-9
    assert 0.3 < fr.bandwidth_3db < 2.0  # the 1.2 Hz motor lag sets the roll-off; measured 0.94
    assert fr.gain_db[-1] < -3.0  # measured -10.2 dB at 2 Hz
