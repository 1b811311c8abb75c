"""A motor-encoder loop around any feedforward: integral action with no tip sensor."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .._util.args import core_errors_as, number
from .._util.arrays import checked_dt
from .._util.param_table import TABLE, number_rows, table_constructor
from .._util.pyobject import bound_attribute
from .._util.units import warn_unit_slips
from ..protocols import step_signals
from . import _bound as core
from ._kinds import require_feedforward, require_servo
from .around import AroundFeedforward
from .limits import CommandLimits, LimitsLike, as_limits

if TYPE_CHECKING:
    from ..identify.servo import ServoFit
    from .tuning import EncoderLoopDesign

_GAINS = number_rows(core.EncoderLoopParams)  # kp, ki, kd, derivative_cutoff_hz, max_correction


@table_constructor(core.EncoderLoopParams)
class EncoderLoop(AroundFeedforward, core.EncoderLoop):  # type: ignore[misc]
    """A feedforward's command made real by a PI(D) loop on the motor encoder.

    A feedforward computes the motor angle x_ff its model says gives the desired output. A
    position servo without integral action yields to the tendons' torque, differently in each
    direction, so the shaft does not reach x_ff. This compensator closes a loop on the motor's
    own encoder q (no tip sensor): with e = x_ff(previous cycle) - q,

        u = x_ff + clamp(kp e + ki integral(e) + kd de/dt, +-max_correction)

    shaped to ``limits``; the integral is held while the command is cut in the direction the
    error pushes (anti-windup), and a NaN encoder reading (a dropout) holds the correction
    (status ``fallback``). The feedforward's model must then describe the drive from the
    *encoder* to the output (calibrate it with ``fit_input="encoder"``): its command is where
    the shaft is made to go. :meth:`from_calibration` chooses the gains from an identified
    servo (:func:`tendonsheath.identify.identify_servo`) with stated margins.

    Parameters
    ----------
    feedforward : compensator
        Any feedforward with ``reset()``, ``step(y_d, dt)`` and ``status()`` (a shipped
        InverseFeedforward, CurveAngleFeedforward or ContinuumFeedforward, or your own).
    limits : CommandLimits, tuple, dict or None, optional
        Saturation of the servo command and its rate (after the correction).

    Raises
    ------
    TypeError
        A feedforward without reset/step, or a setting of the wrong type.
    ValueError
        A gain or limit the C++ core rejects (the message names it).
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    limits: CommandLimits
    design: EncoderLoopDesign | None

    control_inputs = ("y_d", "q")
    control_output = "x"
    step_inputs = ("y_d", "q")
    _saved_settings = ("feedforward", *_GAINS, "limits")

    def __init__(
        self,
        feedforward: Any,
        kp: float = TABLE,
        ki: float = TABLE,
        kd: float = TABLE,
        derivative_cutoff_hz: float = TABLE,
        max_correction: float = TABLE,
        limits: LimitsLike = None,
    ):
        who = "EncoderLoop"
        require_feedforward(who, feedforward)
        if isinstance(feedforward, EncoderLoop) or step_signals(feedforward) != ("y_d",):
            raise TypeError(
                f"{who}: feedforward must be a feedforward compensator with reset() and "
                f"step(y_d, dt) (got {type(feedforward).__name__})"
            )
        values = locals()
        p = core.EncoderLoopParams()
        for key in _GAINS:
            setattr(p, key, number(who, key, values[key]))
        self.limits = as_limits(limits)
        p.limits = self.limits.to_core()
        with core_errors_as(who):
            core.EncoderLoop.__init__(self, p)
        warn_unit_slips(who, p)
        self.feedforward = feedforward
        self.design = None
        self._settings = {**{k: getattr(p, k) for k in _GAINS}, "limits": self.limits}

    @classmethod
    def from_calibration(
        cls,
        feedforward: Any,
        servo: ServoFit,
        dt: float = 1e-3,
        max_sensitivity: float = 1.7,
        derivative: bool = False,
        limits: LimitsLike = None,
        servo_integral_only: bool = False,
    ) -> EncoderLoop:
        """Gains from an identified servo (motor calibration logs alone): the largest integral
        gain whose loop keeps the peak sensitivity |1/(1 + C G)| below ``max_sensitivity``
        (:func:`~tendonsheath.compensate.tuning.tune_encoder_loop`); the design, with its gain
        and phase margins, is kept in ``design``.

        Parameters
        ----------
        feedforward : compensator
            The feedforward whose command the encoder is to follow.
        servo : ServoFit
            The servo identified from a motor calibration run.
        dt : float, default 1e-3
            The control cycle (s).
        max_sensitivity : float, default 1.7
            The largest allowed peak of the sensitivity function, > 1.
        derivative : bool, default False
            Also tune a derivative gain (PID); PI otherwise.
        limits : CommandLimits, tuple, dict or None, optional
            Saturation of the servo command.
        servo_integral_only : bool, default False
            Around a servo identified with integral action of its own (a PID servo), leave the
            loop out (gains 0: the servo's integral alone holds the command) instead of adding
            a second integral; the design's ``note`` says which was done.

        Returns
        -------
        EncoderLoop
            The compensator, with ``design`` set.

        Raises
        ------
        ValueError
            No gains make the identified loop stable within ``max_sensitivity``.

        Warns
        -----
        MarginNotMetWarning
            The design's peak sensitivity is above ``max_sensitivity``.

        Notes
        -----
        Needs NumPy and SciPy only (no python-control).
        """
        from .tuning import tune_encoder_loop

        require_feedforward("EncoderLoop.from_calibration", feedforward)
        require_servo("EncoderLoop.from_calibration", servo)
        design = tune_encoder_loop(servo, dt, max_sensitivity, derivative, servo_integral_only)
        loop = cls(feedforward, **design.gains(), limits=limits)
        loop.design = design
        return loop

    # -- streaming ------------------------------------------------------------------
    def reset(self) -> None:
        """Forget the feedforward's and the loop's state."""
        self.feedforward.reset()
        core.EncoderLoop.reset(self)

    def step(self, y_d: float, q: float, dt: float) -> float:
        """One control cycle: the servo command.

        Parameters
        ----------
        y_d : float
            Desired output.
        q : float
            Motor encoder angle (rad); NaN when there is no reading this cycle.
        dt : float
            Time since the previous cycle (s), >= 0.

        Returns
        -------
        float
            The servo command (rad).
        """
        dt = checked_dt(dt)
        x = float(self.feedforward.step(float(y_d), dt))
        return self.correct(x, float(q), dt)

    @property
    def correction(self) -> float:  # type: ignore[override]
        """The correction added to the feedforward's last command (rad)."""
        return core.EncoderLoop.correction(self)

    def _control_step(self, u, dt: float) -> float:
        return self.step(u[0], u[1], dt)

    # -- the bench and persistence ------------------------------------------------------
    def bench_stage(self) -> tuple[Any, Any]:
        """The C++ loop and the feedforward it is around, for bench.run's C++ loop
        (:class:`~tendonsheath.protocols.BenchCompensator`).

        Returns
        -------
        (object, compensator)
            A copy of this loop's real-time core, and the feedforward.
        """
        return core.EncoderLoop(bound_attribute(self, "params")), self.feedforward

    def __repr__(self) -> str:
        gains = ", ".join(f"{k}={self._settings[k]:g}" for k in _GAINS[:3])  # kp, ki, kd
        return f"EncoderLoop({self.feedforward!r}, {gains})"


__all__ = ["EncoderLoop"]
