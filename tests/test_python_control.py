"""python-control interop: models and compensators as NonlinearIOSystems, FRD from the bench."""

import builtins

import numpy as np
import pytest

import tendonsheath as ts

ct = pytest.importorskip("control")  # in the test extra: never skipped in CI
M = ts.models
SEEDS = range(4)


def _u(rng, lo, hi):
    return float(rng.uniform(lo, hi))


def _backlash(rng):
    return M.Backlash(_u(rng, 0.5, 2), _u(rng, 0.5, 2), _u(rng, 0.01, 0.3), _u(rng, 0.01, 0.3))


def _bouc_wen(rng):
    beta = _u(rng, 0.2, 2)
    return M.BoucWen(
        A=_u(rng, 0.5, 2), beta=beta, gamma=_u(rng, -beta, beta), n=_u(rng, 1, 3),
        alpha=_u(rng, 0, 1), k=_u(rng, 0.5, 2),
    )  # fmt: skip


def _bouc_wen_backlash(rng):
    return M.BoucWenBacklash(
        c_r=_u(rng, 0.5, 2), c_l=_u(rng, 0.5, 2), B_r=_u(rng, 0.02, 0.3), B_l=_u(rng, 0.02, 0.3),
        sigma=_u(rng, 0.5, 2), n=_u(rng, 1, 6),
    )  # fmt: skip


def _plays(rng, count):
    thresholds = np.r_[0.0, np.cumsum(rng.uniform(0.02, 0.1, count - 1))]
    return thresholds, rng.uniform(0.05, 1.0, count)


def _prandtl_ishlinskii(rng):
    return M.PrandtlIshlinskii(*_plays(rng, int(rng.integers(2, 8))))


def _generalized_pi(rng):
    def envelope():
        return (_u(rng, 0.5, 2), _u(rng, 0.5, 2), _u(rng, -0.1, 0.1), _u(rng, -0.1, 0.1))

    thresholds, weights = _plays(rng, int(rng.integers(2, 6)))
    return M.GeneralizedPrandtlIshlinskii(envelope(), envelope(), thresholds, weights)


def _inverses(rng):
    if rng.random() < 0.5:
        return _prandtl_ishlinskii(rng).inverse()
    return _generalized_pi(rng).inverse()


def _polynomial(rng):
    return M.Polynomial(coefficients=rng.normal(size=4))


def _chain(rng):
    if rng.random() < 0.5:
        return M.Chain(_bouc_wen_backlash(rng), _polynomial(rng))
    return M.Chain(_second_order(rng), _prandtl_ishlinskii(rng))


def _scaled(rng):
    return M.Scaled(
        _backlash(rng), _u(rng, -1, 1), _u(rng, 0.2, 3), _u(rng, -1, 1), _u(rng, -3, 3) or 1.0
    )


def _oscillator(rng):
    gamma = _u(rng, 0.1, 0.6)
    return M.HystereticOscillator(
        m=_u(rng, 0.5, 2), c=_u(rng, 0.05, 0.5), k=_u(rng, 0.5, 2), alpha=_u(rng, 0.5, 2),
        beta=_u(rng, 0.5, 2), gamma=gamma, delta=_u(rng, -0.5 * gamma, 0.5), nu=_u(rng, 1, 2),
        input_interpolation=str(rng.choice(["linear", "hold"])),
    )  # fmt: skip


def _first_order(rng):
    return M.FirstOrderLag(_u(rng, 0.01, 0.2))


def _second_order(rng):
    return M.SecondOrderLag(_u(rng, 1, 10), _u(rng, 0.2, 1.5))


MODELS = [
    _backlash, _bouc_wen, _bouc_wen_backlash, _prandtl_ishlinskii, _generalized_pi, _inverses,
    _polynomial, _chain, _scaled, _oscillator, _first_order, _second_order,
]  # fmt: skip


