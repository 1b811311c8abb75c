"""Iterative learning control (ILC): a feedforward correction learned over repeated trials.

A surgeon repeats a motion and the tool tip's error repeats with it. Trial j runs the
feedforward plus a correction table u_j (:class:`LearnedFeedforward`) and measures the tip; the
next table is

    u_{j+1} = Q(u_j + gain * shift_lead(e_j)),    e_j = y_d - y_measured (NaN: 0, no update)

where ``shift_lead`` advances the error by ``lead`` samples (the loop's delay and lag) and Q is a
zero-phase Butterworth low-pass at ``cutoff_hz`` (``scipy.signal.sosfiltfilt``: the robustness
filter). With the loop's frequency response P(f) from the correction to the measured tip, the
tables converge monotonically (in the 2-norm, at every frequency) when

    |Q(f)| |1 - gain e^{j 2 pi f lead dt} P(f)| <= rho < 1  for every f,

which :meth:`IterativeLearning.from_dynamics` designs for: the largest cutoff for which some
lead (0..50 samples) and gain keep ``|1 - gain L P| <= rho`` below the cutoff and Q's attenuation
keeps the product below rho above it. The error converges to what Q lets through (its
components above the cutoff and the trial-varying noise), not to zero.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from .._util.args import integer, number
from .._util.pyobject import PythonObject
from .._util.typing import ArrayLike, FloatArray
from ._kinds import require_feedforward
from .learned_feedforward import LearnedFeedforward
from .limits import LimitsLike

_STALL_EPS = 1e-3  # the error "stops decreasing": rmse ratio above 1 - this, two trials running
_DIVERGENCE = 1.10  # divergence: the rmse grew by more than 10 % over two trials


@dataclass(frozen=True)
class TrialRecord:
    """What one trial gave: its error, against the trial before.

    Parameters
    ----------
    trial : int
        The trial's number (0: the run with the initial table).
    rmse : float
        Root mean square of the tip error y_d - y_measured (finite samples only).
    ratio : float
        rmse over the previous trial's (nan for trial 0).
    converging : bool
        Whether the error decreased (ratio < 1; True for trial 0).
    max_abs_correction : float
        The largest |correction| of the table this trial ran.
    """

    trial: int
    rmse: float
    ratio: float
    converging: bool
    max_abs_correction: float

    def as_dict(self) -> dict[str, Any]:
        """The record as a dict.

        Returns
        -------
        dict
            Its fields.
        """
        return asdict(self)


@dataclass(frozen=True)
class LearningDesign:
    """A learning law designed from the loop's frequency response, and its margins.

    Parameters
    ----------
    lead : int
        Samples the error is advanced by.
    gain : float
        Learning gain (its sign that of the loop's low-frequency response).
    cutoff_hz : float
        Corner of the zero-phase low-pass Q (Hz).
    rho : float
        The achieved max of |1 - gain e^{j 2 pi f lead dt} P(f)| for f <= cutoff_hz.
    contraction : float
        The achieved max over all f of |Q(f)| |1 - gain e^{j 2 pi f lead dt} P(f)|: the
        factor the tables' distance to their limit shrinks by per trial, at least.
    rho_target : float
        The margin asked for (both maxima <= rho_target).
    dt : float
        The sample time (s).
    order : int
        The Butterworth order of Q (applied forward and backward: twice that in magnitude).
    known_up_to_hz : float, optional
        The highest cutoff searched when the response is known only up to it: an identified
        loop with no resonance within its excitation's band (the band's upper edge).
    """

    lead: int
    gain: float
    cutoff_hz: float
    rho: float
    contraction: float
    rho_target: float
    dt: float
    order: int
    known_up_to_hz: float | None = None

    def as_dict(self) -> dict[str, Any]:
        """The design as a dict.

        Returns
        -------
        dict
            Its fields.
        """
        return asdict(self)

    def summary(self) -> str:
        """One line: the law and its margins.

        Returns
        -------
        str
            lead, gain, cutoff and the achieved rho.
        """
        return (
            f"ILC design: lead {self.lead} samples ({1e3 * self.lead * self.dt:.3g} ms), "
            f"gain {self.gain:.3g}, Q cutoff {self.cutoff_hz:.3g} Hz (order {self.order}, "
            f"zero-phase); |1 - gain L P| <= {self.rho:.3f} below the cutoff, "
            f"|Q (1 - gain L P)| <= {self.contraction:.3f} everywhere "
            f"(target {self.rho_target:g})"
            + (
                f"; cutoff searched up to {self.known_up_to_hz:.3g} Hz, the excitation band's "
                "upper edge (no resonance identified within the band)"
                if self.known_up_to_hz is not None
                else ""
            )
        )


class IterativeLearning(PythonObject):
    """Learns a feedforward correction table over repeated trials of one trajectory.

    Parameters
    ----------
    feedforward : compensator
        The feedforward whose command the table corrects (any with ``reset()`` and
        ``step(y_d, dt)``).
    t : array_like of float, shape (n,)
        The trajectory's sample times (s), uniformly spaced (the table's time step).
    reference : array_like of float, shape (n,)
        The desired output y_d at those times.
    gain : float, default 0.5
        Learning gain (the correction per unit of error).
    lead : int, default 0
        Samples the error is advanced by (the loop's delay and lag), >= 0.
    cutoff_hz : float or None, default 10.0
        Corner of the zero-phase low-pass Q (Hz), below the Nyquist frequency; None: no Q.
    max_trials : int, default 10
        Learning trials after the first run (trial 0, with the initial table): the learning
        stops once trial ``max_trials`` is measured.
    tolerance : float or None, optional
        Stop once the error's rmse falls below it.
    order : int, default 2
        Butterworth order of Q.
    initial_table : array_like of float, shape (n,), optional
        The table of trial 0 (zeros by default).
    hold_last : bool, default True
        The compensators' behaviour past the table's end (see LearnedFeedforward).
    limits : CommandLimits, tuple, dict or None, optional
        The compensators' command limits.

    Raises
    ------
    ValueError
        t not uniformly spaced, a length mismatch, or a setting out of range.

    Notes
    -----
    Stop rule (:attr:`stopped`): after ``max_trials`` learning trials; when the rmse falls
    below ``tolerance`` (:attr:`converged`); when the error stops decreasing (rmse ratio above
    1 - 1e-3 for two trials running; :attr:`converged` too, at the floor the loop allows); or
    on divergence (the rmse grew by more than 10 % over two trials: :attr:`diverged`). Once
    stopped, :meth:`compensator` gives the best table measured (:meth:`best_compensator`).
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    feedforward: Any
    t: FloatArray
    reference: FloatArray
    dt: float
    gain: float
    lead: int
    order: int
    cutoff_hz: float | None
    max_trials: int
    tolerance: float | None
    table: FloatArray
    tables: list[FloatArray]
    history: list[TrialRecord]
    design: LearningDesign | None

    def __init__(
        self,
        feedforward: Any,
        t: ArrayLike,
        reference: ArrayLike,
        gain: float = 0.5,
        lead: int = 0,
        cutoff_hz: float | None = 10.0,
        max_trials: int = 10,
        tolerance: float | None = None,
        order: int = 2,
        initial_table: ArrayLike | None = None,
        hold_last: bool = True,
        limits: LimitsLike = None,
    ):
        from scipy import signal

        who = "IterativeLearning"
        require_feedforward(who, feedforward)
        ts = np.asarray(t, dtype=np.float64)
        ys = np.asarray(reference, dtype=np.float64)
        if ts.ndim != 1 or ys.shape != ts.shape or ts.size < 2:
            raise ValueError(
                f"{who}: t and reference must be 1-D of the same length >= 2 "
                f"(got {ts.shape} and {ys.shape})"
            )
        if not (np.all(np.isfinite(ts)) and np.all(np.isfinite(ys))):
            raise ValueError(f"{who}: t and reference must be finite")
        steps = np.diff(ts)
        dt = float(np.mean(steps))
        if not dt > 0 or np.max(np.abs(steps - dt)) > 1e-6 * dt:
            raise ValueError(f"{who}: t must be increasing and uniformly spaced (the table's step)")
        self.t, self.reference, self.dt = ts, ys, dt
        self.gain = number(who, "gain", gain)
        if not math.isfinite(self.gain) or self.gain == 0.0:
            raise ValueError(f"{who}: gain must be finite and nonzero (got {gain!r})")
        self.lead = integer(who, "lead", lead)
        if not 0 <= self.lead < ts.size:
            raise ValueError(f"{who}: lead must be in [0, {ts.size}) samples (got {lead})")
        self.order = integer(who, "order", order)
        if not 1 <= self.order <= 8:
            raise ValueError(f"{who}: order must be 1 to 8 (got {order})")
        self.cutoff_hz = None if cutoff_hz is None else number(who, "cutoff_hz", cutoff_hz)
        nyquist = 0.5 / dt
        if self.cutoff_hz is not None and not 0.0 < self.cutoff_hz < nyquist:
            raise ValueError(
                f"{who}: cutoff_hz must be in (0, {nyquist:g}) Hz, the Nyquist frequency "
                f"(got {cutoff_hz!r}); None: no filter"
            )
        self.max_trials = integer(who, "max_trials", max_trials)
        if self.max_trials < 1:
            raise ValueError(f"{who}: max_trials must be >= 1 (got {max_trials})")
        self.tolerance = None if tolerance is None else number(who, "tolerance", tolerance)
        if self.tolerance is not None and not self.tolerance > 0:
            raise ValueError(f"{who}: tolerance must be > 0 or None (got {tolerance!r})")
        table = np.zeros(ts.size) if initial_table is None else np.array(initial_table, float)
        if table.shape != ts.shape or not np.all(np.isfinite(table)):
            raise ValueError(f"{who}: initial_table must be {ts.size} finite values")
        self._sos = (
            None
            if self.cutoff_hz is None
            else signal.butter(self.order, self.cutoff_hz, fs=1.0 / dt, output="sos")
        )
        self.feedforward = feedforward
        self._hold_last, self._limits = hold_last, limits
        self.table = table
        self.tables = []  # the table each measured trial ran
        self.history = []
        self.design = None
        self._stopped = self._converged = self._diverged = False
        self.compensator()  # the settings are checked now, not at the first trial

    # -- the design from identified dynamics ------------------------------------------------
    @classmethod
    def from_dynamics(
        cls,
        feedforward: Any,
        t: ArrayLike,
        reference: ArrayLike,
        frequency_response: Callable[[FloatArray], ArrayLike] | Any,
        dt: float,
        rho: float = 0.8,
        max_lead: int = 50,
        min_cutoff_hz: float = 0.5,
        order: int = 2,
        max_trials: int = 10,
        tolerance: float | None = None,
        initial_table: ArrayLike | None = None,
        hold_last: bool = True,
        limits: LimitsLike = None,
    ) -> IterativeLearning:
        """The learning law designed from the loop's frequency response (lead, gain and cutoff
        chosen for monotone convergence with margin ``rho``; kept in ``design``).

        The design takes the largest cutoff f_c for which some lead in 0..``max_lead`` samples
        and gain (a grid of 0.1 to 1.5 over |P| at the lowest frequency, with the sign of its
        real part) give ``|1 - gain e^{j 2 pi f lead dt} P(f)| <= rho`` for every f <= f_c and
        ``|Q(f)| |1 - gain e^{j 2 pi f lead dt} P(f)| <= rho`` for every f up to the Nyquist
        frequency (Q: the zero-phase Butterworth at f_c, its digital response squared); among
        the laws at that cutoff, the one with the smallest rho below it.

        Parameters
        ----------
        feedforward : compensator
            The feedforward whose command the table corrects.
        t : array_like of float, shape (n,)
            The trajectory's sample times (s), uniformly spaced by ``dt``.
        reference : array_like of float, shape (n,)
            The desired output.
        frequency_response : callable or LoopDynamics
            f_hz (numpy array, Hz) -> complex array: the response from the correction added
            to the command to the measured tip (servo, tendons, resonance, sensor delay); or
            an identified :class:`~tendonsheath.identify.LoopDynamics` (its response at ``dt``).
        dt : float
            The sample time (s).
        rho : float, default 0.8
            The convergence margin, in (0, 1): the error (below the cutoff) shrinks at least
            by this factor per trial.
        max_lead : int, default 50
            The largest lead searched (samples).
        min_cutoff_hz : float, default 0.5
            Below this cutoff the design is refused (learning nothing useful).
        order : int, default 2
            Butterworth order of Q.
        max_trials, tolerance, initial_table, hold_last, limits
            As for :class:`IterativeLearning`.

        Returns
        -------
        IterativeLearning
            The learner, its ``design`` set.

        Raises
        ------
        ValueError
            No lead and gain make the learning monotonically convergent with a cutoff of at
            least ``min_cutoff_hz``, or a bad argument.
        """
        design = design_learning(
            frequency_response, dt, rho, max_lead, min_cutoff_hz, order, n_samples=np.size(t)
        )
        learner = cls(
            feedforward,
            t,
            reference,
            gain=design.gain,
            lead=design.lead,
            cutoff_hz=design.cutoff_hz,
            order=order,
            max_trials=max_trials,
            tolerance=tolerance,
            initial_table=initial_table,
            hold_last=hold_last,
            limits=limits,
        )
        if abs(learner.dt - design.dt) > 1e-6 * design.dt:
            raise ValueError(
                f"IterativeLearning.from_dynamics: t is spaced by {learner.dt:g} s, not dt = "
                f"{design.dt:g} s"
            )
        learner.design = design
        return learner

    # -- trials ----------------------------------------------------------------------------
    def compensator(self) -> LearnedFeedforward:
        """The compensator to run the next trial with (after a stop: the best table measured).

        Returns
        -------
        LearnedFeedforward
            The feedforward with the current table.
        """
        return LearnedFeedforward(
            self.feedforward, self.table, self.dt, self._hold_last, limits=self._limits
        )

    def best_compensator(self) -> LearnedFeedforward:
        """The compensator with the table of the trial with the smallest error (the current
        table before any trial was measured).

        Returns
        -------
        LearnedFeedforward
            The feedforward with the best table.
        """
        return LearnedFeedforward(
            self.feedforward, self.best_table, self.dt, self._hold_last, limits=self._limits
        )

    @property
    def best_table(self) -> FloatArray:
        """The table of the trial with the smallest rmse (a copy)."""
        if not self.history:
            return self.table.copy()
        best = min(range(len(self.history)), key=lambda i: self.history[i].rmse)
        return self.tables[best].copy()

    def update(self, measured: ArrayLike) -> TrialRecord:
        """Learn from the trial just run with :meth:`compensator`: its record, and the next table.

        Parameters
        ----------
        measured : array_like of float, shape (n,)
            The measured tip at the trajectory's times (NaN: a sensor dropout, no update there).

        Returns
        -------
        TrialRecord
            The trial's rmse and its ratio to the previous trial's.

        Raises
        ------
        RuntimeError
            The learning has stopped (see :attr:`stopped`).
        ValueError
            measured of the wrong length, or with no finite sample.
        """
        if self._stopped:
            raise RuntimeError(
                "IterativeLearning.update: the learning has stopped "
                f"({self.stop_reason}); run best_compensator()"
            )
        y = np.asarray(measured, dtype=np.float64)
        if y.shape != self.reference.shape:
            raise ValueError(
                f"IterativeLearning.update: measured must have {self.reference.size} samples "
                f"(got shape {y.shape})"
            )
        e = self.reference - y
        finite = np.isfinite(e)
        if not finite.any():
            raise ValueError("IterativeLearning.update: no finite sample in measured")
        rmse = float(np.sqrt(np.mean(e[finite] ** 2)))
        trial = len(self.history)
        prev = self.history[-1].rmse if self.history else math.nan
        ratio = rmse / prev if self.history and prev > 0 else math.nan
        record = TrialRecord(
            trial=trial,
            rmse=rmse,
            ratio=ratio,
            converging=not ratio >= 1.0,
            max_abs_correction=float(np.max(np.abs(self.table))),
        )
        self.history.append(record)
        self.tables.append(self.table.copy())
        self._apply_stop_rule()
        if self._stopped:
            self.table = self.best_table
        else:
            self.table = self.next_table(self.table, np.where(finite, e, 0.0))
        return record

    def next_table(self, table: ArrayLike, error: ArrayLike) -> FloatArray:
        """The learning law: Q(table + gain * shift_lead(error)).

        Parameters
        ----------
        table : array_like of float, shape (n,)
            The table the trial ran.
        error : array_like of float, shape (n,)
            Its error y_d - y (finite).

        Returns
        -------
        numpy.ndarray of float, shape (n,)
            The next table.
        """
        from scipy import signal

        e = np.asarray(error, dtype=np.float64)
        shifted = np.zeros_like(e)
        shifted[: e.size - self.lead] = e[self.lead :]  # advanced; nothing learned at the end
        u = np.asarray(table, dtype=np.float64) + self.gain * shifted
        if self._sos is None:
            return u
        padlen = min(3 * (2 * len(self._sos) + 1), u.size - 1)
        return signal.sosfiltfilt(self._sos, u, padlen=padlen)

    def learn(
        self, run_trial: Callable[[LearnedFeedforward], ArrayLike], progress: bool = False
    ) -> list[TrialRecord]:
        """Run trials until the stop rule: each ``run_trial(compensator)`` returns the measured
        tip (e.g. ``lambda c: ts.bench.run(plant, c, t, y_d, noise=sensor).measured``).

        Parameters
        ----------
        run_trial : callable
            LearnedFeedforward -> measured tip at the trajectory's times.
        progress : bool, default False
            Print one line per trial.

        Returns
        -------
        list of TrialRecord
            The history (also :attr:`history`).
        """
        while not self._stopped:
            record = self.update(run_trial(self.compensator()))
            if progress:
                print(
                    f"trial {record.trial}: rmse {record.rmse:.4g}"
                    + ("" if math.isnan(record.ratio) else f" (x{record.ratio:.3f})")
                )
        return self.history

    # -- the stop rule ----------------------------------------------------------------------
    def _apply_stop_rule(self) -> None:
        h = self.history
        last = h[-1]
        if len(h) >= 3 and last.rmse > _DIVERGENCE * h[-3].rmse:
            self._stopped, self._diverged, self.stop_reason = True, True, "diverged"
        elif self.tolerance is not None and last.rmse < self.tolerance:
            self._stopped, self._converged, self.stop_reason = True, True, "tolerance reached"
        elif len(h) >= 3 and all(r.ratio > 1.0 - _STALL_EPS for r in h[-2:]):
            self._stopped, self._converged, self.stop_reason = True, True, "stalled"
        elif last.trial >= self.max_trials:
            self._stopped, self.stop_reason = True, "max_trials"

    stop_reason: str = ""
    """Why the learning stopped ("" while it goes on): "max_trials", "tolerance reached",
    "stalled" (the error stopped decreasing) or "diverged"."""

    @property
    def stopped(self) -> bool:
        """Whether the stop rule has stopped the learning."""
        return self._stopped

    @property
    def converged(self) -> bool:
        """Whether it stopped at its floor: the rmse under ``tolerance``, or no longer decreasing
        (without diverging)."""
        return self._converged

    @property
    def diverged(self) -> bool:
        """Whether it stopped because the error grew (by > 10 % over two trials)."""
        return self._diverged

    def rmse(self) -> FloatArray:
        """Each measured trial's rmse.

        Returns
        -------
        numpy.ndarray of float
            One per trial.
        """
        return np.array([r.rmse for r in self.history])

    def __repr__(self) -> str:
        state = self.stop_reason or "learning"
        return (
            f"IterativeLearning(gain={self.gain:g}, lead={self.lead}, cutoff_hz={self.cutoff_hz}, "
            f"{len(self.history)} trials, {state})"
        )


def design_learning(
    frequency_response: Any,
    dt: float,
    rho: float = 0.8,
    max_lead: int = 50,
    min_cutoff_hz: float = 0.5,
    order: int = 2,
    n_samples: int | None = None,
    gains: Sequence[float] | None = None,
) -> LearningDesign:
    """Lead, gain and cutoff for monotone convergence (see
    :meth:`IterativeLearning.from_dynamics`).

    Parameters
    ----------
    frequency_response : callable or LoopDynamics
        f_hz -> complex response from the correction to the measured tip, or an object with
        ``frequency_response(f_hz, dt=...)`` (an identified LoopDynamics).
    dt : float
        Sample time (s).
    rho : float, default 0.8
        The margin, in (0, 1).
    max_lead : int, default 50
        The largest lead searched (samples).
    min_cutoff_hz : float, default 0.5
        The smallest acceptable cutoff (Hz).
    order : int, default 2
        Butterworth order of Q.
    n_samples : int, optional
        The trajectory's length (the lead is kept below it).
    gains : sequence of float, optional
        Gains relative to 1 / |P| at the lowest frequency (default 0.1 to 1.5).

    Returns
    -------
    LearningDesign
        The design.

    Raises
    ------
    ValueError
        No convergent design at or above min_cutoff_hz (the message says the best cutoff
        reached), or a bad argument.
    """
    who = "IterativeLearning.from_dynamics"
    dt = number(who, "dt", dt)
    rho = number(who, "rho", rho)
    if not dt > 0 or not math.isfinite(dt):
        raise ValueError(f"{who}: dt must be > 0 (got {dt!r})")
    if not 0.0 < rho < 1.0:
        raise ValueError(f"{who}: rho must be in (0, 1) (got {rho!r})")
    max_lead = integer(who, "max_lead", max_lead)
    if max_lead < 0:
        raise ValueError(f"{who}: max_lead must be >= 0 (got {max_lead})")
    if n_samples is not None:
        max_lead = min(max_lead, int(n_samples) - 1)
    nyquist = 0.5 / dt
    min_cutoff_hz = number(who, "min_cutoff_hz", min_cutoff_hz)
    if not 0 < min_cutoff_hz < 0.45 * nyquist:
        raise ValueError(f"{who}: min_cutoff_hz must be in (0, {0.45 * nyquist:g}) Hz")
    response = _response_of(who, frequency_response, dt)
    f_lo = min(0.01, 0.1 * min_cutoff_hz)
    freqs = np.unique(
        np.concatenate([np.geomspace(f_lo, nyquist, 1200), np.linspace(f_lo, nyquist, 800)])
    )
    p = np.asarray(response(freqs), dtype=np.complex128)
    if p.shape != freqs.shape or not np.all(np.isfinite(p)):
        raise ValueError(
            f"{who}: frequency_response must return one finite complex value per frequency "
            f"(got shape {p.shape} for {freqs.size} frequencies)"
        )
    p0 = p[0]
    if abs(p0) == 0.0:
        raise ValueError(f"{who}: the response is 0 at {f_lo:g} Hz: nothing to learn from")
    sign = 1.0 if p0.real >= 0 else -1.0
    rel = np.linspace(0.1, 1.5, 29) if gains is None else np.asarray(gains, dtype=np.float64)
    gain_grid = sign * rel / abs(p0)
    known = None  # an identified loop with no resonance in its band: known up to the band's edge
    if getattr(frequency_response, "resonance_identified", True) is False:
        known = float(frequency_response.design_limit_hz)
        if not known > min_cutoff_hz:
            raise ValueError(
                f"{who}: refused: the identified loop is known only up to {known:g} Hz (no "
                f"resonance within its excitation's band), below min_cutoff_hz = "
                f"{min_cutoff_hz:g} Hz"
            )
    top = 0.45 * nyquist if known is None else min(0.45 * nyquist, known)
    cutoffs = np.geomspace(min_cutoff_hz, top, 60)
    q_mag = _zero_phase_gains(order, cutoffs, freqs, dt)
    best = _best_lead_and_gain(freqs, p, gain_grid, cutoffs, q_mag, max_lead, dt, rho)
    if best is None:
        raise ValueError(
            f"{who}: refused: no lead in 0..{max_lead} samples and gain makes the learning "
            f"monotonically convergent (|Q (1 - gain L P)| <= {rho:g}) with a cutoff of at "
            f"least {min_cutoff_hz:g} Hz: the loop's delay or phase (a resonance, a sign "
            "change) is beyond what a lead can compensate; identify the loop again, close an "
            "inner loop first, or lower min_cutoff_hz"
        )
    c_i, _, lead, gain, pass_rho, whole = best
    return LearningDesign(
        lead=int(lead),
        gain=float(gain),
        cutoff_hz=float(cutoffs[c_i]),
        rho=float(pass_rho),
        contraction=float(whole),
        rho_target=rho,
        dt=dt,
        order=int(order),
        known_up_to_hz=known,
    )


def _zero_phase_gains(order: int, cutoffs: np.ndarray, freqs: np.ndarray, dt: float) -> np.ndarray:
    """|Q|^2 of the zero-phase Butterworth low-pass at each cutoff (rows) and frequency."""
    from scipy import signal

    q_mag = np.empty((cutoffs.size, freqs.size))
    for i, fc in enumerate(cutoffs):
        sos = signal.butter(order, fc, fs=1.0 / dt, output="sos")
        _, h = signal.sosfreqz(sos, worN=freqs, fs=1.0 / dt)
        q_mag[i] = np.abs(h) ** 2  # forward and backward
    return q_mag


def _response_of(who: str, frequency_response: Any, dt: float) -> Callable:
    """f_hz -> complex response: a callable, or a LoopDynamics sampled at the learning's dt."""
    identified = getattr(frequency_response, "frequency_response", None)
    if callable(identified):
        return lambda f: identified(f, dt=dt)
    if callable(frequency_response):
        return frequency_response
    raise TypeError(
        f"{who}: frequency_response must be a callable f_hz -> complex array or a LoopDynamics"
    )


def _best_lead_and_gain(freqs, p, gain_grid, cutoffs, q_mag, max_lead: int, dt: float,
                        rho: float) -> tuple | None:  # fmt: skip
    """(cutoff index, -rho, lead, gain, rho, contraction) of the highest convergent cutoff
    (then the least rho) over every lead and gain, or None."""
    best: tuple | None = None
    idx = np.searchsorted(freqs, cutoffs, side="right") - 1  # last f <= cutoff
    for lead in range(max_lead + 1):
        lp = np.exp(2j * np.pi * freqs * lead * dt) * p  # (F,)
        m = np.abs(1.0 - gain_grid[:, None] * lp[None, :])  # (G, F)
        # rho below each cutoff: the running max of m up to the cutoff
        running = np.maximum.accumulate(m, axis=1)
        pass_rho = running[:, np.maximum(idx, 0)]  # (G, C)
        whole = np.max(q_mag[None, :, :] * m[:, None, :], axis=2)  # (G, C)
        ok = (pass_rho <= rho) & (whole <= rho)
        for g_i, c_i in zip(*np.nonzero(ok), strict=True):
            key = (c_i, -pass_rho[g_i, c_i])
            if best is None or key > best[:2]:
                best = (c_i, -pass_rho[g_i, c_i], lead, gain_grid[g_i], pass_rho[g_i, c_i],
                        whole[g_i, c_i])  # fmt: skip
    return best


__all__ = ["IterativeLearning", "LearningDesign", "TrialRecord", "design_learning"]
