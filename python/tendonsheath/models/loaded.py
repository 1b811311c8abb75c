"""A hysteresis model with a measured load: the offset and the dead band a load causes.

Physics (spec A and S000, quasi-static): the load on the distal joint is carried by the
tendon, which stretches in proportion to it, so the output moves by ``gain * load`` (the
drive's compliance, in output units per load unit). The load also changes the dead band
the input must cross at a reversal. Two effects, both functions of ``|load|``:

- slack taken up: a load on one side preloads the tendon pair and closes the play of the
  slack side (the dead band shrinks with the load), ``slack * exp(-|load| / slack_load)``;
- sheath friction: the friction along the route scales with the tendon tension (capstan),
  so the dead band grows with the load, ``friction * |load|``.

Their sum ``r(load)`` is the half-width of a play operator on the input, in front of the
base model (the play of the unloaded drive stays in the base model):

    y = base(play_r(load)(x)) + gain * load

The base is any hysteresis model (a class, instantiated with its defaults, or a model);
``ts.identify(Loaded(Backlash), recordings=[...], load=[...])`` identifies the base and the
load terms jointly (see :mod:`tendonsheath.identify.loaded`). ``load`` is whatever the user
measured (a jaw torque in N m, a tension in N, a motor current in A): the parameters are in
its unit. Rate-independent when the base is.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._util.args import number
from .._util.typing import ArrayLike, FloatArray
from ..simulation_result import SimulationResult
from ..status import Status
from .base import FORMAT_NAME, FORMAT_VERSION, HysteresisModel, split_wrapped_changes

#: the load terms, in the order of Loaded's parameters
LOAD_TERMS = ("gain", "slack", "slack_load", "friction")


def play_radius(load: ArrayLike, slack: float, slack_load: float, friction: float) -> FloatArray:
    """The load's play half-width r(load) = slack exp(-|load| / slack_load) + friction |load|.

    Parameters
    ----------
    load : float or array_like of float
        The measured load (any unit).
    slack, slack_load, friction : float
        Loaded's parameters (slack >= 0, slack_load > 0, friction >= 0).

    Returns
    -------
    numpy.ndarray of float
        The half-width (input unit), >= 0, shaped as load.
    """
    a = np.abs(np.asarray(load, dtype=float))
    return slack * np.exp(-a / slack_load) + friction * a


def play(x: ArrayLike, radius: ArrayLike, start: float | None = None) -> FloatArray:
    """A play operator with a per-sample half-width: z_k = clip(z_{k-1}, x_k - r_k, x_k + r_k).

    Parameters
    ----------
    x : array_like of float
        The input.
    radius : float or array_like of float
        The half-width of every sample (>= 0).
    start : float, optional
        The state before the first sample (default x[0]: the middle of the band).

    Returns
    -------
    numpy.ndarray of float
        The play's output.
    """
    xs = np.asarray(x, dtype=float)
    rs = np.broadcast_to(np.asarray(radius, dtype=float), xs.shape)
    lo, hi = (xs - rs).tolist(), (xs + rs).tolist()
    z = float(xs[0]) if start is None and xs.size else float(start or 0.0)
    out = [0.0] * xs.size
    for k in range(xs.size):  # sequential by nature; lists are ~5x faster than arrays here
        if z < lo[k]:
            z = lo[k]
        elif z > hi[k]:
            z = hi[k]
        out[k] = z
    return np.asarray(out)


class Loaded(HysteresisModel):
    """y = base(play_r(load)(x)) + gain * load, r(load) = slack exp(-|load|/slack_load) +
    friction |load| (see the module for the physics).

    Parameters are ``base.<name>`` and the four load terms. ``simulate`` and ``step`` need the
    measured load (``load=``, per sample or one number; ``load=0.0`` for an unloaded drive):
    without it they raise, never assume a load of 0.

    Parameters
    ----------
    base : HysteresisModel or type
        The hysteresis model of the unloaded drive, or its class (instantiated with defaults).
    gain : float, default 0.0
        Output per unit load (the drive's compliance; any sign).
    slack : float, default 0.0
        The play's half-width at zero load (input unit), >= 0.
    slack_load : float, default 1.0
        The load over which the slack closes (load unit), > 0.
    friction : float, default 0.0
        The play's growth per unit |load| (input unit per load unit), >= 0.

    Raises
    ------
    ValueError
        A value not finite, slack or friction < 0, slack_load not > 0, or a Loaded base.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    base: HysteresisModel
    terms: dict[str, float]

    param_names = ()
    option_names = ()

    def __init__(
        self,
        base: HysteresisModel | type[HysteresisModel],
        gain: float = 0.0,
        slack: float = 0.0,
        slack_load: float = 1.0,
        friction: float = 0.0,
    ):
        if isinstance(base, type) and issubclass(base, HysteresisModel):
            base = base()
        if not isinstance(base, HysteresisModel) or isinstance(base, Loaded):
            raise TypeError(
                "Loaded: base must be a tendonsheath model or model class, not a Loaded one "
                f"(got {type(base).__name__})"
            )
        values = [
            number("Loaded", k, v)
            for k, v in zip(LOAD_TERMS, (gain, slack, slack_load, friction), strict=True)
        ]
        _check_terms(dict(zip(LOAD_TERMS, values, strict=True)))
        self.base = base
        self.terms = dict(zip(LOAD_TERMS, values, strict=True))
        self.rate_independent = base.rate_independent
        self.control_inputs = ("x", "load")
        self._z: float | None = None  # the play's streaming state
        self._load: float | None = None  # the last finite load (held over a lost sample)

    # -- parameters ------------------------------------------------------------------
    @property
    def params(self) -> dict[str, Any]:
        """The base's parameters as ``base.<name>`` and the four load terms (a copy)."""
        out = {f"base.{k}": v for k, v in self.base.params.items()}
        out.update(self.terms)
        return out

    @property
    def options(self) -> dict[str, Any]:
        """No options of its own: an empty dict."""
        return {}

    def with_params(self, **changes: Any) -> Loaded:
        """A new Loaded model with some parameters changed.

        Parameters
        ----------
        **changes
            New values by ``base.<name>`` or by load term name.

        Returns
        -------
        Loaded
            A new model; this one is unchanged.

        Raises
        ------
        TypeError
            An unknown name.
        """
        base, terms = split_wrapped_changes(changes, "base", self.terms, "Loaded")
        new_base = self.base.with_params(**base) if base else self.base
        model = Loaded(new_base, **terms)
        model.input_range = self.input_range
        return model

    def radius(self, load: ArrayLike) -> FloatArray:
        """The load's play half-width r(load) (input unit).

        Parameters
        ----------
        load : float or array_like of float
            The measured load.

        Returns
        -------
        numpy.ndarray of float
            r(load), shaped as load.
        """
        t = self.terms
        return play_radius(load, t["slack"], t["slack_load"], t["friction"])

    # -- simulation ------------------------------------------------------------------
    def _loads(self, x: np.ndarray, load: ArrayLike | None) -> np.ndarray:
        if load is None:
            raise ValueError(
                "Loaded.simulate needs the measured load (load=, one number or one per "
                "sample; load=0.0 for an unloaded drive): the output depends on it"
            )
        arr = np.asarray(load, dtype=float)
        if arr.ndim == 0:
            arr = np.full_like(x, float(arr))
        if arr.shape != x.shape:
            raise ValueError(f"Loaded: load has {arr.size} samples, x has {x.size}")
        if not np.all(np.isfinite(arr)):
            raise ValueError("Loaded: the load must be finite")
        return arr

    def _simulate(  # the measured load besides the input
        self,
        t: ArrayLike | None,
        x: ArrayLike,
        load: ArrayLike | None = None,
        **kwargs: Any,
    ) -> SimulationResult:
        """Output for the input x under the measured load (from the initial state).

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); None when the base is rate-independent.
        x : array_like of float, shape (n,)
            Input samples.
        load : float or array_like of float, shape (n,)
            The measured load of every sample (or one for all); required.
        **kwargs
            Passed to the base's ``simulate`` (e.g. ``curve_angle``).

        Returns
        -------
        SimulationResult, shape (n,)
            Output samples, with ``status`` the base's per-sample Status flags (all zero for
            a base without a status).

        Raises
        ------
        ValueError
            No load, a load of another length than x, or not finite; the base's own errors.
        """
        xs = np.asarray(x, dtype=float)
        loads = self._loads(xs, load)
        z = play(xs, self.radius(loads))
        out = self.base.simulate(t, z, **kwargs)
        y = np.asarray(out, dtype=float) + self.terms["gain"] * loads
        flags = out.status if out.status is not None else np.zeros(xs.size, dtype=np.uint8)
        return SimulationResult(y, status=flags)

    def reset(self) -> None:
        """Forget the streaming state (the play's and the base's)."""
        self.base.reset()
        self._z = None
        self._load = None

    def step(self, x: float, dt: float = 0.0, load: float | None = None) -> float:
        """Advance one sample (streaming) under the measured load.

        Parameters
        ----------
        x : float
            The input sample.
        dt : float, default 0.0
            Time since the previous sample (s).
        load : float
            The load measured at this sample (required; a non-finite one, a lost sample,
            holds the last finite one).

        Returns
        -------
        float
            The output sample.

        Raises
        ------
        ValueError
            No load, or a non-finite one before any finite load since the reset.
        """
        if load is None:
            raise ValueError(
                "Loaded.step needs the measured load (load=; 0.0 for an unloaded drive): the "
                "output depends on it"
            )
        x, load = float(x), float(load)
        if not math.isfinite(load):
            if self._load is None:
                raise ValueError("Loaded.step: the load is not finite and none came before it")
            load = self._load  # a lost load sample: hold the last one
        self._load = load
        r = float(self.radius(load))
        z = x if self._z is None else min(max(self._z, x - r), x + r)
        self._z = z
        return self.base.step(z, dt) + self.terms["gain"] * load

    @property
    def reports_status(self) -> bool:  # type: ignore[override]  # the base's flag
        """Whether the base reports a Status."""
        return self.base.reports_status

    def status(self) -> Status:
        """The base's last step's Status.

        Returns
        -------
        Status
            The base's flags.
        """
        return self.base.status()

    def _control_step(self, u, dt: float) -> float:
        return self.step(float(u[0]), dt, float(u[1]))

    # -- persistence -----------------------------------------------------------------
    def _dict_fields(self) -> dict[str, Any]:
        """The model as a JSON-ready dict: the base whole and the load terms.

        Returns
        -------
        dict
            format, version, model ("Loaded"), base and terms.
        """
        return {
            "format": FORMAT_NAME,
            "version": FORMAT_VERSION,
            "model": "Loaded",
            "base": self.base.to_dict(),
            "terms": dict(self.terms),
        }

    @classmethod
    def _from_parts(cls, data: dict[str, Any]) -> Loaded:
        try:
            base, terms = data["base"], data["terms"]
        except KeyError as exc:
            raise ValueError(f"Loaded file is missing its '{exc.args[0]}' part") from None
        if not isinstance(terms, dict):
            raise ValueError("Loaded file: 'terms' must be an object")
        unknown = set(terms) - set(LOAD_TERMS)
        if unknown:
            raise ValueError(f"Loaded: unknown term(s) {sorted(unknown)}; expected {LOAD_TERMS}")
        missing = [k for k in LOAD_TERMS if k not in terms]
        if missing:  # strict, like the C++ loader (to_dict writes all four)
            raise ValueError(f"Loaded file: term(s) {missing} missing from 'terms'")
        for key, value in terms.items():
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValueError(f"Loaded file: term '{key}' must be a number (got {value!r})")
        return cls(HysteresisModel.from_dict(base), **terms)

    def __repr__(self) -> str:
        m = ", ".join(f"{k}={v:.6g}" for k, v in self.terms.items())
        return f"Loaded({self.base!r}, {m})"


def _check_terms(terms: dict[str, float]) -> None:
    """The rule of the C++ ``LoadTerms::validate``, with its messages (one per term)."""
    for name, v in terms.items():
        if name == "gain":
            ok, bound = math.isfinite(v), "finite"
        elif name == "slack_load":
            ok, bound = math.isfinite(v) and v > 0, "> 0"
        else:  # slack, friction
            ok, bound = math.isfinite(v) and v >= 0, ">= 0"
        if not ok:
            raise ValueError(f"Loaded: {name} must be {bound} (got {v:g})")


__all__ = ["LOAD_TERMS", "Loaded", "play", "play_radius"]
