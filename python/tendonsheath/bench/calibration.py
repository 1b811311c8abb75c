"""A calibration protocol that cannot cheat: every compensator input from a plant's logs alone.

:func:`calibrate` runs calibration experiments on a plant (the robot) and keeps only what a
real rig logs: the motor encoder (the motor shaft angle), the noisy distal sensor, and the
sensed curve angle of each calibration shape (shape sensing with noise and delay). Every
parameter a compensator is told is then identified from those logs. Nothing is read from
the plant object: no pretension, length, radii, friction, stiffness or load.

Identifiability (spec B, :class:`~tendonsheath.models.CurveAngleModel`): T0, F_L and k_e
enter only through T0 L/EA, F_L L/EA and k_e L/EA, and the radii only through the gain
r_p/r_d. The pretension, the length and the proximal radius are therefore held at declared
NOMINAL values (1, 1 and 1 unless the user declares design values) and the identified
GROUPS are reported: ``mu``, ``T0 L/(EA r_p)`` (rad at the motor), ``gain r_p/r_d``,
``F_L L/(EA r_p)`` and ``k_e L/EA``. Friction is told apart from the other groups only by
calibration shapes of different curve angles; with one angle it is reported unidentified
and held at a declared value.

The returned :class:`Calibration` builds the compensators and carries a provenance record:
for each quantity a compensator is told, its value and where it came from, and which
identified parameters sit at (within 1 % of) their search bounds.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import models
from .._util.units import DURATION, JOINT_ANGLE, warn_if_unit_slip
from ..plant.route import Route
from ..plant.sensor import Sensor
from .loop_calibration import LoopCalibration, calibrate_loop
from .motor_calibration import MotorCalibration, calibrate_servo, run_experiment
from .shape_sensing import ShapeSensing

if TYPE_CHECKING:
    from .._util.typing import ArrayLike
    from ..compensate import (
        ContinuumFeedforward,
        CurveAngleFeedforward,
        EncoderLoop,
        InverseFeedforward,
    )
    from ..identify.loop_dynamics import LoopDynamics
    from ..plant import ContinuumPlant, PullPullPlant
    from .run import Result

NOMINAL = {"pretension": 1.0, "length": 1.0, "proximal_radius": 1.0}
NOMINAL_FRICTION = 0.1  # held when a single curve angle cannot identify it
# the report's column of relative standard errors: the spread were the data made by the class
_SE = "relative s.e. (given the model class)"


# -- calibration ----------------------------------------------------------------------------


#: the calibration excitation's main frequency (Hz)
CALIBRATION_HZ = 0.25


def calibration_input(duration: float, amplitude: float, rate: float = 1000.0):
    """A calibration excitation unlike the test references: a 0.25 Hz sine at full amplitude
    for its first and last period (both signs: the inverses' identified input range is
    symmetric) and, between them, an amplitude that sweeps down to a third and back, plus a
    0.9 Hz ripple (nested minor loops). Runs shorter than three periods shorten the full-
    amplitude parts to a third of the run each."""
    warn_if_unit_slip(amplitude, "calibration input", "amplitude", JOINT_ANGLE)
    warn_if_unit_slip(duration, "calibration input", "duration", DURATION)
    t = np.arange(0.0, duration, 1.0 / rate)
    edge = min(1.0 / CALIBRATION_HZ, duration / 3.0)
    middle = np.clip((t - edge) / max(duration - 2.0 * edge, 1e-9), 0.0, 1.0)
    envelope = amplitude * (1.0 - (2.0 / 3.0) * np.sin(np.pi * middle))
    x = envelope * np.sin(2 * np.pi * CALIBRATION_HZ * t)
    return t, x + 0.08 * amplitude * np.sin(2 * np.pi * 0.9 * t)


@dataclass
class Told:
    """One quantity a compensator is told: its value and where it came from."""

    quantity: str
    value: Any
    source: str

    def as_dict(self) -> dict[str, Any]:
        return {"quantity": self.quantity, "value": self.value, "source": self.source}


@dataclass
class CalibrationRun:
    name: str
    sensed_angle: float
    duration: float
    samples: int


#: the signals a model can be fitted from, and what each is
FIT_INPUTS = {
    "command": "the motor command (what a feedforward sends to the servo)",
    "encoder": "the motor encoder (what an EncoderLoop makes the shaft follow)",
}


@dataclass
class CalibrationLog:
    """What one calibration run logged: the command sent, the motor encoder, the distal
    sensor's reading and the sensed shape (the curve angle, or a sensed Route)."""

    t: np.ndarray
    command: np.ndarray
    encoder: np.ndarray
    output: np.ndarray
    sensed: Any

    def recording(self, fit_input: str) -> tuple:
        """(t, input, output, sensed shape) with the input ``fit_input`` ("command" or
        "encoder")."""
        return (self.t, self.command if fit_input == "command" else self.encoder, self.output,
                self.sensed)  # fmt: skip


def checked_fit_input(fit_input: str) -> str:
    """``fit_input`` if it is one of FIT_INPUTS, else a ValueError naming them."""
    if fit_input not in FIT_INPUTS:
        raise ValueError(f"fit_input must be one of {sorted(FIT_INPUTS)} (got {fit_input!r})")
    return fit_input