def _signal(rng, n=160):
    """A random sample time and a multisine with a random walk: reversals at many levels."""
    dt = _u(rng, 1e-3, 2e-2)
    t = np.arange(n) * dt
    x = sum(
        _u(rng, 0.1, 0.6) * np.sin(2 * np.pi * _u(rng, 0.2, 4) / (n * dt) * 10 * t + _u(rng, 0, 6))
        for _ in range(3)
    )
    return dt, t, x + np.cumsum(rng.normal(0, 0.02, n))


def _close(actual, expected):
    """Equal to 1e-12 of the signal's scale (rounding only)."""
    atol = 1e-12 * max(1.0, float(np.max(np.abs(expected))))
    np.testing.assert_allclose(np.ravel(actual), expected, rtol=0, atol=atol)


@pytest.mark.parametrize("seed", SEEDS)
@pytest.mark.parametrize("make", MODELS, ids=lambda f: f.__name__.strip("_"))
def test_response_equals_simulate(make, seed):
    rng = np.random.default_rng(seed)
    model = make(rng)
    dt, t, x = _signal(rng)
    sys = model.to_control(dt)
    assert isinstance(sys, ct.NonlinearIOSystem) and sys.dt == dt
    assert sys.input_labels == ["x"] and sys.output_labels == ["y"]
    _close(ct.input_output_response(sys, t, x).outputs, model.simulate(t, x))


@pytest.mark.parametrize("seed", SEEDS)
def test_curve_angle_model_takes_the_curve_angle_as_a_second_input(seed):
    rng = np.random.default_rng(seed)
    model = M.CurveAngleModel(
        friction=_u(rng, 0.05, 0.3), stiffness=_u(rng, 1e4, 5e4), pretension=_u(rng, 5, 20),
        length=_u(rng, 0.5, 1.5), load_force=_u(rng, 0, 5), load_stiffness=_u(rng, 0, 200),
    )  # fmt: skip
    dt, t, x = _signal(rng)
    theta = _u(rng, 1, 4) + 1.5 * np.sin(2 * np.pi * t / t[-1] * _u(rng, 0.5, 3))
    sys = model.to_control(dt)
    assert sys.input_labels == ["x", "curve_angle"]
    out = ct.input_output_response(sys, t, [x, theta]).outputs
    _close(out, model.simulate(t, x, curve_angle=theta))


def test_scaled_curve_angle_model_keeps_the_curve_angle_input():
    rng = np.random.default_rng(5)
    model = M.Scaled(M.CurveAngleModel(friction=0.2), 0.1, 0.5, -0.2, -2.0)
    dt, t, x = _signal(rng)
    theta = 2.0 + np.sin(2 * np.pi * t / t[-1])
    sys = model.to_control(dt)
    assert sys.input_labels == ["x", "curve_angle"]
    out = ct.input_output_response(sys, t, [x, theta]).outputs
    _close(out, model.simulate(t, x, curve_angle=theta))


def test_angle_dependent_model_at_one_curve_angle():
    model = M.AngleDependent(
        "Backlash",
        {"c_r": [1.0], "c_l": [0.9], "B_r": [0.02, 0.05], "B_l": [0.03, 0.04]},
        laws={"B_r": "tanh", "B_l": "linear"},
        angle_friction=0.2,
    )
    dt, t, x = _signal(np.random.default_rng(7))
    sys = model.to_control(dt, curve_angle=2.0)
    _close(ct.input_output_response(sys, t, x).outputs, model.simulate(t, x, curve_angle=2.0))
    with pytest.raises(ValueError, match="curve_angle"):
        model.to_control(dt)


