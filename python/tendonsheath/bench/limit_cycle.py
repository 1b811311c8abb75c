"""Limit cycles: an oscillation the closed loop makes on its own, told from tracking error.

A loop that chatters (a controller against a dead band, or one with too much gain for its
delay) turns the tip back and forth many times between two turns of the reference. A loop
that tracks well turns the tip where the reference turns, even when its error has lines at
harmonics of the reference (backlash makes those). So the test counts turns: the reversals
of the tip angle against the reversals of the reference, each reversal a swing larger than
0.1 % of the reference's range (noise and sub-resolution jitter are not counted).
"""

from __future__ import annotations

import numpy as np

#: a swing smaller than this share of the reference's range is not a reversal
SWING_SHARE = 1e-3
#: a limit cycle: the tip's extra reversals at least this many times the reference's ...
EXTRA_OVER_REFERENCE = 2.0
#: ... and at least this many extra oscillation cycles (two reversals each) per second
EXTRA_CYCLES_PER_S = 1.0


def reversals(x: np.ndarray, swing: float) -> int:
    """Turns of ``x`` (maxima and minima) that stand at least ``swing`` above or below
    their neighbourhood (``scipy.signal.find_peaks`` prominence)."""
    from scipy.signal import find_peaks

    if x.size < 3:
        return 0
    peaks = find_peaks(x, prominence=swing)[0]
    troughs = find_peaks(-x, prominence=swing)[0]
    return int(peaks.size + troughs.size)


def _reference_band(reference: np.ndarray, dt: float) -> float:
    """The highest frequency (Hz) at which the reference has 0.1 % of its largest line (a
    Hann window: a run's part is not a whole number of periods, and without one the leakage
    would spread the band far above the reference's lines)."""
    window = np.hanning(reference.size)
    spectrum = np.abs(np.fft.rfft((reference - reference.mean()) * window))
    freqs = np.fft.rfftfreq(reference.size, dt)
    if not spectrum.any():
        return 0.0
    return float(freqs[spectrum >= 1e-3 * spectrum.max()].max())


def _oscillation(error: np.ndarray, dt: float, above_hz: float) -> tuple[float, float]:
    """The error's strongest line above ``above_hz`` (Hz) and the amplitude (peak, output
    units) of all the error above it."""
    spectrum = np.fft.rfft(error - error.mean())
    freqs = np.fft.rfftfreq(error.size, dt)
    high = freqs > above_hz
    if not high.any():
        return float("nan"), 0.0
    windowed = np.abs(np.fft.rfft((error - error.mean()) * np.hanning(error.size)))
    k = int(np.argmax(windowed * high))
    kept = np.where(high, spectrum, 0.0)
    amplitude = float(np.sqrt(2.0) * np.std(np.fft.irfft(kept, error.size)))
    return float(freqs[k]), amplitude


def limit_cycle(t: np.ndarray, reference: np.ndarray, output: np.ndarray) -> dict:
    """Whether the tip oscillates on its own over a run's scored part.

    Parameters
    ----------
    t : numpy.ndarray of float
        Sample times (s), uniform.
    reference, output : numpy.ndarray of float
        The desired and the actual tip angle, of ``t``'s length.

    Returns
    -------
    dict
        ``detected`` (bool), ``output_reversals`` and ``reference_reversals`` (counts),
        ``swing`` (the smallest counted swing, output units), and, when detected,
        ``frequency_hz`` (the error's strongest line above the reference's band) and
        ``amplitude`` (the error above that band, peak); both NaN when not detected.
    """
    if t.size < 8:
        return {"detected": False, "output_reversals": 0, "reference_reversals": 0,
                "swing": 0.0, "frequency_hz": float("nan"), "amplitude": float("nan")}  # fmt: skip
    span = float(np.ptp(reference))
    swing = SWING_SHARE * span if span > 0 else SWING_SHARE
    n_out, n_ref = reversals(output, swing), reversals(reference, swing)
    duration = float(t[-1] - t[0])
    extra = n_out - n_ref
    detected = extra >= EXTRA_OVER_REFERENCE * n_ref and extra >= (
        2.0 * EXTRA_CYCLES_PER_S * duration
    )
    frequency, amplitude = float("nan"), float("nan")
    if detected:
        dt = duration / (t.size - 1)
        frequency, amplitude = _oscillation(output - reference, dt, 2.0 * _reference_band(
            reference, dt))  # fmt: skip
    return {
        "detected": bool(detected),
        "output_reversals": n_out,
        "reference_reversals": n_ref,
        "swing": swing,
        "frequency_hz": frequency,
        "amplitude": amplitude,
    }


def describe(cycle: dict, unit: str = "rad") -> str:
    """One phrase for a report: "limit cycle near 9.1 Hz, +-48 mrad (338 tip reversals for the
    reference's 26)", or "" when none was detected."""
    if not cycle.get("detected"):
        return ""
    amplitude = cycle["amplitude"]
    size = f"+-{1e3 * amplitude:.3g} m{unit}" if unit == "rad" else f"+-{amplitude:.3g} {unit}"
    return (
        f"limit cycle near {cycle['frequency_hz']:.3g} Hz, {size} ({cycle['output_reversals']} "
        f"tip reversals for the reference's {cycle['reference_reversals']})"
    )


__all__ = [
    "EXTRA_CYCLES_PER_S",
    "EXTRA_OVER_REFERENCE",
    "SWING_SHARE",
    "describe",
    "limit_cycle",
    "reversals",
]