@dataclass
class Calibration:
    """Models identified from calibration logs, and where every number came from.

    ``fits``: name -> :class:`~tendonsheath.identify.Fit` ("BoucWenBacklash",
    "CurveAngleModel", and "load: NAME" for load runs); ``groups``: the identified groups
    (name -> {"value", "source", "identified"}); ``runs``: the calibration experiments;
    ``declared``: nominal or user-declared values (never read from the plant);
    ``at_bounds``: identified parameters within 1 % of their search bounds.

    Parameters
    ----------
    fits : dict of str to Fit
        The identified models, by name.
    runs : list of CalibrationRun
        The calibration experiments.
    declared : dict of str to Told
        Declared values (nominal or the user's).
    groups : dict of str to dict
        The identified groups.
    shape : ShapeSensing
        How the curve angle was sensed.
    at_bounds : dict of str to list of str, optional
        Per fit, the parameters at their search bounds.
    loads : dict of str to dict, optional
        The load groups of each load run (:func:`calibrate_load`).
    friction_identified : bool, default True
        False when one curve angle could not identify friction.
    fit_input : {"command", "encoder"}, default "command"
        The signal the models were fitted from (their input).
    logs : list of CalibrationLog, optional
        What each calibration run logged (command, encoder, distal reading, sensed shape).
    servo : MotorCalibration, optional
        The motor calibration run and its identified servo (``calibrate(..., servo=True)``).
    settings : dict, optional
        How the models were identified (what :meth:`refit` repeats).
    loops : list of LoopCalibration, optional
        The loop calibration runs, one per calibration shape, and the tip-feedback loop's
        dynamics identified from each (``calibrate(..., dynamics=True)``).
    """

    fits: dict[str, Any]
    runs: list[CalibrationRun]
    declared: dict[str, Told]
    groups: dict[str, dict[str, Any]]
    shape: ShapeSensing
    at_bounds: dict[str, list[str]] = field(default_factory=dict)
    loads: dict[str, dict[str, Any]] = field(default_factory=dict)
    friction_identified: bool = True
    fit_input: str = "command"
    logs: list[CalibrationLog] = field(default_factory=list)
    servo: MotorCalibration | None = None
    settings: dict[str, Any] = field(default_factory=dict)  # how the fits were made (refit)
    loops: list[LoopCalibration] = field(default_factory=list)

    @property
    def loop_dynamics(self) -> list[LoopDynamics]:
        """The tip-feedback loop's dynamics on each calibration shape (empty unless calibrated
        with ``dynamics=True``)."""
        return [loop.dynamics for loop in self.loops]

    def loop_summary(self) -> str:
        """One line per calibration shape: the loop's identified resonance, damping, delay and
        bandwidth ("" without loop calibration runs).

        Returns
        -------
        str
            The lines, each prefixed by its run's name.
        """
        names = [r.name for r in self.runs]
        return "\n".join(
            f"{names[i] if i < len(names) else f'shape {i + 1}'}: {d.summary()}"
            for i, d in enumerate(self.loop_dynamics)
        )

    # -- the compensators ------------------------------------------------------------
    @property
    def backlash_model(self) -> models.HysteresisModel:
        """The identified BoucWenBacklash (AngleDependent with ``depends_on_angle``)."""
        return self.fits["BoucWenBacklash"].model

    @property
    def curve_model(self) -> models.CurveAngleModel:
        """The identified CurveAngleModel."""
        return self.fits["CurveAngleModel"].model

    def curve_model_with_load(self, load: str | None = "calibrated") -> models.CurveAngleModel:
        """The CurveAngleModel with a load: "calibrated" the load groups identified from the
        calibration runs themselves (what the robot carried then), a name the load of that
        load run (:func:`calibrate_load`), None no load (not told).

        Parameters
        ----------
        load : str or None, default "calibrated"
            Which load.

        Returns
        -------
        CurveAngleModel
            The model with that load.
        """
        p = dict(self.curve_model.params)
        if load == "calibrated":
            pass
        elif load is None:
            p["load_force"], p["load_stiffness"] = 0.0, 0.0
        else:
            told = self.loads[load]
            p["load_force"], p["load_stiffness"] = told["load_force"], told["load_stiffness"]
        return models.CurveAngleModel(**p)

    def inverse_feedforward(self, **options: Any) -> InverseFeedforward:
        """The InverseFeedforward of the identified BoucWenBacklash (an AngleDependent one,
        which follows the route, when it was calibrated with ``depends_on_angle``). Its
        command is the signal the model was fitted from (:attr:`fit_input`).

        Parameters
        ----------
        **options
            Other keywords of :class:`~tendonsheath.compensate.InverseFeedforward`.

        Returns
        -------
        InverseFeedforward
            The compensator.
        """
        from ..compensate import InverseFeedforward

        return InverseFeedforward(self.backlash_model, **options)

    def encoder_loop(self, feedforward: Any, **options: Any) -> EncoderLoop:
        """``feedforward`` inside an EncoderLoop tuned on the identified servo (see
        ``EncoderLoop.from_calibration``). The feedforward's model should be fitted from the
        encoder (:meth:`refit`).

        Parameters
        ----------
        feedforward : compensator
            The feedforward whose command the encoder is to follow.
        **options
            Other keywords of ``EncoderLoop.from_calibration`` (dt, max_sensitivity,
            derivative, limits).

        Returns
        -------
        EncoderLoop
            The compensator, with its design (gains and margins).

        Raises
        ------
        ValueError
            No motor calibration run (calibrate with ``servo=True``), or no stable design.
        """
        from ..compensate import EncoderLoop

        if self.servo is None:
            raise ValueError(
                "Calibration.encoder_loop needs a motor calibration: calibrate(..., servo=True)"
            )
        return EncoderLoop.from_calibration(feedforward, self.servo.servo, **options)

    def refit(
        self, fit_input: str | None = None, depends_on_angle: dict[str, str] | None = None
    ) -> Calibration:
        """The same calibration runs with the models identified again, from the other logged
        signal or with other laws over the sensed shape (no new experiment).

        Parameters
        ----------
        fit_input : {"command", "encoder"}, optional
            The signal to fit the models from (default: as this calibration).
        depends_on_angle : dict of str to str, optional
            Laws of the BoucWenBacklash parameters over the sensed shape ({} for none;
            default: as this calibration).

        Returns
        -------
        Calibration
            A new calibration sharing the runs, logs, shape sensing and servo (this one when
            nothing changes).
        """
        fit_input = checked_fit_input(self.fit_input if fit_input is None else fit_input)
        settings = dict(self.settings)
        if depends_on_angle is not None:
            settings["depends_on_angle"] = dict(depends_on_angle)
        if fit_input == self.fit_input and settings == self.settings:
            return self
        cal = Calibration(
            fits={},
            runs=list(self.runs),
            declared=dict(self.declared),
            groups={},
            shape=self.shape,
            fit_input=fit_input,
            logs=self.logs,
            servo=self.servo,
            settings=settings,
            loops=list(self.loops),
        )
        _identify_models(cal)
        return cal

    def curve_angle_feedforward(
        self, load: str | None = "calibrated", **options: Any
    ) -> CurveAngleFeedforward:
        """The CurveAngleFeedforward of the identified CurveAngleModel.

        Parameters
        ----------
        load : str or None, default "calibrated"
            Which load it is told (see :meth:`curve_model_with_load`).
        **options
            Other keywords of
            :meth:`~tendonsheath.compensate.CurveAngleFeedforward.from_model`.

        Returns
        -------
        CurveAngleFeedforward
            The compensator.
        """
        from ..compensate import CurveAngleFeedforward

        return CurveAngleFeedforward.from_model(self.curve_model_with_load(load), **options)

    def continuum_feedforward(
        self, sensed_angle: float, mode: str = "exact", **options: Any
    ) -> ContinuumFeedforward:
        """Lau et al.'s feedforward from the identified groups: tendon offset r_t = the
        identified r_d at the nominal r_p; the backbone length cancels (EI = k_e r_t^2 l
        enters only as EI/(r_t l)), so it is held at 1.

        Parameters
        ----------
        sensed_angle : float
            The sheath's sensed curve angle (rad).
        mode : {"exact", "published"}, default "exact"
            See :class:`~tendonsheath.compensate.ContinuumFeedforward`.
        **options
            Other constructor keywords (gap_factor, smoothing, limits).

        Returns
        -------
        ContinuumFeedforward
            The compensator.
        """
        from ..compensate import ContinuumFeedforward

        p = self.curve_model.params
        return ContinuumFeedforward.from_model(
            self.curve_model, p["distal_radius"], 1.0, sensed_angle, mode=mode, **options
        )

    # -- provenance ------------------------------------------------------------------
    def _group(self, name: str) -> Told:
        g = self.groups[name]
        return Told(name, g["value"], g["source"])

    def told(
        self, compensator: str, load: str | None = "calibrated", **declared: tuple[float, str]
    ) -> list[dict]:
        """What compensator ``compensator`` is told and where each value came from.
        ``declared``: other values given by the user (name -> (value, source)).

        Parameters
        ----------
        compensator : str
            The compensator's name (e.g. "InverseFeedforward", "CurveAngleFeedforward").
        load : str or None, default "calibrated"
            Which load it is told.
        **declared
            Other values given by the user, as name=(value, source).

        Returns
        -------
        list of dict
            quantity, value and source of each value told.
        """
        rows: list[Told] = []
        if _uses_backlash(compensator):
            fit = self.fits["BoucWenBacklash"]
            for k, v in fit.model.params.items():
                rows.append(Told(f"BoucWenBacklash {k}", v, fit_source(self, fit)))
            if self.settings.get("depends_on_angle"):
                rows.append(Told("route shape", "sensed every cycle", self.shape.describe()))
        elif compensator in ("CurveAngleFeedforward",) or compensator.startswith(
            "ContinuumFeedforward"
        ):
            for name in ("mu", "T0 L/(EA r_p)", "gain r_p/r_d", "play"):
                if name in self.groups:
                    rows.append(self._group(name))
            if compensator.startswith("ContinuumFeedforward"):
                rows.append(self._group("k_e L/EA"))
            else:
                if load is None:
                    rows.append(Told("distal load", 0.0, "not told (ignored)"))
                elif load == "calibrated":
                    rows.append(self._group("F_L L/(EA r_p)"))
                    if "k_e L/EA" in self.groups:
                        rows.append(self._group("k_e L/EA"))
                else:
                    info = self.loads[load]
                    rows.append(Told("F_L L/(EA r_p)", info["F_L L/(EA r_p)"], info["source"]))
                    rows.append(Told("k_e L/EA", info["k_e L/EA"], info["source"]))
            rows += _declared_rows(self.declared)
            rows.append(Told("route shape", "curve angle only", self.shape.describe()))
        if rows:
            source = f"fitted from {FIT_INPUTS[self.fit_input]}"
            rows.append(Told("model input", self.fit_input, source))
        if "EncoderLoop" in compensator and self.servo is not None:
            rows += _servo_rows(self.servo)
        for name, (value, source) in declared.items():
            rows.append(Told(name, value, source))
        return [r.as_dict() for r in rows]

    def bounds_of(self, compensator: str) -> list[str]:
        """The identified parameters behind ``compensator`` that sit at their search bounds.

        Parameters
        ----------
        compensator : str
            The compensator's name.

        Returns
        -------
        list of str
            Parameter names (load runs' as "load: NAME PARAM").
        """
        if _uses_backlash(compensator):
            return list(self.at_bounds.get("BoucWenBacklash", []))
        if compensator == "CurveAngleFeedforward" or compensator.startswith("Continuum"):
            out = list(self.at_bounds.get("CurveAngleModel", []))
            for name, fits in self.at_bounds.items():
                if name.startswith("load:"):
                    out += [f"{name} {p}" for p in fits]
            return out
        return []

    def to_dict(self) -> dict[str, Any]:
        """The calibration as a JSON-ready dict (runs, declared values, groups, fits, ...).

        Returns
        -------
        dict
            The provenance record.
        """
        return {
            "runs": [vars(r) for r in self.runs],
            "declared": {k: v.as_dict() for k, v in self.declared.items()},
            "groups": self.groups,
            "loads": self.loads,
            "friction_identified": self.friction_identified,
            "shape_sensing": vars(self.shape),
            "at_bounds": self.at_bounds,
            "fit_input": self.fit_input,
            "servo": None if self.servo is None else self.servo.servo.as_dict(),
            "loop_dynamics": [d.as_dict() for d in self.loop_dynamics],
            "fits": {
                name: {
                    "model": fit.model.to_dict(),
                    "rmse": fit.rmse,
                    "nrmse": fit.nrmse,
                    "identified": list(fit.identified),
                    "seconds": fit.seconds,
                }
                for name, fit in self.fits.items()
            },
        }

    def identified_rows(self) -> list[dict[str, Any]]:
        """Rows for the report: each identified group or parameter and its source.

        Returns
        -------
        list of dict
            quantity, value, relative s.e. (given the model class) and source.
        """
        rows = [
            {
                "quantity": k,
                "value": g["value"],
                _SE: g.get("relative_se"),
                "source": g["source"],
            }
            for k, g in self.groups.items()
        ]
        for name, fit in self.fits.items():
            if name != "BoucWenBacklash":
                continue
            for k, v in fit.model.params.items():
                se = fit.standard_errors.get(k)
                rows.append(
                    {
                        "quantity": f"BoucWenBacklash {k}",
                        "value": v,
                        _SE: abs(se / v) if se is not None and v else None,
                        "source": fit_source(self, fit),
                    }
                )
        for name, info in self.loads.items():
            for k in ("F_L L/(EA r_p)", "k_e L/EA"):
                rows.append(
                    {
                        "quantity": f"{name}: {k}",
                        "value": info[k],
                        _SE: None,
                        "source": info["source"],
                    }
                )
        rows += _loop_rows(self)
        # the declared values fix the scale of the groups: shown only beside them
        for d in _declared_rows(self.declared) if self.groups else []:
            rows.append({"quantity": d.quantity, "value": d.value, _SE: None,
                         "source": d.source})  # fmt: skip
        return rows