@pytest.mark.parametrize("seed", SEEDS)
def test_the_state_carries_the_history(seed):
    """A run split in two, the second started from the first's last state, equals one run."""
    rng = np.random.default_rng(seed)
    model = _bouc_wen_backlash(rng) if seed % 2 else _oscillator(rng)
    dt, t, x = _signal(rng)
    sys = model.to_control(dt)
    k = int(rng.integers(20, t.size - 20))
    first = ct.input_output_response(sys, t[: k + 1], x[: k + 1])
    second = ct.input_output_response(sys, t[k:], x[k:], X0=first.states[:, -1])
    _close(np.r_[first.outputs[:k], second.outputs], model.simulate(t, x))
    # the functions are pure: the same state and input give the same output and next state
    s = first.states[:, -1]
    assert sys._out(0.0, s, [x[k]]) == sys._out(0.0, s, [x[k]])
    assert sys._rhs(0.0, s, [x[k]]) == sys._rhs(0.0, s, [x[k]])
    # and the state is the history, not the input: another history, another output
    other = ct.input_output_response(sys, t[: k + 1], -x[: k + 1]).states[:, -1]
    assert sys._out(0.0, other, [x[k]])[0] != pytest.approx(sys._out(0.0, s, [x[k]])[0])


def _inverse_feedforwards(rng):
    bwb = _bouc_wen_backlash(rng)
    return [
        ts.compensate.InverseFeedforward(_backlash(rng), smoothing=_u(rng, 0.01, 0.2)),
        ts.compensate.InverseFeedforward(bwb, limits=(-0.4, 0.5, _u(rng, 2, 20))),
        ts.compensate.InverseFeedforward(_prandtl_ishlinskii(rng)),
        ts.compensate.InverseFeedforward(_scaled(rng)),
        ts.compensate.ContinuumFeedforward(
            friction=_u(rng, 0.05, 0.2), curve_angle=_u(rng, 1, 3), mode="published"
        ),
        ts.compensate.LearnedFeedforward(
            ts.compensate.InverseFeedforward(_scaled(rng)), rng.normal(0.0, 0.01, 40), 3e-3
        ),
    ]


@pytest.mark.parametrize("seed", SEEDS)
def test_compensator_response_equals_command(seed):
    rng = np.random.default_rng(seed)
    dt, t, y_d = _signal(rng)
    for ff in _inverse_feedforwards(rng):
        sys = ff.to_control(dt)
        assert sys.input_labels == ["y_d"] and sys.output_labels == ["x"]
        _close(ct.input_output_response(sys, t, y_d).outputs, ff.command(t, y_d))
    ca = ts.compensate.CurveAngleFeedforward(
        friction=_u(rng, 0.05, 0.2), stiffness=1 / _u(rng, 2e-5, 1e-4), length=1.0,
        pretension=_u(rng, 5, 20),
        load_force=_u(rng, 0, 3), smoothing=_u(rng, 0.02, 0.2),
    )  # fmt: skip
    theta = _u(rng, 1, 4) + np.sin(2 * np.pi * t / t[-1])
    out = ct.input_output_response(ca.to_control(dt), t, [y_d, theta]).outputs
    _close(out, ca.command(t, y_d, curve_angle=theta))


def test_adaptive_controller_equals_its_streaming_steps():
    rng = np.random.default_rng(3)
    ctrl = ts.compensate.AdaptiveController.from_model(_backlash(rng), inertia=2e-3)
    dt, t, y_d = _signal(rng)
    y = y_d + rng.normal(0, 0.01, t.size)
    q = y_d + 0.05
    sys = ctrl.to_control(dt)
    out = ct.input_output_response(sys, t, [y_d, y, q]).outputs
    ctrl.reset()
    rows = enumerate(zip(y_d, y, q, strict=True))
    ref = [ctrl.step(a, b, c, dt if k else 0.0) for k, (a, b, c) in rows]
    _close(out, np.array(ref))


