"""Adaptive output-feedback controller (Do et al. 2015, spec D.3)."""

from __future__ import annotations

import math
from typing import Any

from .._util.args import core_errors_as, number
from .._util.arrays import checked_dt
from .._util.pyobject import bound_attribute
from .._util.units import ANGLE_NOISE, warn_if_unit_slip, warn_unit_slips
from ..models import Backlash, BoucWenBacklash, HysteresisModel
from . import _bound as core
from ._kinds import require_dynamics, require_model
from .base import EngineCompensator

_GAINS = (
    "lambda_",
    "k_s",
    "epsilon",
    "gamma_psi",
    "gamma_phi",
    "gamma_D",
    "sigma_psi",
    "sigma_phi",
    "sigma_D",
    "psi_0",
    "phi_0",
    "D_0",
    "phi_min",
    "psi_max",
    "phi_max",
    "D_max",
    "adaptation_deadzone",
    "derivative_cutoff_hz",
    "derivative_damping",
    "max_torque",
    "fallback_kp",
    "fallback_kd",
    "model_acceleration",
)


class AdaptiveController(EngineCompensator, core.AdaptiveController):  # type: ignore[misc]
    """Sliding-surface adaptive controller with a distal sensor; outputs motor torque.

    u = -k_s s - psi y' - phi nu_r - D tanh(s/epsilon) with s = e' + lambda e, and online
    estimates psi (-b/c), phi (J/c, projected >= phi_min) and D (bound of the lumped
    disturbance), each with leakage sigma_*. y' is a 2nd-order filtered derivative of the
    measured output (``derivative_cutoff_hz``). A NaN measurement (dropout) freezes the
    estimates and drives the motor by a PD loop toward the inverse feedforward of
    ``feedforward_model`` (or toward y_d when none is given). Gains default to spec D.3's
    normalised example; :meth:`from_model` scales them to a motor and an identified model.

    Parameters
    ----------
    feedforward_model : Backlash or BoucWenBacklash, optional
        The model whose inverse feedforward the dropout fallback tracks.
    smoothing : float, default 0.05
        Branch-switch speed of that inverse feedforward (output units per s), > 0.
    **gains
        Any of the controller's gains by name: lambda_, k_s, epsilon, gamma_psi, gamma_phi,
        gamma_D, sigma_psi, sigma_phi, sigma_D, psi_0, phi_0, D_0, phi_min, psi_max,
        phi_max, D_max, adaptation_deadzone, derivative_cutoff_hz, derivative_damping,
        max_torque, fallback_kp, fallback_kd, model_acceleration.

    Raises
    ------
    ValueError
        An unknown gain, a feedforward model of another class, or a value the C++ core
        rejects.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    feedforward_model: HysteresisModel | None
    smoothing: float
    design: Any  # set by from_calibration: what the gains were chosen from

    # signal names of to_control()'s system: desired and measured output, motor angle in
    control_inputs = ("y_d", "y", "q")
    control_output = "torque"
    # what step() takes before dt (tendonsheath.protocols): desired, measured, motor angle
    step_inputs = ("y_d", "y", "q")

    def __init__(
        self,
        feedforward_model: HysteresisModel | None = None,
        smoothing: float = 0.05,
        **gains: float,
    ):
        who = "AdaptiveController"
        unknown = set(gains) - set(_GAINS)
        if unknown:
            raise TypeError(f"{who}: unknown gain(s) {sorted(unknown)}")
        p = core.AdaptiveControllerParams()
        for key, value in gains.items():
            setattr(p, key, bool(value) if key == "model_acceleration" else number(who, key, value))
        if feedforward_model is not None:
            require_model(who, feedforward_model, (Backlash, BoucWenBacklash), "feedforward_model")
            ff = core.BacklashInverseParams()
            for key in Backlash.param_names:  # the rows BacklashInverseParams takes (rows_of)
                setattr(ff, key, feedforward_model.params[key])
            ff.smoothing = number(who, "smoothing", smoothing)
            p.feedforward = ff
            p.has_feedforward = True
        self.feedforward_model = feedforward_model
        self.smoothing = number(who, "smoothing", smoothing)
        if not (math.isfinite(self.smoothing) and self.smoothing > 0):  # with a model or not
            raise ValueError(f"{who}: smoothing must be > 0 (got {self.smoothing:g})")
        with core_errors_as(who):
            core.AdaptiveController.__init__(self, p)
        warn_unit_slips(who, p)
        self.design = None
        resolved = bound_attribute(self, "params")
        self._settings = {
            "feedforward_model": feedforward_model,
            "smoothing": self.smoothing,
            **{key: getattr(resolved, key) for key in _GAINS},
        }

    @classmethod
    def from_model(
        cls,
        model: HysteresisModel,
        inertia: float,
        viscous: float = 0.0,
        bandwidth_hz: float = 5.0,
        derivative_cutoff_hz: float | None = None,
        max_torque: float = math.inf,
        noise_std: float = 0.0,
        **overrides: float,
    ) -> AdaptiveController:
        """Gains scaled to a torque-driven motor (inertia J, viscous b, at the motor shaft)
        and an identified backlash model (its mean slope c).

        phi_0 = J/c and psi_0 = -b/c start the estimates at the true values of the rigid
        part; lambda = 2 pi bandwidth_hz and k_s = 2 phi_0 lambda set how fast the error
        decays. The robust term D tanh(s/eps) is a feedback gain D/eps on s, and s contains
        the filtered derivative of the output, so D is projected below
        eps phi_min w_f / 3 (w_f the derivative filter's corner, default 8 x bandwidth):
        eps = 0.05 lambda leaves an error of a few thousandths of a radian for a lumped
        disturbance (friction torque, dead-zone crossings) up to that bound.

        Parameters
        ----------
        model : Backlash or BoucWenBacklash
            The identified model (also the fallback's feedforward).
        inertia : float
            Motor inertia J at the shaft (kg m^2), > 0.
        viscous : float, default 0.0
            Motor viscous damping b (N m s/rad).
        bandwidth_hz : float, default 5.0
            Closed-loop bandwidth (Hz), > 0.
        derivative_cutoff_hz : float, optional
            Corner of the derivative filter (Hz); default 8 x bandwidth_hz.
        max_torque : float, default inf
            Saturation of the torque (N m).
        noise_std : float, default 0.0
            Standard deviation of the output sensor's noise: sets the adaptation dead zone.
        **overrides
            Gains that replace the scaled ones (see the class).

        Returns
        -------
        AdaptiveController
            The controller.

        Raises
        ------
        ValueError
            inertia or bandwidth_hz not > 0, or an unknown gain.
        """
        who = "AdaptiveController.from_model"
        inertia, viscous = number(who, "inertia", inertia), number(who, "viscous", viscous)
        bandwidth_hz = number(who, "bandwidth_hz", bandwidth_hz)
        max_torque, noise_std = (
            number(who, "max_torque", max_torque),
            number(who, "noise_std", noise_std),
        )
        warn_if_unit_slip(noise_std, who, "noise_std", ANGLE_NOISE)
        if derivative_cutoff_hz is not None:
            derivative_cutoff_hz = number(who, "derivative_cutoff_hz", derivative_cutoff_hz)
        if not inertia > 0:
            raise ValueError("AdaptiveController.from_model: inertia must be > 0")
        if not bandwidth_hz > 0:
            raise ValueError("AdaptiveController.from_model: bandwidth_hz must be > 0")
        p = model.params
        c = 0.5 * (p.get("c_r", 1.0) + p.get("c_l", 1.0))
        phi0 = inertia / c
        psi0 = -viscous / c
        lam = 2 * math.pi * bandwidth_hz
        fc = 8.0 * bandwidth_hz if derivative_cutoff_hz is None else float(derivative_cutoff_hz)
        w_f = 2 * math.pi * fc
        eps = 0.05 * lam
        phi_min = 0.5 * phi0
        d_max = eps * phi_min * w_f / 3.0
        gains = dict(
            lambda_=lam,
            k_s=2.0 * phi0 * lam,
            epsilon=eps,
            phi_0=phi0,
            psi_0=psi0,
            phi_min=phi_min,
            phi_max=4.0 * phi0,
            psi_max=10.0 * abs(psi0) + phi0 * lam,
            D_max=d_max,
            gamma_phi=phi0 / lam**2,
            gamma_psi=(abs(psi0) + phi0 * lam) / lam**2,
            gamma_D=d_max * 10.0 / (eps * eps),
            sigma_phi=0.05,
            sigma_psi=0.05,
            sigma_D=0.05,
            adaptation_deadzone=3.0 * noise_std * lam,
            derivative_cutoff_hz=fc,
            max_torque=max_torque,
            fallback_kp=phi0 * lam * lam,
            fallback_kd=2.0 * phi0 * lam,
        )
        gains.update(overrides)
        return cls(feedforward_model=model, **gains)

    @classmethod
    def from_calibration(
        cls,
        model: HysteresisModel,
        dynamics: Any,
        inertia: float,
        viscous: float = 0.0,
        max_torque: float = math.inf,
        noise_std: float = 0.0,
        trial: Any = None,
        **overrides: float,
    ) -> AdaptiveController:
        """:meth:`from_model` with its bandwidth and derivative filter chosen from the loop
        dynamics identified on the calibration shapes
        (:mod:`~tendonsheath.compensate.adaptive_tuning`): the filter's corner at the lowest
        distal resonance, the bandwidth at most a tenth of it and at most what the sensor's
        delay allows (15 deg of phase), or the best of three bandwidths by ``trial`` runs on
        the calibration shapes.

        Parameters
        ----------
        model : Backlash or BoucWenBacklash
            The identified model (also the fallback's feedforward).
        dynamics : LoopDynamics or sequence of LoopDynamics
            The identified loop of each calibration shape.
        inertia : float
            Motor inertia J at the shaft (kg m^2), > 0 (declared).
        viscous : float, default 0.0
            Motor viscous damping b (N m s/rad) (declared).
        max_torque : float, default inf
            Saturation of the torque (N m).
        noise_std : float, default 0.0
            The tip sensor's noise (rad).
        trial : callable, optional
            candidate -> mean squared tip error on the calibration shapes.
        **overrides
            Gains that replace the scaled ones.

        Returns
        -------
        AdaptiveController
            The controller; ``design`` holds the resonance and delay it was designed from.

        Raises
        ------
        ValueError
            The identified resonance and delay leave no stable bandwidth (the design is
            refused), or a bad argument.
        """
        from .adaptive_tuning import choose_bandwidth

        dyns = require_dynamics("AdaptiveController.from_calibration", dynamics)
        if model is not None:
            require_model("AdaptiveController.from_calibration", model, (Backlash, BoucWenBacklash))

        def build(bandwidth_hz: float, cutoff_hz: float) -> AdaptiveController:
            return cls.from_model(model, inertia, viscous, bandwidth_hz, cutoff_hz, max_torque,
                                  noise_std, **overrides)  # fmt: skip

        return choose_bandwidth(dyns, build, trial)

    @property
    def estimates(self) -> dict[str, float]:  # type: ignore[override]
        """The current estimates psi, phi and D."""
        e = bound_attribute(self, "estimates")
        return {"psi": e.psi, "phi": e.phi, "D": e.D}

    @property
    def in_fallback(self) -> bool:  # type: ignore[override]
        """Whether the last cycle ran the dropout fallback (a NaN measurement)."""
        return core.AdaptiveController.in_fallback(self)

    def reset(self) -> None:
        """Back to the initial estimates and state."""
        core.AdaptiveController.reset(self)

    def step(self, y_d: float, y_measured: float, motor_position: float, dt: float) -> float:
        """One control cycle; returns the motor torque. y_measured may be NaN (dropout).

        Parameters
        ----------
        y_d : float
            Desired distal output.
        y_measured : float
            Measured distal output; NaN for a dropout.
        motor_position : float
            Motor angle (rad).
        dt : float
            Time since the previous cycle (s), >= 0.

        Returns
        -------
        float
            The motor torque (N m).
        """
        dt = checked_dt(dt)
        return core.AdaptiveController.step(
            self, float(y_d), float(y_measured), float(motor_position), float(dt)
        )

    def _control_step(self, u, dt: float) -> float:
        return self.step(u[0], u[1], u[2], dt)

    # -- persistence -----------------------------------------------------------------
    _saved_settings = ("feedforward_model", "smoothing", *_GAINS)


__all__ = ["AdaptiveController"]