def _uses_backlash(compensator: str) -> bool:
    """Whether compensator ``compensator`` (a scenario's name for it) is built on the
    identified BoucWenBacklash."""
    return compensator.startswith(
        ("InverseFeedforward", "AdaptiveController", "fixed feedforward")
    ) or (compensator.startswith("EncoderLoop") and "Continuum" not in compensator)


def _servo_rows(motor: MotorCalibration) -> list[Told]:
    """What an EncoderLoop's gains were designed from: the identified servo."""
    sv = motor.servo
    source = "identified from the motor calibration run (command and encoder logs)"
    return [
        Told("servo natural frequency (Hz)", sv.frequency, source),
        Told("servo damping", sv.damping, source),
        Told("servo delay (samples)", sv.delay, source),
    ]


def _loop_rows(cal: Calibration) -> list[dict[str, Any]]:
    """Report rows of the loop calibration runs: resonance, damping, delay and bandwidth."""
    rows = []
    source = "identified from the loop calibration run (command, encoder and tip logs), shape "
    for i, d in enumerate(cal.loop_dynamics):
        se = d.standard_errors
        mode: list[tuple[str, float, str | None]] = [
            ("distal resonance (Hz)", d.resonance_hz, "resonance_hz"),
            ("distal damping", d.damping, "damping"),
        ]
        if not d.resonance_identified:  # the band's edge is what a design was told, not a mode
            mode = [(f"distal resonance: {d.resonance_text()}; limit (Hz)", d.design_limit_hz,
                     None)]  # fmt: skip
        for quantity, value, key in (
            *mode,
            ("tip delay (s)", d.delay, "delay"),
            ("loop bandwidth, command -> tip (Hz)", d.bandwidth_hz, None),
        ):
            rel = abs(se[key] / value) if key in se and value else None
            rows.append({"quantity": f"shape {i + 1}: {quantity}", "value": value,
                         _SE: rel, "source": f"{source}{i + 1}"})  # fmt: skip
    return rows


