"""What every compensator built around a feedforward shares (EncoderLoop, TipLoop,
LearnedFeedforward): its flags join the feedforward's, the route goes to the feedforward, and
it is saved with its feedforward whole."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..status import Status
from .base import EngineCompensator

if TYPE_CHECKING:
    from ..plant.route import Route


def follows_route(feedforward: Any) -> bool:
    """Whether a feedforward follows the route: its ``follows_route`` where it says (an
    InverseFeedforward), else whether it takes one (CurveAngleFeedforward's ``set_route``)."""
    own = getattr(feedforward, "follows_route", None)
    if own is None:
        return callable(getattr(feedforward, "set_route", None))
    return bool(own)


class AroundFeedforward(EngineCompensator):
    """A compensator around ``self.feedforward`` (set by the subclass's constructor)."""

    feedforward: Any

    def status(self) -> Status:
        """The last cycle's flags: the feedforward's and this compensator's own (see the
        class).

        Returns
        -------
        Status
            The flags of the last step.
        """
        own = Status(self._bound_class.status(self))
        inner = getattr(self.feedforward, "status", None)
        return own | Status(int(inner())) if callable(inner) else own

    def bench_engine(self) -> None:
        """None: bench.run runs this compensator as a stage around its feedforward (the
        subclass's ``bench_stage``), not as an engine of its own.

        Returns
        -------
        None
        """
        return None

    # -- a feedforward that follows the route ------------------------------------------
    @property
    def follows_route(self) -> bool:
        """Whether the feedforward inside follows the route's shape."""
        return follows_route(self.feedforward)

    @property
    def friction(self) -> float:
        """The friction the feedforward computes route shapes with.

        Raises
        ------
        AttributeError
            The feedforward does not follow the route.
        """
        return self.feedforward.friction

    def set_route(self, route: Route) -> None:
        """Tell the feedforward the route's shape (when it follows the route).

        Parameters
        ----------
        route : Route
            The route now.
        """
        self.feedforward.set_route(route)

    def set_curve_angle(self, curve_angle: float) -> None:
        """Tell the feedforward the curve angle (when it follows the route).

        Parameters
        ----------
        curve_angle : float
            The total curve angle (rad).
        """
        self.feedforward.set_curve_angle(curve_angle)

    # -- persistence ----------------------------------------------------------------------
    @property
    def params(self) -> dict:
        """The settings and the feedforward (a copy)."""
        return {**super().params, "feedforward": self.feedforward}

    def to_dict(self) -> dict:
        """The compensator as a dict, its feedforward saved whole.

        Returns
        -------
        dict
            What :func:`~tendonsheath.compensate.load_compensator` (and the C++ loader) reads.

        Raises
        ------
        TypeError
            The feedforward cannot be saved (it has no ``to_dict``).
        """
        inner = getattr(self.feedforward, "to_dict", None)
        if not callable(inner):
            raise TypeError(
                f"{type(self).__name__}.to_dict: its feedforward "
                f"{type(self.feedforward).__name__} cannot be saved (it has no to_dict)"
            )
        return {**super().to_dict(), "feedforward": inner()}


__all__ = ["AroundFeedforward", "follows_route"]
