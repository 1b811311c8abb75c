"""The built-in scenarios at reduced length: the rankings and the seed-level factors.

Every figure below was measured at scale 0.25 (do2015 runs of 10 s, sun2015 of 6 s, lau2015 of
5 s; identification budget 40 x 10), seed 0; thresholds sit at least 15 % below (above for an
error) and say so. The full-length figures are in README.md (benchmarks/results/demo-metrics.json).
"""

import math

import numpy as np
import pytest


def _factors(r, servo):
    return r.extra["servo_summary"][servo]


def test_do2015_shape_aware_feedforward_beats_the_paper_on_both_servos(scenario_results):
    # measured, fixed route / random routes median (worst of 5 seeds):
    #   PID: shape-aware + EncoderLoop 240x / 141x (54.7x); shape-aware alone 317x / 188x (59.7x)
    #   PD:  shape-aware + EncoderLoop 459x / 252x (87.5x); shape-aware alone 105x / 96.8x (38.2x)
    #   InverseFeedforward of one calibration shape: 26.0x / 15.9x (4.6x) PID,
    #   27.9x / 13.1x (4.5x) PD
    r = scenario_results["do2015"]
    head = "shape-aware InverseFeedforward + EncoderLoop"
    for servo, (fixed, median, worst) in {"pid": (200, 120, 45), "pd": (390, 210, 74)}.items():
        s = _factors(r, servo)[head]
        assert s["factor_fixed"] >= fixed, servo
        assert s["factor_random"]["median"] >= median, servo
        assert s["factor_random"]["min"] >= worst, servo
        assert s["factor_random"]["seeds"] == 5
    # the shape is what pays under random routes: the one-shape feedforward stays near 5x worst
    for servo in ("pid", "pd"):
        one = _factors(r, servo)["InverseFeedforward"]["factor_random"]["min"]
        assert _factors(r, servo)[head]["factor_random"]["min"] > 8 * one
    # the encoder loop is what pays on the yielding PD servo (4.4x on the fixed route here)
    pd = _factors(r, "pd")
    assert pd[head]["factor_fixed"] > 3 * pd["shape-aware InverseFeedforward"]["factor_fixed"]
    assert len(r.route_schedule) >= 2  # the route did change during the headline run
    assert set(r.honesty) == set(r.runs)  # every compensator has its honesty panel row


def test_do2015_tip_sensor_controllers_are_designed_from_calibration(scenario_results):
    # measured (scale 0.25), TipLoop: 1 ms 3102x fixed, 2833x median (268x worst); 5 ms 178x
    # (70x); 0 ms 6936x (457x); AdaptiveController: 1 ms 124x (50.2x), 5 ms 33x, saturating
    r = scenario_results["do2015"]
    tip = r.extra["tip_sensor"]
    assert set(tip) == {"0 ms", "1 ms", "5 ms"}
    one, five = tip["1 ms"]["TipLoop"], tip["5 ms"]["TipLoop"]
    assert one["factor_fixed"] >= 2600
    assert one["factor_random"]["median"] >= 2400 and one["factor_random"]["min"] >= 220
    assert five["factor_random"]["median"] >= 150
    assert one["factor_random"]["seeds"] == 5
    # a longer latency costs: the loop is slower (the tuner read the delay)
    assert five["factor_random"]["median"] < one["factor_random"]["median"]
    assert five["design"]["ki"] < one["design"]["ki"]
    # every design says what it was designed from: the distal mode (42.5 Hz from the preset's
    # distal inertia and the tendons' stiffness) and the latency, both identified from logs
    for latency, controllers in tip.items():
        for name, d in controllers.items():
            assert all(40.0 < f < 46.0 for f in d["design"]["resonances_hz"]), (latency, name)
            ms = float(latency.removesuffix(" ms"))
            assert d["design"]["delays_s"] == pytest.approx([ms * 1e-3] * 3), (latency, name)
            assert "designed from resonance" in d["designed_from"]
    # the adaptive controller misses and the verdict says so; it saturated, and that is kept
    adaptive = tip["1 ms"]["AdaptiveController"]
    assert 60 < adaptive["factor_random"]["median"] < 190
    claims = {t["claim"]: t["met"] for t in r.targets}
    for claim, met in claims.items():
        if "(tip sensor, " in claim:
            assert met == claim.startswith("TipLoop"), claim
    # the tip sensor pays: against the best no-tip-sensor compensator on the same routes
    head = _factors(r, "pid")["shape-aware InverseFeedforward + EncoderLoop"]["factor_random"]
    assert one["factor_random"]["min"] > 3 * head["min"]
    assert {"TipLoop", "AdaptiveController"} <= set(r.runs) <= set(r.honesty)