def fit_source(cal: Calibration | None, fit) -> str:
    names = getattr(fit, "_calibration_runs", None) or []
    return "identified from calibration run(s) " + ", ".join(names)


def _near_bounds(fit, tol: float = 0.01) -> list[str]:
    """Identified parameters within ``tol`` of their search range from either bound (log
    scale for positive ranges spanning more than a decade)."""
    out = []
    params = fit.model.params
    for name in fit.identified:
        if name not in fit.bounds or name not in params:
            continue
        lo, hi = (float(b) for b in fit.bounds[name])
        v = float(params[name])
        if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo:
            continue
        if lo == 0.0 and v >= 0:  # a physical floor: at it only when v is ~0
            if v <= 1e-6 * hi or hi - v <= 0.01 * hi:
                out.append(name)
            continue
        if lo > 0 and hi / lo > 10 and v > 0:
            lo, hi, v = math.log(lo), math.log(hi), math.log(v)
        span = hi - lo
        if v - lo <= tol * span or hi - v <= tol * span:
            out.append(name)
    return out


def calibrate(
    plant: PullPullPlant | ContinuumPlant,
    routes: Sequence[Route],
    *,
    models_: Sequence[str] = ("BoucWenBacklash", "CurveAngleModel"),
    backlash_route: int = 0,
    spring: bool = False,
    duration: float = 15.0,
    amplitude: float = 1.0,
    sensor: Sensor | None = None,
    shape: ShapeSensing | None = None,
    declared: dict[str, float] | None = None,
    declared_friction: float | None = None,
    warmup: float = 1.5,
    seed: int = 0,
    budget: dict | None = None,
    names: Sequence[str] | None = None,
    fit_input: str = "command",
    depends_on_angle: dict[str, str] | None = None,
    servo: bool = False,
    dynamics: bool = False,
) -> Calibration:
    """Calibrate compensators from experiments on ``plant`` (the robot) alone.

    For each route of ``routes`` (the calibration shapes; they must differ from every test
    route) the robot is bent into that shape and driven through its own motor by
    :func:`calibration_input` (``duration`` s, ``amplitude`` rad); the command sent, the motor
    encoder, the distal ``sensor`` (noisy; default the plant's own sensor) and the sensed
    shape (``shape``: the curve angle, or the curvature profile with ``segments``, with
    noise) are logged. From those logs, with the models' input the signal ``fit_input``:

    * ``"BoucWenBacklash"`` (for InverseFeedforward and the AdaptiveController) is
      identified on the run at ``routes[backlash_route]``; with ``depends_on_angle`` (e.g.
      ``{"B_r": "tanh", "B_l": "tanh"}``) on every run with its sensed shape, as an
      :class:`~tendonsheath.models.AngleDependent` model whose inverse follows the route;
    * ``"CurveAngleModel"`` (for CurveAngleFeedforward; with ``spring=True`` the
      environment spring too, for ContinuumFeedforward) on all runs, with their sensed
      angles: mu, T0 L/(EA r_p), gain r_p/r_d (and k_e L/EA) are identified; pretension,
      length and proximal radius are held at NOMINAL (or ``declared`` design values,
      labelled as declared by the user). With a single curve angle friction cannot be told
      apart from the other groups: it is held at ``declared_friction`` (default 0.1) and
      reported unidentified.

    A compensator inverts the model of the signal it outputs: a feedforward sends commands
    to the servo (``fit_input="command"``, the default); inside an
    :class:`~tendonsheath.compensate.EncoderLoop` it sets where the encoder must go
    (``"encoder"``). :meth:`Calibration.refit` fits the other from the same logs.
    ``servo=True`` adds a motor calibration run (:func:`calibrate_servo`) on
    ``routes[backlash_route]`` whose servo :meth:`Calibration.encoder_loop` is tuned on.
    ``dynamics=True`` adds a loop calibration run (:func:`calibrate_loop`: a chirp on a fast
    ramp, command, encoder and the distal ``sensor`` logged) on every calibration shape, and
    identifies the tip-feedback loop's dynamics from each (``Calibration.loop_dynamics``).
    ``budget``: options of :func:`tendonsheath.identify` (maxiter, popsize).

    Parameters
    ----------
    plant : PullPullPlant or ContinuumPlant
        The robot (only driven and logged, never read).
    routes : sequence of Route
        The calibration shapes.
    models_ : sequence of str, default ("BoucWenBacklash", "CurveAngleModel")
        The models to identify.
    backlash_route : int, default 0
        The run the BoucWenBacklash is identified on (and the servo's run).
    spring : bool, default False
        Also identify the environment spring (for ContinuumFeedforward).
    duration : float, default 15.0
        Length of each run (s).
    amplitude : float, default 1.0
        Amplitude of the excitation (rad).
    sensor : Sensor, optional
        The distal sensor (default the plant's own).
    shape : ShapeSensing, optional
        The shape sensing (default one with ``seed``).
    declared : dict of str to float, optional
        Design values of pretension, length and proximal radius.
    declared_friction : float, optional
        Friction held when one curve angle cannot identify it (default 0.1).
    warmup : float, default 1.5
        Seconds at the start of each run left out of the fits.
    seed : int, default 0
        Seed of the noise and of the identification.
    budget : dict, optional
        Options of :func:`tendonsheath.identify` (maxiter, popsize).
    names : sequence of str, optional
        Names of the runs (default cal1, cal2, ...).
    fit_input : {"command", "encoder"}, default "command"
        The signal the models are fitted from.
    depends_on_angle : dict of str to str, optional
        Laws of the BoucWenBacklash parameters over the sensed shape (see above).
    servo : bool, default False
        Also run the motor calibration and identify the servo.
    dynamics : bool, default False
        Also run a loop calibration on each shape and identify the tip-feedback loop's
        dynamics (servo, distal resonance, sensor delay).

    Returns
    -------
    Calibration
        The identified models and their provenance.

    Raises
    ------
    ValueError
        A plant driven by a torque motor (the excitation is an angle command for a position
        servo), or a bad setting.
    """
    _refuse_torque_motor(plant)
    checked_fit_input(fit_input)
    shape = shape or ShapeSensing(seed=seed)
    t, command = calibration_input(duration, amplitude)
    names = list(names) if names is not None else [f"cal{i + 1}" for i in range(len(routes))]
    experiment = (plant, t, command, sensor, seed)
    runs, logs = _calibration_logs(experiment, routes, names, shape, duration)
    warm = int(round(warmup / (t[1] - t[0])))
    settings = {
        "models": tuple(models_),
        "backlash_route": backlash_route,
        "spring": spring,
        "declared_friction": declared_friction,
        "depends_on_angle": dict(depends_on_angle or {}),
        "options": {"warmup": warm, "seed": seed, "budget": dict(budget or {})},
    }
    cal = Calibration(
        fits={},
        runs=runs,
        declared=_declared_values(declared),
        groups={},
        shape=shape,
        fit_input=fit_input,
        logs=logs,
        settings=settings,
    )
    _identify_models(cal)
    if servo:
        cal.servo = calibrate_servo(plant, routes[backlash_route])
        m = cal.servo
        duration_m = float(m.t[-1] - m.t[0])
        cal.runs.append(CalibrationRun("motor (chirp on a ramp)", runs[backlash_route].sensed_angle,
                                       duration_m, int(m.t.size)))  # fmt: skip
    if dynamics:
        for i, route in enumerate(routes):
            loop = calibrate_loop(plant, route, sensor, seed=seed + 401 + i)
            cal.loops.append(loop)
            cal.runs.append(CalibrationRun(f"loop (chirp on a fast ramp), shape {i + 1}",
                                           runs[i].sensed_angle, float(loop.t[-1] - loop.t[0]),
                                           int(loop.t.size)))  # fmt: skip
    return cal


