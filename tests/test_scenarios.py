"""The built-in scenarios at reduced length: the rankings and the seed-level factors."""

import math

import numpy as np


def test_do2015_ranking_and_factors(scenario_results):
    # Realistic plant (tendonsheath.presets) and bench.calibrate (calibration route, not a
    # test route). Measured at scale 0.25, seed 0: random routes feedforward 5.6x, adaptive
    # 6.1x; nominal route feedforward 8.4x, adaptive 4.0x. Do et al.'s 13x (feedforward) and
    # 190x (adaptive) are NOT reached, and their ranking (adaptive far ahead) is not either:
    # motor Coulomb friction and gear play hurt the torque-driven loop most.
    r = scenario_results["do2015"]
    mse = {k: v.metrics["mse"] for k, v in r.runs.items()}  # with random route changes
    assert mse["none"] / mse["InverseFeedforward"] >= 4.5
    assert mse["none"] / mse["AdaptiveController"] >= 4.5
    fixed = {k: v["mse"] for k, v in r.extra["fixed_route"].items()}
    assert fixed["none"] / fixed["InverseFeedforward"] >= 7
    assert fixed["none"] / fixed["AdaptiveController"] >= 3.3
    assert len(r.route_schedule) >= 2  # the route did change during the run
    assert set(r.honesty) == set(r.runs)  # every compensator has its honesty panel row


def test_sun2015_curve_angle_feedforward_follows_the_route(scenario_results):
    r = scenario_results["sun2015"]
    rmse = {k: v.metrics["rmse"] for k, v in r.runs.items()}
    assert rmse["CurveAngleFeedforward"] < rmse["fixed feedforward"] < rmse["none"]
    per = r.extra["per_condition"]
    assert len(per) == 15  # five curve angles x three loads
    # measured (scale 0.25): curve-angle feedforward / none at most 0.95 (Theta = 0, no
    # load), 0.27-0.40 elsewhere; against the fixed feedforward it is better everywhere but
    # near the fixed one's calibration angle (1.15 pi) without load (1.08x at pi/2, 1.35x at
    # pi): the seed's "always better" ranking holds on average only (measured mean 0.58x)
    for condition, m in per.items():
        assert m["CurveAngleFeedforward"]["rmse"] <= m["none"]["rmse"], condition
    mean = r.extra["mean_rmse_over_conditions"]
    assert mean["CurveAngleFeedforward"] < 0.8 * mean["fixed feedforward"]


def test_sun2015_curve_angle_feedforward_within_2x_of_a_local_calibration(scenario_results):
    """Sun et al.'s claim: at curve angles it was not calibrated at, the curve-angle
    feedforward (told the sensed angle, with noise and delay) does about as well as a
    feedforward calibrated at that very angle. Target: within 2x at every test angle."""
    local = scenario_results["sun2015"].extra["local_reference"]
    ratios = {k: v["ratio"] for k, v in local["angles"].items()}
    assert len(ratios) == 5
    # measured (scale 0.25, seed 0): 1.47 at 0 pi (no friction to follow there, the residual
    # is the drive's own), 0.99-1.07 elsewhere; the 2x target holds with a 1.36x margin
    assert max(ratios.values()) <= 2.0, ratios
    assert local["met"]


def test_lau2015_exact_feedforward_meets_the_papers_claim(scenario_results):
    r = scenario_results["lau2015"]
    exact = r.runs["ContinuumFeedforward (exact)"].metrics
    # measured (scale 0.25, realistic plant, bench.calibrate at 0.4/0.75/1.4 pi): exact 12.6 %,
    # published 9.5 %, none 15.0 %. Lau et al.'s < 5 % is NOT reached.
    assert exact["percent_error"] < 0.95 * r.runs["none"].metrics["percent_error"]
    span = np.ptp(r.runs["none"].reference)
    assert math.isclose(span, math.pi, rel_tol=1e-3)  # +/-90 deg
    fr = r.frequency["none"]
    assert fr.frequencies.min() <= 0.05 + 1e-9 and fr.frequencies.max() >= 2.0 - 1e-9
    # measured (scale 0.25): the uncompensated realistic drive already loses 3.4 dB at
    # 0.05 Hz (its -3 dB "bandwidth" is the lowest frequency), -12.4 dB at 2 Hz; the exact
    # feedforward's -3 dB bandwidth is 0.38 Hz: the paper's 0.8 Hz is NOT reached
    assert fr.gain_db[-1] < fr.gain_db[0] - 6.0  # the 1.2 Hz motor lag sets the roll-off
    assert 0.3 < r.frequency["ContinuumFeedforward (exact)"].bandwidth_3db < 2.0


def test_paper_target_verdicts_follow_the_measured_figures(scenario_results):
    """Each scenario's targets are computed from its own runs, and the verdict from the figure."""
    do = scenario_results["do2015"]
    mse = {k: v.metrics["mse"] for k, v in do.runs.items()}
    factors = {t["claim"].split()[0]: t for t in do.targets}
    for name, bound in (("InverseFeedforward", 13), ("AdaptiveController", 190)):
        assert factors[name]["measured"] == mse["none"] / mse[name]
        assert factors[name]["met"] == (factors[name]["measured"] >= bound)
    (sun,) = scenario_results["sun2015"].targets
    assert sun["measured"] == scenario_results["sun2015"].extra["local_reference"]["worst_ratio"]
    lau = scenario_results["lau2015"]
    for t in lau.targets:
        name = t["claim"].split(" mean error")[0]
        assert t["measured"] == lau.runs[name].metrics["percent_error"]
        assert t["met"] == (t["measured"] < 5.0)
