"""identify_loop_dynamics and calibrate_loop: a tip-feedback loop's servo, distal resonance and
sensor delay from calibration logs (synthetic linear data, the realistic Do plant, bad inputs,
bench.calibrate(..., dynamics=True))."""

import math
import warnings

import numpy as np
import pytest
from scipy.signal import lfilter

import tendonsheath as ts
from tendonsheath import presets
from tendonsheath.bench import calibrate, calibrate_loop, loop_calibration_input
from tendonsheath.bench.scenarios import do
from tendonsheath.identify import (
    LoopDynamics,
    ResonanceOutOfBandWarning,
    empirical_response,
    identify_loop_dynamics,
)
from tendonsheath.identify.servo import servo_filter

DT = 1e-3


def _synthetic(rng, resonance, damping, delay, servo_hz, noise=2e-4, duration=3.0):
    """Logs generated from the model's own discrete forms: the servo (zero-order hold) and
    the distal mode (first-order hold) with ``delay`` samples, white noise on the tip."""
    t, u = loop_calibration_input(duration=duration)
    ns, ds = servo_filter(servo_hz, 0.8, 1.0, 0, DT)
    q = lfilter(ns, ds, u - u[0]) + u[0]
    nd, dd = servo_filter(resonance, damping, 1.0, delay, DT, 0.0, "foh")
    y = lfilter(nd, dd, q - q[0]) + q[0] + noise * rng.standard_normal(u.size)
    true = (np.convolve(ns, nd), np.convolve(ds, dd))
    return t, u, q, y, true


def _true_response(true, f):
    zinv = np.exp(-2j * np.pi * f * DT)
    num, den = true
    return np.polyval(num[::-1], zinv) / np.polyval(den[::-1], zinv)


def test_synthetic_cases_recovered_within_their_standard_errors():
    rng = np.random.default_rng(20260514)
    f = np.linspace(1.0, 100.0, 60)
    for _ in range(8):
        resonance, damping = rng.uniform(10, 80), rng.uniform(0.05, 0.5)
        delay, servo_hz = int(rng.integers(0, 9)), rng.uniform(30, 80)
        t, u, q, y, true = _synthetic(rng, resonance, damping, delay, servo_hz)
        dyn = identify_loop_dynamics(t, u, q, y)
        case = f"case {resonance:.1f} Hz, {damping:.3f}, {delay}: {dyn.summary()}"
        se = dyn.standard_errors
        # 4 standard errors, not 3: 16 checks over 8 cases, and the linearised errors ignore
        # the high-pass's colouring of the noise; a wrong fit misses by many more
        assert abs(dyn.resonance_hz - resonance) < 4 * se["resonance_hz"], case
        assert abs(dyn.damping - damping) < 4 * se["damping"], case
        assert dyn.delay_samples == delay, case  # whole samples: found exactly at this noise
        assert dyn.delay == pytest.approx(delay * DT)
        assert 0 < se["delay"] < 1.5 * DT
        # the data are the model's own form: the response is the true one but for the noise
        # (1e-3 of the tip's chirp), so 3 % leaves room for the noise only
        model, exact = dyn.frequency_response(f), _true_response(true, f)
        assert np.max(np.abs(model - exact) / np.abs(exact)) < 0.03, case


