"""A hysteresis model followed by a static output map, fitted and used as one model."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._util.typing import ArrayLike
from ..simulation_result import SimulationResult
from ..status import Status
from .base import FORMAT_NAME, FORMAT_VERSION, HysteresisModel


class Chain(HysteresisModel):
    """y = second(first(x)), e.g. ``Chain(BoucWenBacklash(), Polynomial(3))``.

    Parameters are addressed as ``first.<name>`` and ``second.<name>``.

    Parameters
    ----------
    first : HysteresisModel
        The model fed with x (not a Chain).
    second : HysteresisModel
        The model fed with first's output (not a Chain).

    Raises
    ------
    ValueError
        A part that is not a tendonsheath model, or is itself a chain.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    first: HysteresisModel
    second: HysteresisModel

    param_names = ()
    option_names = ()

    def __init__(self, first: HysteresisModel, second: HysteresisModel):
        if not isinstance(first, HysteresisModel) or not isinstance(second, HysteresisModel):
            raise TypeError(
                "Chain: both parts must be tendonsheath models "
                f"(got {type(first).__name__} and {type(second).__name__})"
            )
        if isinstance(first, Chain) or isinstance(second, Chain):
            raise ValueError("Chain: parts cannot themselves be chains")
        self.first, self.second = first, second
        self.rate_independent = first.rate_independent and second.rate_independent

    @property
    def params(self) -> dict[str, Any]:
        """Both parts' parameters, as ``first.<name>`` and ``second.<name>`` (a copy)."""
        out = {f"first.{k}": v for k, v in self.first.params.items()}
        out.update({f"second.{k}": v for k, v in self.second.params.items()})
        return out

    @property
    def options(self) -> dict[str, Any]:
        """No options of its own (each part keeps its own): an empty dict."""
        return {}

    def with_params(self, **changes: Any) -> Chain:
        """A new chain with some parameters of its parts changed.

        Parameters
        ----------
        **changes
            New values by ``first.<name>`` or ``second.<name>``.

        Returns
        -------
        Chain
            A new chain; this one is unchanged.

        Raises
        ------
        ValueError
            A name that is not ``first.<name>`` or ``second.<name>``.
        """
        parts: dict[str, dict[str, Any]] = {"first": {}, "second": {}}
        for key, value in changes.items():
            part, _, name = key.partition(".")
            if part not in parts or not name:
                raise TypeError(f"Chain: parameter names are first.<name> or second.<name> ({key})")
            parts[part][name] = value
        return Chain(
            self.first.with_params(**parts["first"]), self.second.with_params(**parts["second"])
        )

    def _simulate(self, t: ArrayLike | None, x: ArrayLike) -> SimulationResult:
        """y = second(first(x)); its ``status`` holds each sample's Status flags, those of both
        parts together (a part without a status, a linear block, adds none).

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); None when both parts are rate-independent.
        x : array_like of float, shape (n,)
            Input samples.

        Returns
        -------
        SimulationResult, shape (n,)
            Output samples, with ``status`` the uint8 :class:`~tendonsheath.Status` bits of
            each sample.
        """
        u = self.first.simulate(t, x)
        t2 = None if self.second.rate_independent else t
        y = self.second.simulate(t2, u)
        flags = np.zeros(np.size(x), dtype=np.uint8)
        for out in (u, y):
            if out.status is not None:
                flags |= out.status
        return SimulationResult(y, status=flags)

    def reset(self) -> None:
        """Forget both parts' streaming state."""
        self.first.reset()
        self.second.reset()

    def step(self, x: float, dt: float = 0.0) -> float:
        """Advance one sample through both parts (streaming).

        Parameters
        ----------
        x : float
            The input sample.
        dt : float, default 0.0
            Time since the previous sample (s).

        Returns
        -------
        float
            second(first(x)).
        """
        return self.second.step(self.first.step(x, dt), dt)

    def status(self) -> Status:
        """The last step's Status of both parts (a part without a status adds none).

        Returns
        -------
        Status
            The union of both parts' flags.
        """
        s = Status.OK
        for part in (self.first, self.second):
            if part.reports_status:
                s |= part.status()
        return s

    def _dict_fields(self) -> dict[str, Any]:
        """The chain as a JSON-ready dict, each part saved whole.

        Returns
        -------
        dict
            format, version, model ("Chain"), first and second.
        """
        return {
            "format": FORMAT_NAME,
            "version": FORMAT_VERSION,
            "model": "Chain",
            "first": self.first.to_dict(),
            "second": self.second.to_dict(),
        }

    @classmethod
    def _from_parts(cls, data: dict[str, Any]) -> Chain:
        try:
            first, second = data["first"], data["second"]
        except KeyError as exc:
            raise ValueError(f"Chain file is missing its '{exc.args[0]}' part") from None
        return cls(HysteresisModel.from_dict(first), HysteresisModel.from_dict(second))

    def __repr__(self) -> str:
        return f"Chain({self.first!r}, {self.second!r})"


__all__ = ["Chain"]
