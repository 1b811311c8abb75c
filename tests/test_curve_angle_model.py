"""CurveAngleModel against the closed forms of spec A.7/B1/A.4, and its identification."""

import numpy as np
import pytest

import tendonsheath as ts
from reference import closed_forms as ref
from tendonsheath.models import CurveAngleModel
from tendonsheath.plant.physics import backlash_half_width, load_offset, spring_slope


def _random_params(rng):
    return dict(
        friction=rng.uniform(0.05, 0.2),
        stiffness=rng.uniform(5e3, 5e4),
        pretension=rng.uniform(2.0, 40.0),
        length=rng.uniform(0.5, 2.0),
        load_force=rng.uniform(-5.0, 5.0),
        proximal_radius=rng.uniform(3e-3, 10e-3),
        distal_radius=rng.uniform(3e-3, 10e-3),
    )


def test_worked_example_of_the_spec():
    # L=1.2 m, EA=2.4e4 N, T0=10 N, mu=0.1, Theta=2 pi: e_b = 0.152 mm, e_L(5 N) = 0.121 mm.
    assert backlash_half_width(1.2, 2.4e4, 10.0, 0.1, 2 * np.pi) == pytest.approx(
        1.5211e-4, rel=1e-4
    )
    assert load_offset(1.2, 2.4e4, 5.0, 0.1, 2 * np.pi) == pytest.approx(1.2104e-4, rel=1e-4)
    m = CurveAngleModel(distal_radius=3e-3)
    assert 2 * m.backlash_half_width(2 * np.pi) * 5e-3 / 3e-3 == pytest.approx(0.1014, rel=1e-3)


@pytest.mark.parametrize("seed", range(20))
def test_branches_and_dead_zone_match_closed_form(seed):
    rng = np.random.default_rng(seed)
    p = _random_params(rng)
    theta = rng.uniform(0.0, 4 * np.pi)
    model = CurveAngleModel(**p)
    r_p, r_d = p["proximal_radius"], p["distal_radius"]
    e_b = backlash_half_width(p["length"], p["stiffness"], p["pretension"], p["friction"], theta)
    e_l = load_offset(p["length"], p["stiffness"], p["load_force"], p["friction"], theta)
    # input amplitude: several dead zones, in motor rad
    amp = 6 * e_b / r_p + 0.1
    q = np.r_[np.linspace(0, amp, 400), np.linspace(amp, -amp, 800), np.linspace(-amp, amp, 800)]
    y = model.simulate(None, q, curve_angle=theta)
    x_in = r_p * q
    # forward slip at the end (x rising): x_out = x_in - e_b - e_L
    assert r_d * y[-1] == pytest.approx(x_in[-1] - e_b - e_l, rel=1e-9, abs=1e-12)
    # backward slip at the minimum: x_out = x_in + e_b - e_L
    k_min = 1199
    assert r_d * y[k_min] == pytest.approx(x_in[k_min] + e_b - e_l, rel=1e-9, abs=1e-12)
    # dead zone after the reversal at the maximum: the output holds over an input travel 2 e_b
    k_max = 400
    held = np.flatnonzero(np.abs(y[k_max:1200] - y[k_max]) < 1e-15)
    travel = x_in[k_max] - x_in[k_max + held[-1]]
    step = abs(x_in[1] - x_in[0])
    assert travel == pytest.approx(2 * e_b, abs=2 * step)


def test_small_angle_series_is_continuous():
    m = CurveAngleModel()
    for a in (1e-4 * (1 - 1e-9), 1e-4 * (1 + 1e-9)):
        theta = a / 0.1
        assert m.backlash_half_width(theta) * 5e-3 == pytest.approx(
            ref.backlash_half_width(1.2, 2.4e4, 10.0, a), rel=1e-12
        )
    assert m.backlash_half_width(0.0) == 0.0
    assert load_offset(1.2, 2.4e4, 5.0, 0.1, 0.0) == pytest.approx(5 * 1.2 / 2.4e4 / 2)


def test_spring_slope_and_straight_sheath():
    p = dict(friction=0.1, stiffness=2e3, load_stiffness=3e4, length=1.2)
    m = CurveAngleModel(**p)
    theta = np.pi
    c = spring_slope(1.2, 2e3, 0.1, theta, 3e4)
    q = np.linspace(0.0, 2.0, 2001)
    y = m.simulate(None, q, curve_angle=theta)
    slope = (y[-1] - y[-500]) / (q[-1] - q[-500])
    assert slope == pytest.approx(c, rel=1e-9)
    assert c == pytest.approx(ref.spring_slope(1.2, 2e3, 3e4, 0.1 * np.pi), rel=1e-14)
    # straight sheath, no load, no spring: output == input
    straight = CurveAngleModel().simulate(None, np.sin(q), curve_angle=0.0)
    assert np.allclose(straight, np.sin(q), atol=1e-15)


