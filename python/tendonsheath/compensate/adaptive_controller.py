"""Adaptive output-feedback controller (seed 002, spec D.3)."""

from __future__ import annotations

import math

from .. import _core as core
from ..models import Backlash, BoucWenBacklash

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
)


class AdaptiveController:
    """Sliding-surface adaptive controller with a distal sensor; outputs motor torque.

    u = -k_s s - psi y' - phi nu_r - D tanh(s/epsilon) with s = e' + lambda e, and online
    estimates psi (-b/c), phi (J/c, projected >= phi_min) and D (bound of the lumped
    disturbance), each with leakage sigma_*. y' is a 2nd-order filtered derivative of the
    measured output (``derivative_cutoff_hz``). A NaN measurement (dropout) freezes the
    estimates and drives the motor by a PD loop toward the inverse feedforward of
    ``feedforward_model`` (or toward y_d when none is given). Gains default to spec D.3's
    normalised example; :meth:`from_model` scales them to a motor and an identified model.
    """

    def __init__(self, feedforward_model=None, smoothing: float = 0.05, **gains):
        unknown = set(gains) - set(_GAINS)
        if unknown:
            raise ValueError(f"AdaptiveController: unknown gain(s) {sorted(unknown)}")
        p = core.AdaptiveControllerParams()
        for key, value in gains.items():
            setattr(p, key, float(value))
        if feedforward_model is not None:
            if not isinstance(feedforward_model, Backlash | BoucWenBacklash):
                raise ValueError("feedforward_model must be a Backlash or BoucWenBacklash")
            ff = core.BacklashInverseParams()
            for key in ("c_r", "c_l", "B_r", "B_l"):
                setattr(ff, key, feedforward_model.params[key])
            ff.v_eps = smoothing
            p.feedforward = ff
            p.has_feedforward = True
        self.feedforward_model = feedforward_model
        self._engine = core.AdaptiveController(p)

    @classmethod
    def from_model(
        cls,
        model,
        inertia: float,
        viscous: float = 0.0,
        bandwidth_hz: float = 5.0,
        max_torque: float = math.inf,
        noise_std: float = 0.0,
        **overrides,
    ) -> AdaptiveController:
        """Gains scaled to a torque-driven motor (inertia J, viscous b) and an identified
        backlash model (its mean slope c): phi_0 = J/c, psi_0 = -b/c, lambda and the
        feedback k_s = phi_0 * 2 pi * 4 * bandwidth set the closed-loop speed; the
        adaptation rates are scaled so that each estimate moves by its own size within
        about a second of 0.1 rad tracking error."""
        if not inertia > 0:
            raise ValueError("AdaptiveController.from_model: inertia must be > 0")
        p = model.params
        c = 0.5 * (p.get("c_r", 1.0) + p.get("c_l", 1.0))
        phi0 = inertia / c
        psi0 = -viscous / c
        w = 2 * math.pi * bandwidth_hz
        gains = dict(
            lambda_=w,
            k_s=phi0 * 4 * w,
            epsilon=0.05,
            phi_0=phi0,
            psi_0=psi0,
            phi_min=0.1 * phi0,
            phi_max=10 * phi0,
            psi_max=10 * abs(psi0) + 10 * phi0 * w,
            gamma_phi=phi0 / (0.1 * w) ** 2,
            gamma_psi=(abs(psi0) + phi0) / 0.1**2,
            gamma_D=phi0 * w / 0.1,
            D_max=phi0 * w * w,
            sigma_phi=0.01,
            sigma_psi=0.01,
            sigma_D=0.01,
            adaptation_deadzone=3 * noise_std * w,
            max_torque=max_torque,
            fallback_kp=phi0 * w * w,
            fallback_kd=2 * phi0 * w,
        )
        gains.update(overrides)
        return cls(feedforward_model=model, **gains)

    @property
    def estimates(self) -> dict[str, float]:
        e = self._engine.estimates
        return {"psi": e.psi, "phi": e.phi, "D": e.D}

    @property
    def in_fallback(self) -> bool:
        return self._engine.in_fallback()

    def reset(self) -> None:
        self._engine.reset()

    def step(self, y_d: float, y_measured: float, motor_position: float, dt: float) -> float:
        """One control cycle; returns the motor torque. y_measured may be NaN (dropout)."""
        return self._engine.step(float(y_d), float(y_measured), float(motor_position), float(dt))