def test_loop_dynamics_api():
    rng = np.random.default_rng(3)
    t, u, q, y, true = _synthetic(rng, 40.0, 0.2, 3, 60.0)
    dyn = identify_loop_dynamics(t, u, q, y)
    assert isinstance(dyn, LoopDynamics)
    num, den = dyn.discrete()
    assert den[0] == pytest.approx(1.0)
    assert np.all(num[:3] == 0) and num[3] != 0  # 3 samples of delay, no more
    # the bandwidth is where |command -> tip| is 3 dB below its static value
    h0, hb = dyn.frequency_response([0.0, dyn.bandwidth_hz])
    assert abs(hb / h0) == pytest.approx(1 / math.sqrt(2), rel=1e-3)
    assert np.all(
        np.abs(dyn.frequency_response(np.linspace(0, dyn.bandwidth_hz * 0.99, 50)) / abs(h0)) > 0.7
    )
    # at another sample time the delay stays 3 ms
    num2, _ = dyn.discrete(0.5e-3)
    assert np.all(num2[:6] == 0) and num2[6] != 0
    d = dyn.as_dict()
    assert d["delay"] == pytest.approx(3e-3) and d["delay_samples"] == 3
    assert d["servo"]["frequency_hz"] == dyn.servo.frequency
    line = dyn.summary()
    assert "resonance" in line and "+-" in line and "delay 3 " in line and "\n" not in line
    # the empirical H1 of the logs matches the model where the coherence is high
    e = empirical_response(t, u, y)
    band = (e.coherence > 0.9) & (e.frequency_hz > 6) & (e.frequency_hz < 80)
    assert band.sum() > 20
    err = np.abs(dyn.frequency_response(e.frequency_hz[band]) - e.response[band])
    assert np.median(err / np.abs(e.response[band])) < 0.05
    pytest.importorskip("control")
    tf = dyn.to_control()
    assert tf.dt == pytest.approx(DT)
    assert complex(tf(np.exp(2j * np.pi * 20 * DT))) == pytest.approx(
        dyn.frequency_response([20.0])[0]
    )


def _expected_distal_mode():
    """The distal mode from the preset's numbers: the distal inertia on the two tendons'
    stiffness EA/L through the distal radius, damped by the distal damping alone (the sheath's
    viscosity adds more: this is a lower bound)."""
    kw = do.physics(elements=20)
    k = (kw["stiffness"] + kw["stiffness2"]) / do.NOMINAL.length * kw["distal_radius"] ** 2
    inertia = presets.REALISTIC["distal_inertia"]
    w = math.sqrt(k / inertia)
    return w / (2 * math.pi), presets.REALISTIC["distal_damping"] / (2 * math.sqrt(k * inertia))


@pytest.fixture(scope="module")
def do_plant():
    return ts.PullPullPlant(
        route=do.NOMINAL, motor=do.servo_motor("pid"), **do.physics(elements=20)
    )


@pytest.mark.parametrize("delay", [0.0, 1e-3, 5e-3])
def test_realistic_plant_sensor_delay_and_distal_mode(do_plant, delay):
    sensor = ts.Sensor(noise_std=2e-4, resolution=1e-4, delay=delay)
    loop = calibrate_loop(do_plant, sensor=sensor, seed=5)
    dyn = loop.dynamics
    assert abs(dyn.delay - delay) <= DT + 1e-12, dyn.summary()  # within one sample
    f_mode, zeta_floor = _expected_distal_mode()  # 42.5 Hz, 0.19
    # the tendons' stiffness is only approximately EA/L (pretension, friction, 20 elements):
    # 15 % (6 Hz) around the mode; a fit of the servo or a harmonic would be 20 Hz off
    assert abs(dyn.resonance_hz - f_mode) < 0.15 * f_mode, dyn.summary()
    assert zeta_floor < dyn.damping < 1.0, dyn.summary()  # the sheath's viscosity adds damping
    assert 20 < dyn.bandwidth_hz < 100
    # the identified response against the logs' own H1, inside the chirp (5-120 Hz) where the
    # coherence is high (the tip's noise and the ramp's slow creep out of it): 10 % median, 25 %
    # at worst (the plant is not linear: friction, creep)
    e = loop.empirical()
    band = (e.coherence > 0.9) & (e.frequency_hz >= 7)
    assert band.sum() > 20
    rel = np.abs(dyn.frequency_response(e.frequency_hz[band]) / e.response[band] - 1)
    assert np.median(rel) < 0.1 and np.max(rel) < 0.25, (np.median(rel), np.max(rel))


