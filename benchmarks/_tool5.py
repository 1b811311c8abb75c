"""The shared da Vinci tool 5 (MRDLab; ODbL/DbCL), read as a user would, and its sessions.

Fifty runs (a 30 deg sine at 0.1-0.5 Hz against ten resistive torque levels), read with every
column the log has for the drive: ``read_log(path, time="t", input="motor", output="jaw",
load="jaw_torque")``. The data is read from its folder at run time, never copied.

Sessions: the jaw encoder is relative and its zero jumps in blocks of runs, as if zeroed anew
per recording session. The runs are taken in their recording order (frequency, then load:
the order of the files) and a session ends where the output's offset against one reference
model jumps by more than :data:`JUMP` rad from one run to the next
(``ts.session.session_shift``; the reference: Loaded(Backlash) fitted on the first three
runs of the 0.1 Hz block at loads 10, 50 and 100 %). Within a session the offset moves with
the load by at most 0.005 rad between neighbours; the jumps are 0.02-0.08 rad.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

import tendonsheath as ts
from tendonsheath.apps.compare import _settle
from tendonsheath.apps.inverse_error import offline_inverse
from tendonsheath.apps.session import session_shift

DEFAULT = Path(__file__).resolve().parents[2] / "shared" / "data" / "davinci_tool5"
FREQS = (0.1, 0.2, 0.3, 0.4, 0.5)
LOADS = tuple(range(10, 101, 10))
#: an offset step between consecutive runs that starts a new session (rad)
JUMP = 0.015


def run_name(f: float, load: int) -> str:
    return f"f{f:.2f}Hz_load{load:03d}"


NAMES = [run_name(f, p) for f in FREQS for p in LOADS]  # the recording order


def read(data: Path, name: str) -> ts.io.Log:
    return ts.io.read_log(
        data / f"{name}.csv", time="t", input="motor", output="jaw", load="jaw_torque"
    )


def read_all(data: Path) -> dict[str, ts.io.Log]:
    return {n: read(data, n) for n in NAMES}


def sessions(logs: dict[str, ts.io.Log]) -> list[list[str]]:
    """The runs split into sessions at the offset jumps (see the module's doc)."""
    ref = [logs[run_name(0.1, p)] for p in (10, 50, 100)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = ts.identify(ts.models.Loaded(ts.models.Backlash()), recordings=ref,
                            progress=False).model  # fmt: skip
    offsets = [session_shift(model, logs[n]).shifts["offset"].value for n in NAMES]
    out: list[list[str]] = [[NAMES[0]]]
    for prev, cur, name in zip(offsets, offsets[1:], NAMES[1:], strict=False):
        if abs(cur - prev) > JUMP:
            out.append([])
        out[-1].append(name)
    return out


def predict(model, log) -> np.ndarray:
    if isinstance(model, ts.models.Loaded):
        return np.asarray(model.simulate(log.t, log.x, load=log.load), dtype=float)
    return np.asarray(model.simulate(log.t, log.x), dtype=float)


def rmse(e: np.ndarray, zero_free: bool = False) -> float:
    e = e - np.mean(e) if zero_free else e
    return float(np.sqrt(np.mean(e * e)))


def scores(model, log, start: int | None = None) -> dict[str, float]:
    """Forward and inverse rmse on one run, plain (abs) and with the mean error removed
    (zero_free), from ``start`` (default: the input's first reversal) on. Inverse: the
    commands the model's inverse sends for the recorded output (offline_inverse, with the
    run's load for a Loaded model) against the input that produced it."""
    k = _settle(log.x) if start is None else max(start, _settle(log.x))
    fwd = (predict(model, log) - log.y)[k:]
    commands, _ = offline_inverse(model, log.t, log.y, None, log.load)
    inv = (np.asarray(commands, dtype=float) - log.x)[k:]
    return {
        "forward_abs": rmse(fwd),
        "forward_zero_free": rmse(fwd, True),
        "inverse_abs": rmse(inv),
        "inverse_zero_free": rmse(inv, True),
    }


def first_cycle(log: ts.io.Log, seconds: float) -> tuple[tuple, np.ndarray, int]:
    """The first ``seconds`` of a run as a (t, x, y) tuple and its load: a session's short
    re-calibration log; and the sample where the rest of the run starts."""
    n = int(np.searchsorted(log.t, log.t[0] + seconds))
    return (log.t[:n], log.x[:n], log.y[:n]), log.load[:n], n
