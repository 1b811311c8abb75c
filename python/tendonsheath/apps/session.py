"""Sessions: whether a new log comes from the drive state a model was fitted in, and a short
re-calibration that absorbs the difference.

Real drives come in sessions. Between them the encoders are re-zeroed (the tip's zero is
arbitrary on a relative encoder), a tendon is re-tensioned, a sheath takes another shape:
the loop moves (an offset), stretches (a gain) or widens (a dead band). A model fitted once
then misses by the shift, which can be larger than everything else it gets wrong.

Both functions refit those few parameters on the new log and keep every other one:

- the output's offset and gain, as the map of a :class:`~tendonsheath.models.Scaled` model
  around the fitted one (inside a Loaded model, around its base): y' = m + o + g (y - m),
  m the model's mean prediction over the log, so that the offset o is the loop's move at its
  middle and the gain g is independent of it;
- the dead band where the model has one: Backlash's and BoucWenBacklash's B_r and B_l
  widened together by d (a play of half-width d in front of the model: exactly so for a
  backlash), a Loaded model's slack moved by d; d in the input's unit;
- by name (``refit=``), a Loaded model's load gain (the tendon's stretch per unit load,
  which re-tensioning changes), from logs at two loads or more (a load that follows the
  motion within one run, as a brake's does, would be taken for part of the loop).

The fit is least squares on the simulated output (each log scored from its input's first
reversal on), from no shift at all. :func:`session_shift` reports each one with its standard
error (Newey-West: the residuals of a drive are correlated over a cycle, so the plain ones
would be far too small; :mod:`tendonsheath.identify.newey_west`); a shift is *significant*
when it is more than twice its standard error from none, and the log is from the *same
state* unless the fit lowers the rmse by more than :data:`MATERIAL` (a shift too small to
matter is not one to act on). :func:`recalibrate` returns the refitted model, which
predicts, inverts, saves and exports like the model it came from.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..identify.fit import simulate_model
from ..identify.newey_west import newey_west
from ..models import HysteresisModel, Loaded, Scaled
from .compare import SETTLE_FRACTION, _as_recs, _settle

#: the share of the rmse the significant shifts must remove to call the log another state
MATERIAL = 0.1
#: what recalibrate refits by default
TERMS = ("offset", "gain", "dead band")
#: what it can refit: the load gain (a Loaded model's) by name, from logs at two loads or more
REFITTABLE = (*TERMS, "load gain")
#: a load gain is refitted only where the logs determine it: its standard error within this
#: share of the model's own load gain
LOAD_GAIN_SPREAD = 0.25
UNITS = {
    "offset": "output unit",
    "gain": "ratio - 1",
    "dead band": "input unit, half-width",
    "load gain": "output unit per load unit",
}


@dataclass(frozen=True)
class Shift:
    """One measured shift: its estimate, standard error and unit, and whether it is
    significant (more than twice its standard error beyond what the model's own logs show).

    Parameters
    ----------
    name : str
        "offset", "gain" or "dead band".
    value : float
        The change: the output's offset at its middle (output unit), the gain's change
        (the ratio less 1), the dead band's (half-width, input unit; > 0 wider).
    se : float
        Its standard error (Newey-West), same unit.
    unit : str
        The unit in words.
    tolerance : float, default 0.0
        How far the model's own logs already stray (the largest such shift on the reference
        logs of :func:`session_shift`; 0 without them).
    """

    name: str
    value: float
    se: float
    unit: str
    tolerance: float = 0.0

    @property
    def significant(self) -> bool:
        """More than two standard errors beyond the tolerance."""
        return bool(abs(self.value) > self.tolerance + 2.0 * self.se)

    def text(self) -> str:
        """The shift in one line.

        Returns
        -------
        str
            Name, value +/- two standard errors, unit and whether it is significant.
        """
        mark = "significant" if self.significant else "within its noise"
        own = f"; its own logs stray {self.tolerance:.2g}" if self.tolerance else ""
        return f"{self.name}: {self.value:+.4g} +/- {2 * self.se:.2g} {self.unit} ({mark}{own})"


@dataclass(frozen=True)
class SessionShift:
    """What :func:`session_shift` found on a log.

    Parameters
    ----------
    shifts : dict of str to Shift
        The offset, the gain and the dead band's change.
    rmse : float
        The model's rmse on the log (from the input's first reversal on).
    rmse_absorbed : float
        The rmse once the shifts are refitted.
    samples : int
        The samples scored.
    notes : list of str
        What was not measured, and why.
    """

    shifts: dict[str, Shift]
    rmse: float
    rmse_absorbed: float
    samples: int
    notes: list[str] = field(default_factory=list)

    @property
    def same_state(self) -> bool:
        """Whether the log looks like the model's drive state: no significant shift, or the
        refitted ones lower the rmse by less than :data:`MATERIAL`."""
        if not any(s.significant for s in self.shifts.values()):
            return True
        return bool(self.rmse_absorbed > (1.0 - MATERIAL) * self.rmse)

    def text(self) -> str:
        """The finding in a few lines.

        Returns
        -------
        str
            The verdict, the rmse before and after, and each shift.
        """
        verdict = (
            "same drive state"
            if self.same_state
            else "the drive state has shifted: run ts.recalibrate on a few seconds of motion"
        )
        lines = [
            f"{verdict} (rmse {self.rmse:.4g}; {self.rmse_absorbed:.4g} with the shifts "
            f"refitted; {self.samples} samples)"
        ]
        lines += ["  " + s.text() for s in self.shifts.values()]
        return "\n".join(lines + ["  " + n for n in self.notes])

    def __str__(self) -> str:
        return self.text()


@dataclass(frozen=True)
class Recalibration:
    """What :func:`recalibrate` did.

    Parameters
    ----------
    model : HysteresisModel
        The re-calibrated model (the given one with the refitted parameters).
    refitted : dict of str to float
        Each refitted parameter's new value, by the new model's parameter name.
    rmse_before : float
        The given model's rmse on the log (from the input's first reversal on).
    rmse_after : float
        The re-calibrated model's.
    notes : list of str
        What could not be refitted, and why.
    """

    model: HysteresisModel
    refitted: dict[str, float]
    rmse_before: float
    rmse_after: float
    notes: list[str] = field(default_factory=list)

    def text(self) -> str:
        """The re-calibration in a few lines.

        Returns
        -------
        str
            The rmse before and after and the refitted values.
        """
        values = ", ".join(f"{k} = {v:.5g}" for k, v in self.refitted.items())
        lines = [f"re-calibrated: rmse {self.rmse_before:.4g} -> {self.rmse_after:.4g} ({values})"]
        return "\n".join(lines + self.notes)

    def __str__(self) -> str:
        return self.text()


def _recordings(logs: Any, load: Any) -> list:
    recs = _as_recs(logs)
    if not recs:
        raise ValueError("give a log (a Log or a (t, x, y) tuple), or a list of them")
    if load is not None:
        if len(recs) != 1:
            raise ValueError("load= goes with one log; give logs that carry their load")
        (rec,) = recs
        load = np.asarray(load, dtype=float)
        if load.shape != rec.x.shape or not np.all(np.isfinite(load)):
            raise ValueError(f"load: {rec.n} finite values are needed (got shape {load.shape})")
        rec.load = load
    return recs


def _predict(model: HysteresisModel, rec) -> np.ndarray:
    if isinstance(model, Loaded) and rec.load is None:
        raise ValueError(
            "this model takes a measured load: give a log read with load=... (or load=)"
        )
    y = np.asarray(simulate_model(model, rec.t, rec.x, rec.angle_input, rec.load), dtype=float)
    if not np.all(np.isfinite(y)):
        raise ValueError("the model's prediction on this log is not finite")
    return y


def _branch(x: np.ndarray) -> np.ndarray:
    """+1 where the input rises, -1 where it falls: the direction of its last move by more
    than SETTLE_FRACTION of its range (so that noise at a turn does not flip it).

    Parameters
    ----------
    x : numpy.ndarray of float
        The input.

    Returns
    -------
    numpy.ndarray of float
        +1 or -1 per sample (+1 before the first such move).
    """
    tol = SETTLE_FRACTION * float(np.ptp(x))
    out = np.ones(x.size)
    anchor, sign = float(x[0]), 1.0
    for i, v in enumerate(x.tolist()):
        if sign > 0 and v < anchor - tol:
            sign = -1.0
        elif sign < 0 and v > anchor + tol:
            sign = 1.0
        anchor = max(anchor, v) if sign > 0 else min(anchor, v)
        out[i] = sign
    return out


def _with_map(model: HysteresisModel) -> tuple[HysteresisModel, str]:
    """The model with a Scaled map where the output's offset and gain go (the model's own
    map, a Loaded model's base's, or a new one around it) and the prefix of its names."""
    if isinstance(model, Scaled):
        return model, ""
    if isinstance(model, Loaded):
        if isinstance(model.base, Scaled):
            return model, "base."
        return _loaded_with(model, Scaled(model.base)), "base."
    mapped = Scaled(model)
    mapped.input_range = getattr(model, "input_range", None)
    return mapped, ""


def _loaded_with(model: Loaded, base: HysteresisModel) -> Loaded:
    new = Loaded(base, **model.terms)
    new.input_range = model.input_range
    return new


def _dead_band_names(model: HysteresisModel) -> list[str]:
    """The parameters that set the dead band: a Loaded model's slack, else every B_r and B_l
    (Backlash, BoucWenBacklash, inside a Scaled map or a Chain); none for the others."""
    if isinstance(model, Loaded):
        return ["slack"]
    return [n for n in model.params if n.rsplit(".", 1)[-1] in ("B_r", "B_l")]


@dataclass(frozen=True)
class _Refitted:
    """The shared least-squares refit: the new model, each fitted shift with its standard
    error, and the rmse before and after on the log."""

    model: HysteresisModel
    start: HysteresisModel  # the given model with the map the shifts went into
    shifts: dict[str, Shift]
    rmse_before: float
    rmse_after: float
    samples: int
    notes: list[str]


class _Shifted:
    """The model with the shifts ``names`` applied, on the scored samples of the recordings
    (each from its input's first reversal on)."""

    def __init__(self, model: HysteresisModel, recs: list, refit) -> None:
        self.recs, self.starts = recs, [_settle(r.x) for r in recs]
        for r, k in zip(recs, self.starts, strict=True):
            direction = _branch(r.x)
            if np.ptp(r.x) <= 0 or np.all(direction[k:] == direction[-1]):
                raise ValueError("the log's input must move both ways for a shift to be measured")
        self.mapped, self.prefix = _with_map(model)
        values = self.mapped.params
        self.map0 = values[self.prefix + "output_offset"], values[self.prefix + "output_gain"]
        self.initial = self.predict(model)  # the model as given, on the scored samples
        self.mean = float(np.mean(self.initial))
        bands = _dead_band_names(self.mapped) if "dead band" in refit else []
        self.band0 = {n: float(values[n]) for n in bands}
        # a B inside a Scaled map is in the map's normalised input unit
        inner = bands and bands[0].startswith("inner.")
        self.unit = float(values["input_scale"]) if inner else 1.0
        loads = [r.load for r in recs if r.load is not None]
        varied = isinstance(model, Loaded) and bool(loads) and np.ptp(np.concatenate(loads)) > 0
        self.load_gain0 = float(values["gain"]) if varied and "load gain" in refit else None
        self.names = [n for n in ("offset", "gain") if n in refit] + (["dead band"] * bool(bands))
        self.names += ["load gain"] if self.load_gain0 is not None else []

    def predict(self, model: HysteresisModel) -> np.ndarray:
        parts = [_predict(model, r)[k:] for r, k in zip(self.recs, self.starts, strict=True)]
        return np.concatenate(parts)

    @property
    def size(self) -> int:
        return sum(r.n - k for r, k in zip(self.recs, self.starts, strict=True))

    def measured(self) -> np.ndarray:
        return np.concatenate([r.y[k:] for r, k in zip(self.recs, self.starts, strict=True)])

    def build(self, theta: np.ndarray) -> HysteresisModel:
        v = dict(zip(self.names, theta.tolist(), strict=True))
        o, g = v.get("offset", 0.0), v.get("gain", 1.0)
        offset0, gain0 = self.map0
        changes = {
            self.prefix + "output_offset": self.mean + o + g * (offset0 - self.mean),
            self.prefix + "output_gain": g * gain0,
        }
        changes |= {n: b + v.get("dead band", 0.0) / self.unit for n, b in self.band0.items()}
        if self.load_gain0 is not None:
            changes["gain"] = self.load_gain0 + v["load gain"]
        return self.mapped.with_params(**changes)

    def notes(self, model: HysteresisModel, refit) -> list[str]:
        out = []
        if "dead band" in refit and not self.band0:
            out.append(f"dead band: kept ({_kind(model)} has no dead-band parameter)")
        if "load gain" in refit and self.load_gain0 is None:
            if isinstance(model, Loaded):
                out.append("load gain: kept (the load does not vary in the logs)")
            else:
                out.append(f"load gain: kept ({_kind(model)} takes no load)")
        return out


def _refit(model: HysteresisModel, recs: list, refit) -> _Refitted:
    """Fit the ``refit`` shifts of ``model`` on the recordings (see the module's doc); a
    load gain the logs do not determine (its standard error over :data:`LOAD_GAIN_SPREAD`
    of the model's own) is kept, and the others refitted without it."""
    problem, shifts, before, after, fitted = _least_squares(_Shifted(model, recs, refit))
    shift = shifts.get("load gain")
    if shift is not None and shift.se > LOAD_GAIN_SPREAD * abs(problem.load_gain0):
        kept = tuple(n for n in refit if n != "load gain")
        if not kept:
            raise ValueError("the logs' load does not vary enough to refit the load gain")
        again = _refit(model, recs, kept)
        note = (f"load gain: kept (the logs' load varies too little to determine it: "
                f"+/- {2 * shift.se:.2g} {UNITS['load gain']})")  # fmt: skip
        return replace(again, notes=[*again.notes, note])
    new, notes = problem.build(fitted), problem.notes(model, refit)
    return _Refitted(new, problem.mapped, shifts, before, after, problem.size, notes)


def _least_squares(problem: _Shifted):
    """(problem, shifts, rmse before, rmse after, the fitted vector)."""
    from scipy.optimize import least_squares

    recs, names, y = problem.recs, problem.names, problem.measured()

    def residual(theta: np.ndarray) -> np.ndarray:
        return problem.predict(problem.build(theta)) - y

    start = {"offset": 0.0, "gain": 1.0, "dead band": 0.0, "load gain": 0.0}
    low = dict.fromkeys(start, -np.inf) | {"gain": 0.2}
    low["dead band"] = -problem.unit * min(problem.band0.values(), default=0.0)
    x_span = float(np.ptp(np.concatenate([r.x for r in recs])))
    loads = [np.ptp(r.load) for r in recs if r.load is not None]
    scale = {"offset": float(np.ptp(y)), "gain": 0.1, "dead band": 0.01 * x_span,
             "load gain": float(np.ptp(y)) / max(max(loads, default=1.0), 1e-12)}  # fmt: skip
    found = least_squares(
        residual,
        np.array([start[n] for n in names]),
        bounds=([low[n] for n in names], [5.0 if n == "gain" else np.inf for n in names]),
        x_scale=[scale[n] or 1.0 for n in names],
        diff_step=1e-4,
    )
    sizes = [r.n - k for r, k in zip(recs, problem.starts, strict=True)]
    periods = None if any(r.t is None for r in recs) else [_period(r.t) for r in recs]
    se, _, _ = newey_west(found.jac, found.fun, len(names), None, sizes, periods)
    shifts = {
        n: Shift(n, float(v - start[n]), float(e), UNITS[n])
        for n, v, e in zip(names, found.x, se, strict=True)
    }
    before = float(np.sqrt(np.mean((problem.initial - y) ** 2)))
    after = float(np.sqrt(np.mean(found.fun**2)))
    return problem, shifts, before, after, found.x


def _period(t: np.ndarray) -> float:
    return float(np.median(np.diff(t)))


def _kind(model: HysteresisModel) -> str:
    inner = model.inner if isinstance(model, Scaled) else model
    return type(inner).__name__


def session_shift(
    model: HysteresisModel, log: Any, *, reference: Any = None, load: Any = None
) -> SessionShift:
    """Whether ``log`` comes from the drive state ``model`` was fitted in: its output's
    offset and gain and its dead band, refitted on the log with standard errors (see the
    module's doc).

    A model never fits its own logs exactly: from one run to the next (another load, another
    speed) its offset strays too. ``reference`` (the logs the model was fitted on, or others
    of its session) measures how far: each shift is then significant only beyond the
    largest the reference logs show (``Shift.tolerance``), so that a run of the same session
    is not taken for a new one.

    Parameters
    ----------
    model : HysteresisModel
        A fitted model.
    log : Log, tuple or list of them
        The new recording(s) (t, x, y[, curve angle]); their load where the model takes one.
    reference : Log, tuple or list of them, optional
        Logs of the model's own session.
    load : array_like of float, optional
        The measured load of ``log``, where it does not carry it.

    Returns
    -------
    SessionShift
        The shifts and the verdict (``same_state``).

    Raises
    ------
    ValueError
        No recording, a missing load, a prediction that is not finite, or an input that
        does not move both ways.
    """
    found = _refit(model, _recordings(log, load), TERMS)
    shifts = found.shifts
    if reference is not None:
        own = [_refit(model, [r], TERMS).shifts for r in _recordings(reference, None)]
        shifts = {
            name: replace(s, tolerance=max(abs(o[name].value) for o in own if name in o))
            for name, s in shifts.items()
        }
    return SessionShift(shifts, found.rmse_before, found.rmse_after, found.samples, found.notes)


def recalibrate(
    model: HysteresisModel,
    log: Any,
    *,
    refit: tuple[str, ...] | list[str] = TERMS,
    load: Any = None,
) -> Recalibration:
    """Refit a few parameters of ``model`` on a short log of a new session and keep every
    other one: the output's offset and gain, and the dead band where the model has one (see
    the module's doc). A few seconds of motion that reverse a few times are enough.

    Parameters
    ----------
    model : HysteresisModel
        A fitted model.
    log : Log, tuple or list of them
        The new session's short recording(s) (t, x, y[, curve angle]); their load where the
        model takes one (at two loads or more for the load gain).
    refit : sequence of str, default ("offset", "gain", "dead band")
        What to refit; "load gain" too, by name.
    load : array_like of float, optional
        The measured load, where the log does not carry it.

    Returns
    -------
    Recalibration
        The re-calibrated model (``.model``), the refitted values and the rmse before and
        after on the log.

    Raises
    ------
    ValueError
        Unknown names in ``refit``, no recording, a missing load, or an input that does
        not move both ways.
    """
    unknown = [name for name in refit if name not in REFITTABLE]
    if unknown or not refit:
        raise ValueError(f"refit: one or more of {list(REFITTABLE)} (got {list(refit)})")
    found = _refit(model, _recordings(log, load), tuple(refit))
    refitted = {n: float(found.model.params[n]) for n in _changed(found.model, found.start)}
    return Recalibration(found.model, refitted, found.rmse_before, found.rmse_after, found.notes)


def _changed(new: HysteresisModel, old: HysteresisModel) -> list[str]:
    return [n for n, v in new.params.items() if np.any(np.asarray(v) != np.asarray(old.params[n]))]


__all__ = ["MATERIAL", "TERMS", "Recalibration", "SessionShift", "Shift", "recalibrate",
           "session_shift"]  # fmt: skip