def _refuse_torque_motor(plant: Any) -> None:
    """calibrate drives the robot with angle commands: a torque motor would take them as
    torques (N m) and the fit would be nonsense, so such a plant is refused."""
    motor = getattr(plant, "motor", None)
    if motor is not None and getattr(motor, "kind", "position") == "torque":
        raise ValueError(
            "calibrate: the plant's motor is a torque motor, but calibration drives the robot "
            "with angle commands to a position servo; calibrate the same robot with a position "
            "motor (Motor.position) and give a torque-driven joint its identified model with the "
            "motor's declared inertia and damping (AdaptiveController.from_calibration)"
        )


def _identify_models(cal: Calibration) -> None:
    """The models of ``cal.settings`` identified from ``cal.logs`` with ``cal.fit_input``."""
    st = cal.settings
    recordings = [log.recording(cal.fit_input) for log in cal.logs]
    names = [r.name for r in cal.runs[: len(recordings)]]
    options = st["options"]
    if "BoucWenBacklash" in st["models"]:
        if st["depends_on_angle"]:
            search = {"recordings": recordings, "depends_on_angle": st["depends_on_angle"]}
            _add_fit(cal, "BoucWenBacklash", names, (), search, **options)
        else:
            tb, xb, yb, _ = recordings[st["backlash_route"]]
            run = [names[st["backlash_route"]]]
            _add_fit(cal, "BoucWenBacklash", run, (tb, xb, yb), {}, **options)
    if "CurveAngleModel" in st["models"]:
        _add_curve_angle_fit(cal, recordings, names, st["spring"], st["declared_friction"], options)


