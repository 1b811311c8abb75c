"""Feedforward of a tendon-sheath-driven continuum segment (Lau et al. 2015, spec C)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .._util.args import core_errors_as, number
from .._util.param_table import TABLE, number_rows, row_default, table_constructor, table_defaults
from .._util.units import warn_unit_slips
from . import _bound as core
from .base import Feedforward
from .limits import LimitsLike, as_limits

if TYPE_CHECKING:
    from ..models import CurveAngleModel

_PARAMS = core.ContinuumFeedforwardParams
_MODES = {"exact": core.ContinuumMode.exact, "published": core.ContinuumMode.published}
# saved files' old keys -> vocabulary names (docs/vocabulary.md): such files still load
SAVED_AS = {"sheath_length": "length", "total_angle": "curve_angle"}


def _numbers(arguments: dict) -> dict:
    """The numeric constructor arguments (all but self, mode and limits)."""
    return {k: v for k, v in arguments.items() if k not in ("self", "mode", "limits", "who")}


@table_constructor(core.ContinuumFeedforwardParams)
class ContinuumFeedforward(Feedforward, core.ContinuumFeedforward):  # type: ignore[misc]
    """Desired bending angle (rad) in, motor angle (rad) out: X_in = X_d + delta_ts + delta_F.

    ``mode="published"`` implements Lau et al.'s equations as printed (effective backlash
    delta_0 = 2 T0 L (1 - e^{-xi Theta})/EA and a separate delta_F, which partly double
    count); ``mode="exact"`` uses the capstan-consistent full-slip elongations (spec A5/A6)
    under the bending force F = kappa EI / r_t, without double counting. ``play``, the
    motor-side play, adds S play / 2 to the motor command at the direction S.

    Parameters
    ----------
    limits : CommandLimits, tuple, dict or None, optional
        Saturation of the command and its rate (see :class:`CommandLimits`).

    Raises
    ------
    TypeError
        A value of the wrong type, or an unknown keyword.
    ValueError
        An unknown mode, or a value out of range (the message names the argument and the value).
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    mode: str

    _renamed_settings = SAVED_AS  # files written before the vocabulary still load
    _saved_settings = (
        "friction",
        "length",
        "stiffness",
        "pretension",
        "curve_angle",
        "bending_stiffness",
        "tendon_offset",
        "backbone_length",
        "proximal_radius",
        "gap_factor",
        "play",
        "smoothing",
        "mode",
        "limits",
    )

    def __init__(
        self,
        friction: float = TABLE,
        length: float = TABLE,
        stiffness: float = TABLE,
        pretension: float = TABLE,
        curve_angle: float = TABLE,
        bending_stiffness: float = TABLE,
        tendon_offset: float = TABLE,
        backbone_length: float = TABLE,
        proximal_radius: float = TABLE,
        gap_factor: float = TABLE,
        play: float = TABLE,
        smoothing: float = TABLE,
        mode: str = TABLE,
        limits: LimitsLike = None,
    ):
        who = type(self).__name__
        values = _numbers(locals())
        if not isinstance(mode, str):
            raise TypeError(f"{who}: mode must be a string (got {type(mode).__name__} {mode!r})")
        if mode not in _MODES:
            raise ValueError(f"{who}: mode must be one of {list(_MODES)} (got {mode!r})")
        self._settings = {k: number(who, k, v) for k, v in values.items()}
        self._settings.update(mode=mode, limits=as_limits(limits))
        p = core.ContinuumFeedforwardParams()
        for name in number_rows(core.ContinuumFeedforwardParams):
            setattr(p, name, self._settings[name])
        p.mode = _MODES[mode]
        p.limits = self._settings["limits"].to_core()
        self.mode = mode
        with core_errors_as(who):
            core.ContinuumFeedforward.__init__(self, p)
        warn_unit_slips(who, p)

    @classmethod
    @table_defaults(core.ContinuumFeedforwardParams)
    def from_model(
        cls,
        model: CurveAngleModel,
        tendon_offset: float,
        backbone_length: float,
        curve_angle: float,
        mode: str = TABLE,
        **options: Any,
    ) -> ContinuumFeedforward:
        """Built from a ``CurveAngleModel`` identified on the continuum drive (motor angle in,
        bending angle out, its ``distal_radius`` = r_t): friction, EA, T0 and L carry over,
        and the identified environment spring k_e (N/m on the stroke) is the backbone,
        EI = k_e r_t^2 l (Li and Rahn).

        Parameters
        ----------
        model : CurveAngleModel
            Identified on the continuum drive, with a spring k_e = load_stiffness > 0.
        tendon_offset : float
            r_t (m).
        backbone_length : float
            l (m).
        curve_angle : float
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
            model lacks a CurveAngleModel parameter or has no spring (load_stiffness <= 0).
        """
        p = model.params
        missing = {"friction", "stiffness", "pretension", "length", "load_stiffness"} - set(p)
        if missing:
            raise ValueError(
                "ContinuumFeedforward.from_model needs a CurveAngleModel "
                f"(missing {sorted(missing)})"
            )
        k_e = p["load_stiffness"]
        if not k_e > 0:
            raise ValueError(
                "ContinuumFeedforward.from_model: the model has no spring (load_stiffness <= 0)"
            )
        return cls(
            friction=p["friction"],
            length=p["length"],
            stiffness=p["stiffness"],
            pretension=p["pretension"],
            curve_angle=curve_angle,
            bending_stiffness=k_e * tendon_offset**2 * backbone_length,
            tendon_offset=tendon_offset,
            backbone_length=backbone_length,
            proximal_radius=p.get("proximal_radius", row_default(_PARAMS, "proximal_radius")),
            play=p.get("play", row_default(_PARAMS, "play")),
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
        return core.ContinuumFeedforward.bending_force(self, float(theta_d))


__all__ = ["ContinuumFeedforward", "SAVED_AS"]