@pytest.mark.parametrize("seed", SEEDS)
def test_tip_loop_equals_its_streaming_steps(seed):
    rng = np.random.default_rng(seed)
    loop = ts.compensate.TipLoop(
        ts.compensate.InverseFeedforward(_backlash(rng)), kp=_u(rng, 0.1, 1.0),
        ki=_u(rng, 5, 80), kd=_u(rng, 0, 0.005), max_correction=_u(rng, 0.1, 0.5),
    )  # fmt: skip
    dt, t, y_d = _signal(rng)
    y = 0.9 * y_d + rng.normal(0, 0.01, t.size)
    sys = loop.to_control(dt)
    assert sys.input_labels == ["y_d", "y"] and sys.output_labels == ["x"]
    out = ct.input_output_response(sys, t, [y_d, y]).outputs
    loop.reset()
    ref = [loop.step(a, b, dt if k else 0.0) for k, (a, b) in enumerate(zip(y_d, y, strict=True))]
    _close(out, np.array(ref))


@pytest.mark.parametrize("seed", SEEDS)
def test_interconnection_equals_manual_composition(seed):
    """Feedforward of an identified model in series with a plant model outside its class."""
    rng = np.random.default_rng(seed)
    ff = ts.compensate.InverseFeedforward(_bouc_wen_backlash(rng), smoothing=0.05)
    plant = M.Chain(_backlash(rng), _first_order(rng))
    dt, t, y_d = _signal(rng)
    loop = ct.interconnect(
        [ff.to_control(dt, name="ff"), plant.to_control(dt, name="plant")],
        inplist=["y_d"],
        outlist=["y"],
    )
    _close(ct.input_output_response(loop, t, y_d).outputs, plant.simulate(t, ff.command(t, y_d)))


def test_frequency_response_converts_to_frd():
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(1.0, np.pi),
        friction=0.05,
        elements=10,
        motor=ts.Motor.position(bandwidth_hz=1.5, damping=0.5),
    )
    f = np.array([0.2, 0.7, 1.5, 2.5])
    fr = ts.bench.frequency_response(plant, None, frequencies=f, amplitude=0.3, cycles=2)
    frd = fr.to_control(name="bench")
    assert isinstance(frd, ct.FrequencyResponseData)
    np.testing.assert_allclose(frd.omega, 2 * np.pi * f, rtol=1e-15)
    np.testing.assert_allclose(20 * np.log10(np.ravel(frd.magnitude)), fr.gain_db, atol=1e-12)
    np.testing.assert_allclose(np.degrees(np.ravel(frd.phase)), fr.phase_deg, atol=1e-10)
    # usable in python-control's algebra: in series with a gain of 2, +6.02 dB
    np.testing.assert_allclose(np.ravel((2 * frd).magnitude), 2 * np.ravel(frd.magnitude))


def test_missing_extra_is_a_clear_import_error(monkeypatch):
    real_import = builtins.__import__

    def no_control(name, *args, **kwargs):
        if name == "control" or name.startswith("control."):
            raise ImportError("No module named 'control'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_control)
    with pytest.raises(ImportError, match=r"tendonsheath\[control\]"):
        M.Backlash().to_control(0.01)
    with pytest.raises(ImportError, match=r"tendonsheath\[control\]"):
        ts.compensate.InverseFeedforward(M.Backlash()).to_control(0.01)


@pytest.mark.parametrize("dt", [0.0, -0.1, float("nan"), float("inf"), "0.01", True, None])
def test_bad_sample_time(dt):
    with pytest.raises(ValueError, match="dt must be"):
        M.Backlash().to_control(dt)


def test_bad_uses_are_one_line_errors():
    with pytest.raises(ValueError, match="delay"):
        M.HystereticOscillator(input_interpolation="bandlimited").to_control(0.01)
    with pytest.raises(ValueError, match="delay"):
        lagging = M.HystereticOscillator(input_interpolation="bandlimited")
        M.Chain(lagging, M.Polynomial(1)).to_control(0.01)
    with pytest.raises(ValueError, match="2 input"):
        M.CurveAngleModel().to_control(0.01, inputs=["x"])
    sys = M.Backlash().to_control(0.01)
    with pytest.raises(ValueError, match="snapshot index"):
        ct.input_output_response(sys, np.arange(5) * 0.01, np.zeros(5), X0=3.5)