def test_memory_effect_of_curve_angle_changes_at_rest():
    m = CurveAngleModel(friction=0.1, stiffness=2e3)
    q = np.r_[np.linspace(0, 1.0, 200), np.full(300, 1.0)]
    # pulled forward at pi/2, then Theta raised to 2 pi at rest: the output does not move
    theta_up = np.r_[np.full(200, np.pi / 2), np.linspace(np.pi / 2, 2 * np.pi, 300)]
    y_up = m.simulate(None, q, curve_angle=theta_up)
    assert np.all(y_up[200:] == y_up[199])
    # pulled forward at 2 pi, then Theta lowered to pi/2 at rest: it creeps to the new branch
    theta_down = theta_up[::-1].copy()
    theta_down[:200] = 2 * np.pi
    y_down = m.simulate(None, q, curve_angle=theta_down)
    r = 5e-3
    e_new = m.backlash_half_width(np.pi / 2) * r
    assert y_down[-1] * r == pytest.approx(1.0 * r - e_new, rel=1e-12)
    assert y_down[-1] > y_down[199]
    assert np.all(np.diff(y_down[199:]) >= 0)


def test_streaming_equals_batch_and_json_round_trip():
    m = CurveAngleModel(friction=0.15, stiffness=3e3, load_force=1.5)
    q = np.sin(np.linspace(0, 12, 600))
    theta = np.linspace(np.pi / 2, 3 * np.pi, 600)
    y = m.simulate(None, q, curve_angle=theta)
    m.reset()
    ys = [m.step(a, 0.0, th) for a, th in zip(q, theta, strict=True)]
    assert np.allclose(ys, y, rtol=0, atol=0)
    back = ts.load_model(m.to_json())
    assert back == m
    assert np.array_equal(back.simulate(None, q, curve_angle=theta), y)
    with pytest.raises(ValueError, match="curve_angle"):
        m.simulate(None, q)
    with pytest.raises(ValueError, match="stiffness"):
        CurveAngleModel(stiffness=-1.0)


def test_self_class_recovery_three_angles_predict_unseen_angles():
    """Self-class recovery: data generated by the model class being fitted
    (CurveAngleModel, noise added)."""
    truth = CurveAngleModel(friction=0.12, stiffness=2.0e3, load_force=2.0)
    t = np.arange(0.0, 8.0, 5e-3)
    x = 0.6 * np.sin(2 * np.pi * 0.3 * t) + 0.2 * np.sin(2 * np.pi * 0.71 * t)
    rng = np.random.default_rng(7)
    noise = 0.004

    def record(theta):
        y = truth.simulate(t, x, curve_angle=theta)
        return y + noise * rng.standard_normal(t.size)

    recs = [(t, x, record(th), th) for th in (np.pi / 2, np.pi, 2 * np.pi)]
    fit = ts.identify(CurveAngleModel, recordings=recs, progress=False)
    for theta in (1.5 * np.pi, 3 * np.pi):
        val = fit.validate(t, x, record(theta), curve_angle=theta)
        assert val["rmse"] < 2 * fit.rmse, (theta, val, fit.rmse)
        assert val["rmse"] < 1.2 * noise


def test_self_class_recovery_angle_dependent_parameters_unseen_angles():
    """Self-class recovery: data generated by the model class being fitted
    (AngleDependent BoucWenBacklash, noise added)."""
    truth = ts.models.AngleDependent(
        "BoucWenBacklash",
        {
            "c_r": [1.0],
            "c_l": [0.95],
            "B_r": [0.0, 0.3],
            "B_l": [0.01, 0.25],
            "rho": [12.0],
            "sigma": [1.0],
            "n": [3.0],
        },
        {"B_r": "tanh", "B_l": "tanh"},
        angle_friction=0.2,
    )
    t = np.arange(0.0, 6.0, 5e-3)
    x = 0.6 * np.sin(2 * np.pi * 0.4 * t) + 0.2 * np.sin(2 * np.pi * 0.9 * t)
    rng = np.random.default_rng(3)
    recs = []
    for th in (np.pi / 2, np.pi, 2 * np.pi):
        y = truth.simulate(t, x, curve_angle=th)
        recs.append((t, x, y + 0.003 * rng.standard_normal(t.size), th))
    fit = ts.identify(
        ts.models.BoucWenBacklash,
        recordings=recs,
        progress=False,
        depends_on_angle={"B_r": "tanh", "B_l": "tanh"},
    )
    assert isinstance(fit.model, ts.models.AngleDependent)
    assert fit.model.params["angle_friction"] == pytest.approx(0.2, rel=0.1)
    for th in (1.5 * np.pi, 3 * np.pi):
        y = truth.simulate(t, x, curve_angle=th) + 0.003 * rng.standard_normal(t.size)
        assert fit.validate(t, x, y, curve_angle=th)["rmse"] < 2 * fit.rmse
    back = ts.load_model(fit.model.to_json())
    assert back == fit.model
    assert np.array_equal(back.simulate(t, x, curve_angle=3.0), fit.model.simulate(t, x, 3.0))