def _calibration_logs(experiment: tuple, routes, names: list[str], shape, duration: float):
    """Drive the robot on each calibration route (``experiment``: plant, t, command, distal
    sensor, seed) and log it: the runs and their logs (command, encoder, distal reading,
    sensed shape)."""
    plant, t, command, sensor, seed = experiment
    runs, logs = [], []
    for i, route in enumerate(routes):
        x, y = run_experiment(plant, route, t, command, sensor, seed + 101 + i)
        sensed = _sensed_shape(shape, route, duration, i)
        angle = float(sensed if isinstance(sensed, int | float) else sensed.curve_angle)
        runs.append(CalibrationRun(names[i], angle, duration, int(t.size)))
        logs.append(CalibrationLog(t, np.asarray(command, dtype=float), x, y, sensed))
    return runs, logs


def _sensed_shape(shape, route, duration: float, i: int):
    """What the shape sensor records for a calibration shape held still: the sensed Route when
    it senses the profile (``segments``), else the sensed curve angle."""
    if getattr(shape, "segments", 0):
        return shape.static_route(route, duration, seed_offset=i)
    return shape.static_reading(route.curve_angle, duration, seed_offset=i)


def _add_curve_angle_fit(cal, recordings, names, spring: bool, declared_friction, options):
    """The CurveAngleModel on all calibration runs with the declared values held (and
    friction too where a single curve angle cannot identify it), and its groups."""
    fixed = {k: d.value for k, d in cal.declared.items()}
    if len({round(_angle_of(r[3]), 3) for r in recordings}) < 2:
        cal.friction_identified = False
        fixed["friction"] = (
            NOMINAL_FRICTION if declared_friction is None else float(declared_friction)
        )
    r_d0 = fixed["proximal_radius"] / max(_mean_slope(recordings), 1e-6)
    # the motor-side play is the same at every angle: angles that differ tell it apart
    play = [] if not cal.friction_identified else ["play"]
    search = {
        "recordings": recordings,
        "fixed": fixed,
        "free": ["distal_radius", *play] + (["load_stiffness"] if spring else []),
        "bounds": {"distal_radius": (0.3 * r_d0, 3.0 * r_d0)},
    }
    fit = _add_fit(cal, "CurveAngleModel", names, (), search, **options)
    cal.groups = _curve_angle_groups(fit, cal.runs, cal.friction_identified, spring)


def _angle_of(sensed) -> float:
    """The total curve angle of a sensed shape (a number, or a sensed Route)."""
    return float(getattr(sensed, "curve_angle", sensed))


def _declared_values(declared: dict[str, float] | None) -> dict[str, Told]:
    """The values held at NOMINAL, or at the user's declared design values."""
    user = dict(declared or {})
    decl: dict[str, Told] = {}
    for key, value in NOMINAL.items():
        if key in user:
            decl[key] = Told(key, float(user[key]), "declared by the user (design value)")
        else:
            decl[key] = Told(key, value, "declared nominal (a scale, not identifiable)")
    return decl


_SCALE_SOURCE = (
    "not measured: a scale. A position log identifies only the groups these enter "
    "(T0 L/(EA r_p), gain r_p/r_d, F_L L/(EA r_p), k_e L/EA), given with their standard "
    "errors; each is held at 1 (declare design values to change the scale)"
)


def _declared_rows(declared: dict[str, Told]) -> list[Told]:
    """The declared values as a report shows them: a user's design value on its own row, the
    nominal ones together in one row, for they are a scale, not a measurement."""
    user = [d for d in declared.values() if d.source.startswith("declared by the user")]
    nominal = [d for d in declared.values() if d not in user]
    rows = list(user)
    if nominal:
        values = ", ".join(f"{d.value:g}" for d in nominal)
        rows.append(Told(", ".join(d.quantity for d in nominal), values, _SCALE_SOURCE))
    return rows


