"""identify_coupled on several recordings: the coupling and its Newey-West SE against the
truth (C[1,0] = 0.25, C[0,1] = 0) on benchmarks/coupled.py's wrist (two realistic pull-pull
drives, outside every model class, noisy quantised encoders).

* split: one 9 s design at 500 Hz (frequencies drawn per seed) cut in three 3 s sessions, the
  wrist run from rest in each, fitted together (warm-up 250 samples per session).
* rates: session A (6 s at 1 kHz) and session B (8 s at 400 Hz, other frequencies and
  amplitudes), each alone and both together (warm-up 400 samples per session); B is given
  twice: 0.45/0.71 Hz at 0.9/1.0 rad (the test's) and 0.29/0.53 Hz at 0.7/0.6 rad.

The Newey-West bandwidth is a time (Andrews' rule pooled over the sessions in seconds), given
in lags of each session at its own rate; each line ends with joint 1's and joint 0's (the rows
of C[1,0] and C[0,1]).

    .venv/bin/python benchmarks/coupled_recordings.py [--seeds 6]
"""

from __future__ import annotations

import argparse
import warnings

import numpy as np
from coupled import C10, wrist

import tendonsheath as ts
from tendonsheath.identify import identify_coupled


def commands(t: np.ndarray, f0: float, f1: float, a0: float, a1: float) -> np.ndarray:
    """Both joints excited independently, slowly modulated (tests/test_coupled_recordings)."""
    span = t[-1] - t[0]
    return np.column_stack(
        [
            a0 * np.sin(2 * np.pi * f0 * t) * (1 - 0.5 * np.sin(np.pi * t / span)),
            a1 * np.sin(2 * np.pi * f1 * t + 1.0) * (1 - 0.4 * np.cos(np.pi * t / span)),
        ]
    )


def session(seed: int, t: np.ndarray, x: np.ndarray) -> tuple:
    return t, x, wrist(seed).simulate(t - t[0], x).measured


def fit(recordings: list, warmup: int):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
        return identify_coupled(
            ts.models.BoucWenBacklash, recordings=recordings, warmup=warmup, seed=0
        )


def line(name: str, f) -> str:
    c10, s10, c01, s01 = (
        f.coupling[1, 0],
        f.coupling_se[1, 0],
        f.coupling[0, 1],
        f.coupling_se[0, 1],
    )
    return (
        f"{name:10s} C[1,0] {c10:.5f} +/- {s10:.5f} ({(c10 - C10) / s10:+.2f} SE)   "
        f"C[0,1] {c01:+.5f} +/- {s01:.5f} ({c01 / s01:+.2f} SE)   {f.seconds:.1f} s   "
        f"NW bandwidth {f.lag_s[1]:.2f} / {f.lag_s[0]:.2f} s"
    )


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=6)
    args = parser.parse_args(argv)
    print("split: one design in three sessions")
    for seed in range(args.seeds):
        rng = np.random.default_rng(seed)
        t = np.arange(0.0, 9.0, 2e-3)
        x = commands(t, rng.uniform(0.6, 0.8), rng.uniform(0.9, 1.2), 1.1, 0.9)
        pieces = np.array_split(np.arange(t.size), 3)
        print(line(f"seed {seed}", fit([session(seed, t[p], x[p]) for p in pieces], 250)))
    t_a, t_b = np.arange(0.0, 6.0, 1e-3), np.arange(0.0, 8.0, 2.5e-3)
    a = session(10, t_a, commands(t_a, 0.37, 0.63, 1.1, 0.9))
    for design in ((0.45, 0.71, 0.9, 1.0), (0.29, 0.53, 0.7, 0.6)):
        b = session(20, t_b, commands(t_b, *design))
        print(f"rates: B's frequencies (Hz) and amplitudes (rad) {design}")
        for name, recs in (("A 1 kHz", [a]), ("B 400 Hz", [b]), ("A + B", [a, b])):
            print(line(name, fit(recs, 400)))


if __name__ == "__main__":
    main()