@pytest.mark.parametrize("seed", range(10))
def test_the_play_widens_the_dead_zone_by_itself_at_every_angle(seed):
    """A motor-side play p in series with the tendons: the input's dead-zone travel is
    2 e_b + r_p p at any curve angle (p alone on a straight sheath)."""
    rng = np.random.default_rng(100 + seed)
    p = _random_params(rng)
    play = rng.uniform(0.002, 0.05)
    theta = rng.choice([0.0, rng.uniform(0.5, 4 * np.pi)])
    model = CurveAngleModel(**p, play=play)
    r_p = p["proximal_radius"]
    e_b = backlash_half_width(p["length"], p["stiffness"], p["pretension"], p["friction"], theta)
    amp = 6 * e_b / r_p + 3 * play + 0.1
    q = np.r_[np.linspace(0, amp, 4000), np.linspace(amp, -amp, 8000)]
    y = model.simulate(None, q, curve_angle=theta)
    held = np.flatnonzero(np.abs(y[4000:] - y[3999]) < 1e-15)
    travel = r_p * (q[3999] - q[4000 + held[-1]])
    step = r_p * abs(q[1] - q[0])
    assert travel == pytest.approx(2 * e_b + r_p * play, abs=2 * step)


def test_the_curve_angle_feedforward_inverts_the_play():
    """CurveAngleFeedforward.from_model of a model with play makes that model track the
    reference (the inverse's defining property), where ignoring the play leaves an error of
    half the play at each reversal."""
    model = CurveAngleModel(friction=0.1, stiffness=5e3, pretension=20.0, length=1.2,
                            proximal_radius=1e-2, distal_radius=1e-2, play=0.04)  # fmt: skip
    t = np.arange(0.0, 10.0, 1e-3)
    y_d = 0.6 * np.sin(2 * np.pi * 0.2 * t)
    errors = {}
    for told in (0.0, 0.04):
        ff = ts.compensate.CurveAngleFeedforward.from_model(
            model.with_params(play=told), curve_angle=2.0, smoothing=1e-3
        )
        y = model.simulate(t, ff.command(t, y_d), curve_angle=2.0)
        errors[told] = float(np.max(np.abs(y - y_d)[t > 5.0]))
    assert errors[0.04] < 1e-3  # the smoothing's rounding at reversals only
    assert errors[0.0] > 0.5 * 0.04 * 0.5  # without the play: about half the play, r_p = r_d


def test_identify_recovers_the_play_from_three_angles():
    """Self-class: curve angles that differ tell the constant play from the tendons' dead zone."""
    truth = CurveAngleModel(friction=0.12, stiffness=2.0e3, load_force=1.0, play=0.03)
    t = np.arange(0.0, 8.0, 5e-3)
    x = 0.6 * np.sin(2 * np.pi * 0.3 * t) + 0.2 * np.sin(2 * np.pi * 0.71 * t)
    rng = np.random.default_rng(3)
    recs = [
        (t, x, truth.simulate(t, x, curve_angle=th) + 0.002 * rng.standard_normal(t.size), th)
        for th in (0.5 * np.pi, np.pi, 2 * np.pi)
    ]
    fit = ts.identify(CurveAngleModel, recordings=recs, free=["play"], progress=False)
    assert fit.model.params["play"] == pytest.approx(0.03, abs=0.003)
    assert fit.model.params["friction"] == pytest.approx(0.12, rel=0.05)


def test_files_saved_before_the_play_still_load():
    data = CurveAngleModel(friction=0.12).to_dict()
    del data["params"]["play"]
    assert ts.load_model(data) == CurveAngleModel(friction=0.12)
    ff = ts.compensate.CurveAngleFeedforward(0.1, 5e3, 1.0, 10.0).to_dict()
    del ff["play"]
    assert ts.compensate.load(ff).params["play"] == 0.0