def _mean_slope(recordings) -> float:
    """|least-squares slope| of output on input over all recordings (a scale to search by)."""
    x_all = np.concatenate([r[1] for r in recordings])
    y_all = np.concatenate([r[2] for r in recordings])
    xc = x_all - x_all.mean()
    return abs(float(np.dot(xc, y_all - y_all.mean()) / max(np.dot(xc, xc), 1e-300)))


#: global searches of a curve-angle model (seeds seed, seed + 1, ...; the best kept): its groups
#: are strongly correlated (the play with the tendons' dead zone, the load stiffness with the
#: gain) and one search stops in a local minimum on some drives (lau2015's PID servo: an rmse
#: 2.2x the best of three)
RESTARTS = {"CurveAngleModel": 3}


def _add_fit(cal: Calibration, name: str, run_names, data, search: dict, *, warmup, seed, budget):
    """Identify model ``name`` from calibration ``data`` (t, x, y; or none, with the
    recordings in ``search``) and file the fit, its runs and its parameters at bounds."""
    from ..identify import identify

    model = getattr(models, name)
    fits = [
        # data is (t, x, y) or empty (then search holds the recordings)
        identify(model, *data, **search, warmup=warmup, seed=s, progress=False, **budget)  # type: ignore[misc]
        for s in range(seed, seed + RESTARTS.get(name, 1))
    ]
    fit = min(fits, key=lambda f: f.rmse)
    fit._calibration_runs = list(run_names)
    cal.fits[name] = fit
    cal.at_bounds[name] = _near_bounds(fit)
    return fit


def _curve_angle_groups(fit, runs, friction_identified: bool, spring: bool) -> dict:
    """The identified groups of a CurveAngleModel fit, with their relative standard errors
    and where they came from."""
    p = fit.model.params
    se = fit.standard_errors

    def rel(*names):  # relative standard error of a product of parameters
        terms = [(se.get(n) or 0.0) / abs(p[n]) for n in names if n in se and p[n] != 0]
        return float(math.sqrt(sum(x * x for x in terms))) if terms else None

    src = (
        fit_source(None, fit)
        + " (sensed curve angles "
        + ", ".join(f"{r.sensed_angle:.3f}" for r in runs)
        + " rad)"
    )
    scale = p["length"] / (p["stiffness"] * p["proximal_radius"])
    groups = {}
    groups["mu"] = {
        "value": p["friction"],
        "source": src
        if friction_identified
        else f"UNIDENTIFIED (one curve angle): declared value {p['friction']:g}",
        "relative_se": rel("friction"),
        "identified": friction_identified,
    }
    groups["T0 L/(EA r_p)"] = {
        "value": p["pretension"] * scale,
        "source": src,
        "relative_se": rel("stiffness"),
        "identified": True,
        "unit": "rad at the motor",
    }
    groups["gain r_p/r_d"] = {
        "value": p["proximal_radius"] / p["distal_radius"],
        "source": src,
        "relative_se": rel("distal_radius"),
        "identified": True,
    }
    groups["F_L L/(EA r_p)"] = {
        "value": p["load_force"] * scale,
        "source": src,
        "relative_se": rel("stiffness", "load_force"),
        "identified": True,
        "unit": "rad at the motor",
    }
    if friction_identified:
        groups["play"] = {
            "value": p["play"],
            "source": src,
            "relative_se": rel("play"),
            "identified": True,
            "unit": "rad at the motor",
        }
    if spring:
        groups["k_e L/EA"] = {
            "value": p["load_stiffness"] * p["length"] / p["stiffness"],
            "source": src,
            "relative_se": rel("stiffness", "load_stiffness"),
            "identified": True,
        }
    return groups


def calibrate_load(
    cal: Calibration,
    name: str,
    plant: PullPullPlant | ContinuumPlant,
    route: Route,
    *,
    duration: float = 10.0,
    amplitude: float = 1.0,
    sensor: Sensor | None = None,
    warmup: float = 1.5,
    seed: int = 0,
    budget: dict | None = None,
) -> None:
    """A load calibration run: the robot carrying load ``name`` (``plant``) is driven on a
    calibration ``route``; the load groups F_L L/EA and k_e L/EA of the CurveAngleModel are
    identified with the other groups held at their identified values. Adds
    ``cal.loads[name]``.

    Parameters
    ----------
    cal : Calibration
        The calibration to add to (changed in place).
    name : str
        The load's name.
    plant : PullPullPlant or ContinuumPlant
        The robot carrying the load.
    route : Route
        The calibration shape.
    duration : float, default 10.0
        Length of the run (s).
    amplitude : float, default 1.0
        Amplitude of the excitation (rad).
    sensor : Sensor, optional
        The distal sensor (default the plant's own).
    warmup : float, default 1.5
        Seconds left out of the fit.
    seed : int, default 0
        Seed of the noise and of the identification.
    budget : dict, optional
        Options of :func:`tendonsheath.identify` (maxiter, popsize).
    """
    from ..identify import identify

    t, command = calibration_input(duration, amplitude)
    warm = int(round(warmup / (t[1] - t[0])))
    i = len(cal.runs)
    encoder, y = run_experiment(plant, route, t, command, sensor, seed + 301 + i)
    x = command if cal.fit_input == "command" else encoder
    sensed = cal.shape.static_reading(route.curve_angle, duration, seed_offset=50 + i)
    run_name = f"load '{name}'"
    cal.runs.append(CalibrationRun(run_name, sensed, duration, int(t.size)))
    p = dict(cal.curve_model.params)
    fixed = {k: v for k, v in p.items() if k not in ("load_force", "load_stiffness")}
    fit = identify(
        models.CurveAngleModel,
        t,
        x,
        y,
        curve_angle=sensed,
        fixed=fixed,
        free=["load_stiffness", "distal_radius"],
        warmup=warm,
        seed=seed,
        progress=False,
        **dict(budget or {}),
    )
    q = fit.model.params
    fit._calibration_runs = [run_name]
    cal.fits[f"load: {name}"] = fit
    cal.at_bounds[f"load: {name}"] = _near_bounds(fit)
    scale = q["length"] / (q["stiffness"] * q["proximal_radius"])
    cal.loads[name] = {
        "load_force": q["load_force"],
        "load_stiffness": q["load_stiffness"],
        "F_L L/(EA r_p)": q["load_force"] * scale,
        "k_e L/EA": q["load_stiffness"] * q["length"] / q["stiffness"],
        "source": f"identified from calibration run {run_name} (sensed angle {sensed:.3f} rad)",
    }


