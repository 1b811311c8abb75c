"""Frequency response: closed forms of a frictionless plant behind a second-order motor."""

import numpy as np
import pytest

import tendonsheath as ts


def test_frictionless_plant_shows_the_motor_lag():
    fn, zeta = 1.5, 0.5
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(1.0, np.pi),
        friction=0.0,
        elements=10,
        motor=ts.Motor.position(bandwidth_hz=fn, damping=zeta),
    )
    f = np.array([0.1, 0.5, 1.0, 1.5, 2.5])
    fr = ts.bench.frequency_response(
        plant, None, frequencies=f, amplitude=0.3, rate=2000.0, cycles=4
    )
    r = f / fn
    G = 1.0 / (1 - r**2 + 2j * zeta * r)
    # discrete-time motor at 2 kHz: within 0.1 dB and 1.5 deg of the continuous lag
    np.testing.assert_allclose(fr.gain_db, 20 * np.log10(np.abs(G)), atol=0.1)
    np.testing.assert_allclose(fr.phase_deg, np.degrees(np.angle(G)), atol=1.5)
    np.testing.assert_allclose(fr.error_magnitude, np.abs(G - 1), atol=0.01)
    r3 = np.sqrt(1 - 2 * zeta**2 + np.sqrt((1 - 2 * zeta**2) ** 2 + 1))
    assert fr.bandwidth_3db == pytest.approx(r3 * fn, rel=0.05)


def test_bad_frequencies():
    plant = ts.PullPullPlant(route=ts.Route.uniform(1.0, 1.0), elements=10)
    with pytest.raises(ValueError, match="positive"):
        ts.bench.frequency_response(plant, None, frequencies=[0.1, -1.0])
    with pytest.raises(ValueError, match="cycles"):
        ts.bench.frequency_response(plant, None, frequencies=[0.1], cycles=1)
