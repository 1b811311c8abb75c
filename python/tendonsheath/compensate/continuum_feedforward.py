"""Feedforward of a tendon-sheath-driven continuum segment (seed 001, spec C)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from .. import _core as core
from .base import Feedforward
from .limits import LimitsLike, as_limits

if TYPE_CHECKING:
    from ..models import CurveAngleModel

_MODES = {"exact": core.ContinuumMode.exact, "published": core.ContinuumMode.published}


class ContinuumFeedforward(Feedforward):
    """Desired bending angle (rad) in, motor angle (rad) out: X_in = X_d + delta_ts + delta_F.

    ``mode="published"`` implements Lau et al.'s equations as printed (effective backlash
    delta_0 = 2 T0 L (1 - e^{-xi Theta})/EA and a separate delta_F, which partly double
    count); ``mode="exact"`` uses the capstan-consistent full-slip elongations (spec A5/A6)
    under the bending force F = kappa EI / r_t, without double counting.

    Parameters
    ----------
    friction : float, default 0.1
        Friction coefficient mu.
    sheath_length : float, default 1.0
        Sheath length L (m).
    stiffness : float, default 2.4e4
        Tendon axial stiffness EA (N).
    pretension : float, default 10.0
        Pretension T0 (N).
    total_angle : float, default pi
        Curve angle Theta of the sheath (rad).
    bending_stiffness : float, default 4e-4
        Backbone bending stiffness EI (N m^2).
    tendon_offset : float, default 2e-3
        Distance r_t of the tendon from the backbone (m).
    backbone_length : float, default 0.03
        Length l of the bending segment (m).
    proximal_radius : float, default 5e-3
        Motor pulley radius (m).
    gap_factor : float, default 1.0
        Kesner and Howe's gamma delta_r: xi = gap_factor mu (1: plain capstan), > 0.
    smoothing : float, default 0.1
        Direction-switch speed (rad/s of the bending angle), > 0.
    mode : {"exact", "published"}, default "exact"
        Capstan-consistent equations, or Lau et al.'s as printed.
    limits : CommandLimits, tuple, dict or None, optional
        Saturation of the command and its rate (see :class:`CommandLimits`).

    Raises
    ------
    ValueError
        An unknown mode, or a value the C++ core rejects (the message names it).
    """

    _saved_settings = (
        "friction",
        "sheath_length",
        "stiffness",
        "pretension",
        "total_angle",
        "bending_stiffness",
        "tendon_offset",
        "backbone_length",
        "proximal_radius",
        "gap_factor",
        "smoothing",
        "mode",
        "limits",
    )

    def __init__(
        self,
        friction: float = 0.1,
        sheath_length: float = 1.0,
        stiffness: float = 2.4e4,
        pretension: float = 10.0,
        total_angle: float = math.pi,
        bending_stiffness: float = 4e-4,
        tendon_offset: float = 2e-3,
        backbone_length: float = 0.03,
        proximal_radius: float = 5e-3,
        gap_factor: float = 1.0,
        smoothing: float = 0.1,
        mode: str = "exact",
        limits: LimitsLike = None,
    ):
        if mode not in _MODES:
            raise ValueError(
                f"ContinuumFeedforward: mode must be one of {list(_MODES)} (got {mode!r})"
            )
        self._settings = {
            "friction": friction,
            "sheath_length": sheath_length,
            "stiffness": stiffness,
            "pretension": pretension,
            "total_angle": total_angle,
            "bending_stiffness": bending_stiffness,
            "tendon_offset": tendon_offset,
            "backbone_length": backbone_length,
            "proximal_radius": proximal_radius,
            "gap_factor": gap_factor,
            "smoothing": smoothing,
            "mode": mode,
            "limits": as_limits(limits),
        }
        p = core.ContinuumFeedforwardParams()
        p.friction, p.sheath_length, p.stiffness = friction, sheath_length, stiffness
        p.pretension, p.total_angle = pretension, total_angle
        p.bending_stiffness, p.tendon_offset = bending_stiffness, tendon_offset
        p.backbone_length, p.proximal_radius = backbone_length, proximal_radius
        p.gap_factor, p.v_eps, p.mode = gap_factor, smoothing, _MODES[mode]
        p.limits = self._settings["limits"].to_core()
        self.mode = mode
        self._engine = core.ContinuumFeedforward(p)

    @classmethod
    def from_model(
        cls,
        model: CurveAngleModel,
        tendon_offset: float,
        backbone_length: float,
        total_angle: float,
        mode: str = "exact",
        **options: Any,
    ) -> ContinuumFeedforward:
        """Built from a ``CurveAngleModel`` identified on the continuum drive (motor angle in,
        bending angle out, its ``distal_radius`` = r_t): friction, EA, T0 and L carry over,
        and the identified environment spring k_e (N/m on the stroke) is the backbone,
        EI = k_e r_t^2 l (Li and Rahn).

        Parameters
        ----------
        model : CurveAngleModel
            Identified on the continuum drive, with a spring k_e > 0.
        tendon_offset : float
            r_t (m).
        backbone_length : float
            l (m).
        total_angle : float
            Curve angle of the sheath (rad).
        mode : {"exact", "published"}, default "exact"
            See the class.
        **options
            Other constructor settings (gap_factor, smoothing, limits).

        Returns
        -------
        ContinuumFeedforward
            The compensator.

        Raises
        ------
        ValueError
            model lacks a CurveAngleModel parameter or has no spring.
        """
        p = model.params
        missing = {"friction", "stiffness", "pretension", "length", "spring"} - set(p)
        if missing:
            raise ValueError(
                "ContinuumFeedforward.from_model needs a CurveAngleModel "
                f"(missing {sorted(missing)})"
            )
        k_e = p["spring"]
        if not k_e > 0:
            raise ValueError("ContinuumFeedforward.from_model: the model has no spring (k_e <= 0)")
        return cls(
            friction=p["friction"],
            sheath_length=p["length"],
            stiffness=p["stiffness"],
            pretension=p["pretension"],
            total_angle=total_angle,
            bending_stiffness=k_e * tendon_offset**2 * backbone_length,
            tendon_offset=tendon_offset,
            backbone_length=backbone_length,
            proximal_radius=p.get("proximal_radius", 5e-3),
            mode=mode,
            **options,
        )

    def bending_force(self, theta_d: float) -> float:
        """Tendon pulling force of the bent segment, F = kappa EI / r_t (N).

        Parameters
        ----------
        theta_d : float
            Bending angle of the segment (rad).

        Returns
        -------
        float
            F (N).
        """
        return self._engine.bending_force(float(theta_d))
