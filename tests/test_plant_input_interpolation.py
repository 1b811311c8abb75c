"""Input reconstruction between samples for the realistic (continuous-time) plant (issue 12,
Step 9 leftovers item 5).

Reference: the same plant stepped on a grid 256x finer than the samples with the exact
continuous input (a sum of sines evaluated there), read at the sample times; at that step
the input's path inside a step no longer matters. The sampled record is then simulated with
each reconstruction at the sample rate."""

import warnings

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.plant.presets import realistic_plant

FS = 100.0
N = 400
REF = 256


def _plant(**extra):
    kw = realistic_plant()
    kw.pop("route", None)
    kw.update(elements=20, pretension=30.0, **extra)  # no slack at these rates
    return ts.PullPullPlant(route=ts.Route.uniform(1.0, np.pi), **kw)


def _sines(rng, band=0.2 * FS, count=12):
    f = rng.uniform(0.5, band, count)
    ph = rng.uniform(0, 2 * np.pi, count)
    return lambda s: 0.1 * np.sin(2 * np.pi * np.outer(s, f) + ph).sum(axis=1) / np.sqrt(count)


@pytest.mark.parametrize("seed", [0, 1])
def test_bandlimited_beats_hold_and_linear_on_a_smooth_input(seed):
    """Measured (rmse / range, seeds 0 and 1, 8 sub-steps): hold 3.0e-2 / 2.7e-2, linear
    2.6e-2 / 2.3e-2, bandlimited 7.6e-3 / 7.6e-3 (what is left is mostly the plant's own
    time stepping at dt / 8: 32 sub-steps give 3.6e-3)."""
    u = _sines(np.random.default_rng(seed))
    plant = _plant()
    t = np.arange(N) / FS
    tf = np.arange(N * REF) / (FS * REF)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ts.SlackWarning)
        ref = plant.simulate(tf, u(tf))[::REF]
        err = {}
        for mode in ("hold", "linear", "bandlimited"):
            res = plant.simulate(t, u(t), input_interpolation=mode, periodic=False)
            e = (res.q_out - ref)[20:-20]  # away from the held ends of the windowed sinc
            err[mode] = float(np.sqrt(np.mean(e**2)) / np.ptp(ref))
            assert res.input_interpolation.startswith(mode)
    assert err["bandlimited"] < 0.35 * err["hold"], err
    assert err["bandlimited"] < 0.5 * err["linear"], err


def test_default_is_hold_and_step_stays_causal():
    """simulate() with the default reconstruction is the sample-by-sample plant; step() holds
    the sample whatever the plant's reconstruction (no look-ahead, no delay)."""
    u = _sines(np.random.default_rng(3))
    t = np.arange(200) / FS
    x = u(t)
    plant = _plant()
    assert plant.input_interpolation == "hold"
    held = plant.simulate(t, x)
    plant.set_input_interpolation("bandlimited", substeps=8)
    assert plant.input_interpolation == "bandlimited"
    assert np.array_equal(plant.simulate(t, x, input_interpolation="hold"), held)
    assert not np.allclose(plant.simulate(t, x), held, atol=1e-6 * np.ptp(held))
    plant.reset()
    stream = np.array([plant.step(v, 1.0 / FS) for v in x])
    assert np.max(np.abs(stream - held)) < 1e-12 * np.ptp(held)


def test_periodic_record_uses_fft_and_the_motor_and_routes_follow_the_grid():
    fs, n = FS, 256
    k = np.array([1, 3, 7, 12])
    t = np.arange(n) / fs
    x = 0.08 * np.sin(2 * np.pi * np.outer(t, k * fs / n)).sum(axis=1) / 2
    plant = _plant(motor=ts.Motor.position(bandwidth_hz=20.0))
    res = plant.simulate(t, x, input_interpolation="bandlimited")
    assert res.input_interpolation == "bandlimited (periodic: FFT)"
    assert res.q_out.shape == res.q_motor.shape == res.slack.shape == (n,)
    hold = plant.simulate(t, x)
    assert np.ptp(res.q_in) > 0.5 * np.ptp(x)  # the motor follows on the finer grid
    assert np.max(np.abs(res.q_in - hold.q_in)) < 0.2 * np.ptp(hold.q_in)
    linear = plant.simulate(t, x, input_interpolation="linear")
    assert linear.input_interpolation == "linear"
    # a route change at sample 100 lands at the same time on the finer grid
    bent = ts.Route.uniform(1.0, 1.5 * np.pi)

    def routes(tk):
        return bent if tk >= t[100] else plant.route

    plant = _plant()
    a = plant.simulate(t, x, routes=routes, input_interpolation="linear")
    b = plant.simulate(t, x, input_interpolation="linear")
    assert np.allclose(a[:100], b[:100]) and not np.allclose(a[100:], b[100:])


def test_bad_reconstruction_options_are_refused_with_a_reason():
    plant = _plant()
    t = np.arange(50) / FS
    with pytest.raises(ValueError, match="input_interpolation must be one of"):
        plant.simulate(t, np.sin(t), input_interpolation="cubic")
    with pytest.raises(ValueError, match="uniform sampling"):
        plant.simulate(np.r_[t[:10], t[10:] + 0.003], np.sin(t), input_interpolation="linear")
    with pytest.raises(ValueError, match="substeps must be an integer >= 1"):
        plant.set_input_interpolation("linear", substeps=0)


def test_continuum_plant_takes_the_same_option():
    """ContinuumPlant (a PullPullPlant) with distal dynamics: the same reconstruction runs."""
    kw = realistic_plant()
    for k in ("route", "friction2", "stiffness2"):
        kw.pop(k, None)
    plant = ts.ContinuumPlant(elements=20, pretension=30.0, **kw)
    t = np.arange(300) / FS
    x = _sines(np.random.default_rng(4), count=6)(t)
    res = plant.simulate(t, x, input_interpolation="bandlimited", periodic=False)
    held = plant.simulate(t, x)
    assert res.input_interpolation == "bandlimited (windowed sinc)"
    assert np.all(np.isfinite(res.q_out))
    assert 1e-4 * np.ptp(held) < np.max(np.abs(res.q_out - held)) < 0.5 * np.ptp(held)