# -- how far the plant is from a compensator's model class ---------------------------------

MODEL_CLASS = {
    "none": "linear gain",
    "InverseFeedforward": "BoucWenBacklash",
    "AdaptiveController": "BoucWenBacklash",
    "fixed feedforward": "BoucWenBacklash",
    "CurveAngleFeedforward": "CurveAngleModel",
}


def model_class_of(compensator: str) -> str:
    if compensator.startswith("ContinuumFeedforward"):
        return "CurveAngleModel (with spring)"
    return MODEL_CLASS.get(compensator, "BoucWenBacklash")


def in_class_fit(
    compensator: str,
    result: Result,
    curve_angle: ArrayLike | None = None,
    rate_hz: float = 200.0,
    seed: int = 0,
    budget: dict | None = None,
) -> dict[str, Any]:
    """The best fit of ``compensator``'s model class to the test run's own log (motor
    encoder in, distal sensor out, decimated to ``rate_hz``; the first period excluded):
    how far the plant lies from what the compensator can represent, next to the output's
    range. ``curve_angle``: per-sample curve angle of the run (CurveAngleModel).

    Parameters
    ----------
    compensator : str
        The compensator's name (its model class follows from it).
    result : Result
        The test run (:func:`tendonsheath.bench.run`).
    curve_angle : float or array_like of float, optional
        The run's curve angle, for a CurveAngleModel class.
    rate_hz : float, default 200.0
        Rate the log is decimated to (Hz).
    seed : int, default 0
        Seed of the identification.
    budget : dict, optional
        Options of :func:`tendonsheath.identify` (maxiter, popsize).

    Returns
    -------
    dict
        model_class, output_range, in_class_rmse and in_class_nrmse.
    """
    from ..identify import identify

    t = np.asarray(result.t)
    step = max(1, int(round(1.0 / (rate_hz * (t[1] - t[0])))))
    sl = slice(None, None, step)
    ts, x, y = t[sl], np.asarray(result.q_motor)[sl], np.asarray(result.measured)[sl]
    keep = ts >= ts[0] + result.warmup
    warm = int(np.argmax(keep)) if keep.any() else 0
    ok = np.isfinite(y)
    name = model_class_of(compensator)
    out: dict[str, Any] = {"model_class": name, "output_range": float(np.ptp(y[ok]))}
    budget = {"maxiter": 30, "popsize": 8, **(budget or {})}
    if not ok.all():
        ts, x, y = ts[ok], x[ok], y[ok]
    if name == "linear gain":
        A = np.column_stack([x[warm:], np.ones(x.size - warm)])
        coef, *_ = np.linalg.lstsq(A, y[warm:], rcond=None)
        rmse = float(np.sqrt(np.mean((A @ coef - y[warm:]) ** 2)))
    elif name == "BoucWenBacklash":
        fit = identify(
            models.BoucWenBacklash, ts, x, y, warmup=warm, seed=seed, progress=False, **budget
        )
        rmse = fit.rmse
    else:
        theta = np.asarray(curve_angle, dtype=float)
        theta = theta[sl][ok] if theta.ndim else np.full(x.size, float(theta))
        slope = abs(np.polyfit(x, y, 1)[0]) or 1.0
        fit = identify(
            models.CurveAngleModel,
            ts,
            x,
            y,
            curve_angle=theta,
            fixed=dict(NOMINAL),
            free=["distal_radius"] + (["load_stiffness"] if "spring" in name else []),
            bounds={"distal_radius": (0.3 / slope, 3.0 / slope)},
            warmup=warm,
            seed=seed,
            progress=False,
            **budget,
        )
        rmse = fit.rmse
    out["in_class_rmse"] = rmse
    out["in_class_nrmse"] = rmse / out["output_range"] if out["output_range"] > 0 else None
    return out


def honesty_entry(
    compensator: str,
    result: Result,
    told: list[dict],
    at_bounds: list[str],
    curve_angle: ArrayLike | None = None,
    seed: int = 0,
    budget: dict | None = None,
) -> dict[str, Any]:
    """One row of a scenario's honesty panel (see docs/metrics-json.md, "honesty").

    Parameters
    ----------
    compensator : str
        The compensator's name.
    result : Result
        Its test run.
    told : list of dict
        What it was told (:meth:`Calibration.told`).
    at_bounds : list of str
        Its parameters at their search bounds (:meth:`Calibration.bounds_of`).
    curve_angle : float or array_like of float, optional
        The run's curve angle.
    seed : int, default 0
        Seed of the in-class fit.
    budget : dict, optional
        Options of :func:`tendonsheath.identify` (maxiter, popsize).

    Returns
    -------
    dict
        told, at_bounds and the :func:`in_class_fit` figures.
    """
    entry = {"told": told, "at_bounds": at_bounds}
    entry.update(in_class_fit(compensator, result, curve_angle, seed=seed, budget=budget))
    return entry


__all__ = [
    "NOMINAL",
    "Calibration",
    "Told",
    "calibrate",
    "calibrate_load",
    "calibration_input",
    "honesty_entry",
    "in_class_fit",
]