def test_loop_calibration_input_is_monotonic_and_excites_the_tip_above_noise():
    t, command = loop_calibration_input()
    assert np.all(np.diff(command) > 0)  # the tendons never reverse
    # chirp amplitude at 30-60 Hz (the ramp removed): well above 2e-4 rad of sensor noise
    f = 5.0 * (120 / 5.0) ** (t / t[-1])
    chirp = command - np.polyval(np.polyfit(t, command, 1), t)
    for lo, hi in ((30, 40), (50, 60)):
        sel = (f > lo) & (f < hi)
        assert np.max(np.abs(chirp[sel])) > 5 * 2e-4


def _clean():
    rng = np.random.default_rng(0)
    t, u, q, y, _ = _synthetic(rng, 40.0, 0.2, 2, 60.0, duration=1.0)
    return t, u, q, y


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda t, u, q, y: (t, u[:-1], q, y), "different lengths"),
        (lambda t, u, q, y: (t, u, q, y[:-1]), "different lengths"),
        (lambda t, u, q, y: (t, np.where(t > 0.5, np.nan, u), q, y), "command must be finite"),
        (lambda t, u, q, y: (t, u, q, np.where(np.abs(t - 0.3) < 2e-3, np.nan, y)), "dropouts"),
        (lambda t, u, q, y: (t * (1 + 0.1 * t), u, q, y), "uniform"),
        (lambda t, u, q, y: (t[:50], u[:50], q[:50], y[:50]), "at least 64 samples"),
        (lambda t, u, q, y: (t, np.ones_like(u), q, y), "command does not move"),
        (lambda t, u, q, y: (t, u, q, np.zeros_like(y)), "tip reading does not move"),
        (
            lambda t, u, q, y: (t, u, q, 1e-3 * np.random.default_rng(1).standard_normal(t.size)),
            "does not respond",
        ),
    ],
)
def test_bad_logs_raise_a_clear_error(change, message):
    with pytest.raises(ValueError, match=message):
        identify_loop_dynamics(*change(*_clean()))


def test_bad_arguments_raise():
    t, u, q, y = _clean()
    with pytest.raises(ValueError, match="max_delay"):
        identify_loop_dynamics(t, u, q, y, max_delay=-1)
    with pytest.raises(ValueError, match="highpass_hz"):
        identify_loop_dynamics(t, u, q, y, highpass_hz=400.0)
    torque = ts.PullPullPlant(route=do.NOMINAL, motor=do.torque_motor(), **do.physics(elements=10))
    with pytest.raises(ValueError, match="position motor"):
        calibrate_loop(torque)


def test_calibrate_attaches_one_loop_per_shape(do_plant):
    sensor = ts.Sensor(noise_std=2e-4, resolution=1e-4, delay=2e-3)
    routes = list(do.CALIBRATION_ROUTES)
    plain = calibrate(do_plant, routes[:1], models_=(), duration=2.0, sensor=sensor)
    assert plain.loops == [] and plain.loop_summary() == ""
    cal = calibrate(do_plant, routes, models_=(), duration=2.0, sensor=sensor, dynamics=True)
    assert len(cal.loop_dynamics) == len(routes)
    for dyn in cal.loop_dynamics:
        assert isinstance(dyn, LoopDynamics)
        assert abs(dyn.delay - 2e-3) <= DT + 1e-12
    assert len(cal.loop_summary().splitlines()) == len(routes)
    assert len(cal.to_dict()["loop_dynamics"]) == len(routes)
    rows = [r["quantity"] for r in cal.identified_rows()]
    assert "shape 3: distal resonance (Hz)" in rows
    assert not any("pretension" in r for r in rows)  # no groups: no scale to declare
    assert sum("loop (chirp" in r.name for r in cal.runs) == len(routes)