def test_do2015_iterative_learning_reaches_1000x_and_holds_on_a_shifted_route(scenario_results):
    # measured (scale 0.25): 4440x after 10 trials, run without the sensor; on the shifted
    # route 13.8x against 5.37x for the feedforward alone
    r = scenario_results["do2015"]
    ilc = r.extra["ilc"]
    assert ilc["trials"] <= 10
    assert ilc["factor_learned_no_sensor"] >= 3000
    by_trial = ilc["factor_by_trial"]
    assert by_trial[0] < 100 and max(by_trial) > 1000  # learned, not given: trial 0 is the ff
    shifted = ilc["shifted_route_factor"]
    assert shifted["learned"] > 1.5 * shifted["InverseFeedforward"]
    assert "lead" in ilc["designed_from"] and ilc["design"]["rho"] < 1
    claims = [t for t in r.targets if t["claim"].startswith("ILC")]
    assert len(claims) == 2 and all(t["met"] for t in claims)


def test_sun2015_curve_angle_feedforward_follows_the_route(scenario_results):
    r = scenario_results["sun2015"]
    rmse = {k: v.metrics["rmse"] for k, v in r.runs.items()}
    # measured: route change run 0.0254 / 0.0413 / 0.121 rad (curve-angle / fixed / none)
    assert rmse["CurveAngleFeedforward"] < rmse["fixed feedforward"] < rmse["none"]
    per = r.extra["per_condition"]
    assert len(per) == 15  # five curve angles x three loads
    # measured: curve-angle feedforward / none at most 0.27 (Theta = 0, no load: the residual
    # is the drive's own), 0.02-0.06 elsewhere; mean rmse 0.0031 rad against the fixed
    # feedforward's 0.066
    for condition, m in per.items():
        assert m["CurveAngleFeedforward"]["rmse"] <= 0.35 * m["none"]["rmse"], condition
    mean = r.extra["mean_rmse_over_conditions"]
    assert mean["CurveAngleFeedforward"] < 0.1 * mean["fixed feedforward"]


def test_sun2015_curve_angle_feedforward_within_2x_of_a_local_calibration(scenario_results):
    """Sun et al.'s claim: at curve angles it was not calibrated at, the curve-angle
    feedforward (told the sensed angle, with noise and delay) does about as well as a
    feedforward calibrated at that very angle. Target: within 2x at every test angle, on
    both servos."""
    extra = scenario_results["sun2015"].extra
    for local in (extra["local_reference"], extra["pd_servo"]["local_reference"]):
        ratios = {k: v["ratio"] for k, v in local["angles"].items()}
        assert len(ratios) == 5
        # measured: 1.12-1.39 (PID), 0.97-1.23 (PD): the 2x target holds with a 1.4x margin
        assert max(ratios.values()) <= 1.65, ratios
        assert local["met"]


def test_lau2015_exact_feedforward_in_the_encoder_loop_beats_the_papers_claim(scenario_results):
    r = scenario_results["lau2015"]
    head = "ContinuumFeedforward (exact) + EncoderLoop"
    for servo, runs in r.extra["servo_runs"].items():
        # measured: 0.54 % mean (max 0.94 %) PID, 0.55 % (0.98 %) PD; uncompensated 4.7 % and
        # 15.0 %; the paper's < 5 % (8 % at the extremes), the issue's < 2 % (max < 5 %)
        assert runs[head]["percent_error"] < 0.7, servo
        assert runs[head]["max_percent_error"] < 1.2, servo
        assert runs[head]["percent_error"] < 0.15 * runs["none"]["percent_error"], servo
    span = np.ptp(r.runs["none"].reference)
    assert math.isclose(span, math.pi, rel_tol=1e-3)  # +/-90 deg
    fr = r.frequency["none"]
    assert fr.frequencies.min() <= 0.05 + 1e-9 and fr.frequencies.max() >= 2.0 - 1e-9
    # measured: the uncompensated drive behind the 1.2 Hz lag loses 0.46 dB at 0.05 Hz and
    # 12.1 dB at 2 Hz; the exact feedforward's -3 dB bandwidth is 0.85 Hz (paper 0.8 Hz)
    assert fr.gain_db[-1] < fr.gain_db[0] - 6.0  # the 1.2 Hz motor lag sets the roll-off
    assert 0.5 < r.frequency["ContinuumFeedforward (exact)"].bandwidth_3db < 2.0


def test_paper_target_verdicts_follow_the_measured_figures(scenario_results):
    """Each scenario's targets are computed from its own runs, and the verdict from the figure."""
    do = scenario_results["do2015"]
    head = "shape-aware InverseFeedforward + EncoderLoop"
    for t in do.targets:
        if "(tip sensor, " in t["claim"]:  # the tip-sensor study's own figures
            name, rest = t["claim"].split(" (tip sensor, ")
            f = do.extra["tip_sensor"][rest.split(" latency")[0]][name]["factor_random"]
            worst = "worst seed" in t["claim"]
            expected = f["min"] if worst else f["median"]
            bound = 190 if worst else (500 if "1 ms" in rest else 100)
            assert t["measured"] == expected and t["met"] == (expected >= bound), t["claim"]
            continue
        if t["claim"].startswith("ILC"):  # test_do2015_iterative_learning_... checks these
            continue
        servo = "pid" if "PID servo" in t["claim"] else "pd"
        s = _factors(do, servo)[head]
        if "fixed route" in t["claim"]:
            expected, bound = s["factor_fixed"], 30
        elif "worst seed" in t["claim"]:
            expected, bound = s["factor_random"]["min"], 13
        else:
            expected, bound = s["factor_random"]["median"], 30
        assert t["measured"] == expected and t["met"] == (expected >= bound), t["claim"]
    sun = scenario_results["sun2015"]
    pid, pd = sun.targets
    assert pid["measured"] == sun.extra["local_reference"]["worst_ratio"]
    assert pd["measured"] == sun.extra["pd_servo"]["local_reference"]["worst_ratio"]
    lau = scenario_results["lau2015"]
    for t in lau.targets:
        servo = "pid" if "PID servo" in t["claim"] else "pd"
        name = t["claim"].split(",")[0]
        key = "max_percent_error" if "max error" in t["claim"] else "percent_error"
        assert t["measured"] == lau.extra["servo_runs"][servo][name][key]
        bound = 5.0 if key == "max_percent_error" or "published" in name else 2.0
        assert t["met"] == (t["measured"] < bound)


def test_sun2015_shows_the_plants_own_groups_beside_the_identified_ones(scenario_results):
    from tendonsheath.bench.scenarios.common import PLANT_VALUE

    rows = {r["quantity"]: r for r in scenario_results["sun2015"].identified}
    assert rows["mu"][PLANT_VALUE] == "0.1 / 0.115 (sheaths 1 / 2)"
    assert rows["gain r_p/r_d"][PLANT_VALUE] == "1"
    # T0 L / (EA r_p) = 20 N * 1.2 m / (5000 N * 10 mm), and for the second sheath's EA -10 %
    assert rows["T0 L/(EA r_p)"][PLANT_VALUE].startswith("0.48 / 0.5333 rad")
    outside = [r for q, r in rows.items() if q.startswith("BoucWenBacklash ")]
    assert outside and all(r[PLANT_VALUE].startswith("none: the plant is outside") for r in outside)