def test_a_mode_outside_the_excitation_band_is_refused():
    """Logs say nothing of a mode the command never excited: a synthetic 250 Hz mode under the
    5-120 Hz chirp is fitted near 250 Hz (the data are the model's own form), but reported as
    no resonance within the band; the distal part is then its gain and delay, and a mode below
    the band is refused outright. A 100 Hz mode, inside the band, is still reported."""
    rng = np.random.default_rng(7)
    t, u, q, y, true = _synthetic(rng, 250.0, 0.2, 1, 60.0)
    for band in (None, (5.0, 120.0)):  # inferred from the command (2-117 Hz) or given
        with pytest.warns(ResonanceOutOfBandWarning, match="no resonance identified"):
            dyn = identify_loop_dynamics(t, u, q, y, band_hz=band)
        assert not dyn.resonance_identified and dyn.resonance_hz == math.inf
        assert math.isnan(dyn.damping)
        assert dyn.rejected_resonance_hz > dyn.band_hz[1]
        assert dyn.design_limit_hz == dyn.band_hz[1]
        # the inferred band's upper edge: the chirp ends at 120 Hz, its last Hz tapered
        assert 100.0 < dyn.band_hz[1] <= 120.0
        assert dyn.delay_samples == 1  # a 250 Hz mode adds < 0.3 samples of lag in the band
        num, den = dyn.distal_discrete()
        assert den.tolist() == [1.0] and num.tolist() == [0.0, pytest.approx(dyn.gain)]
        # up to 40 Hz the static distal part is within 10 % of the truth: it misses the 250 Hz
        # mode's phase lag, about 2 zeta f / f_n (6 % at 40 Hz), and its lift (f / f_n)^2 (3 %)
        f = np.linspace(5.0, 40.0, 30)
        rel = np.abs(dyn.frequency_response(f) / _true_response(true, f) - 1)
        assert np.max(rel) < 0.1, np.max(rel)
        assert "none within the" in dyn.summary() and "refused" in dyn.summary()
        d = dyn.as_dict()
        assert d["resonance_hz"] is None and d["resonance_identified"] is False
        assert d["rejected_resonance_hz"] == dyn.rejected_resonance_hz
    t, u, q, y, _ = _synthetic(rng, 3.0, 0.3, 1, 60.0)
    with pytest.raises(ValueError, match=r"below the excitation's band \(5-120 Hz\)"):
        identify_loop_dynamics(t, u, q, y, band_hz=(5.0, 120.0))
    t, u, q, y, _ = _synthetic(rng, 100.0, 0.2, 1, 60.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ResonanceOutOfBandWarning)
        dyn = identify_loop_dynamics(t, u, q, y, band_hz=(5.0, 120.0))
    assert dyn.resonance_identified and abs(dyn.resonance_hz - 100.0) < 5.0
    for bad in ((120.0, 5.0), (5.0, 900.0), "wide"):
        with pytest.raises(ValueError, match="band_hz"):
            identify_loop_dynamics(t, u, q, y, band_hz=bad)


def test_calibrate_loop_finds_no_resonance_on_a_plant_without_distal_dynamics(do_plant):
    """A pull-pull pair with no distal inertia has no mode for the 5-120 Hz chirp to show: the
    fit's mode lands far above the band (about 220 Hz) and calibrate_loop refuses it; the
    realistic preset's mode (42.5 Hz, in the band) is still found, without the warning."""
    sensor = ts.Sensor(noise_std=2e-4, resolution=1e-4, delay=1e-3)
    bare = ts.PullPullPlant(route=do.NOMINAL, motor=do.servo_motor("pid"),
                            **{**do._COMMON, "elements": 20}, distal_inertia=0.0)  # fmt: skip
    with pytest.warns(ResonanceOutOfBandWarning, match="5-120 Hz excitation band"):
        dyn = calibrate_loop(bare, sensor=sensor, seed=5).dynamics
    assert dyn.band_hz == (5.0, 120.0) and not dyn.resonance_identified
    assert dyn.rejected_resonance_hz > 120.0 and dyn.design_limit_hz == 120.0
    assert abs(dyn.delay - 1e-3) <= DT + 1e-12
    with warnings.catch_warnings():
        warnings.simplefilter("error", ResonanceOutOfBandWarning)
        real = calibrate_loop(do_plant, sensor=sensor, seed=5).dynamics
    f_mode, _ = _expected_distal_mode()
    assert real.resonance_identified and real.band_hz == (5.0, 120.0)
    assert abs(real.resonance_hz - f_mode) < 0.15 * f_mode  # as the realistic test above
