"""The inverse of a :class:`~tendonsheath.models.Coupled` model, as a feedforward for coupled
joints (one motor command per joint each cycle, no distal sensor; C++ ``CoupledFeedforward``
of ``tendonsheath/compensators/coupled_feedforward.hpp``)."""

from __future__ import annotations

import functools
from typing import Any

import numpy as np

from .._util.arrays import as_vector, checked_dt
from .._util.pyobject import PythonObject
from .._util.typing import ArrayLike, FloatArray
from ..models import Coupled
from ..plant.coupled import _joint_matrix
from ..simulation_result import SimulationResult
from ..status import Status
from . import _bound as core
from . import persistence
from ._kinds import require_model
from .base import SavedAsJson
from .inverse_feedforward import InverseFeedforward


class CoupledFeedforward(PythonObject, SavedAsJson, core.CoupledFeedforward):  # type: ignore[misc]
    """Motor commands that make a :class:`~tendonsheath.models.Coupled` model's joints follow
    their desired angles.

    Joint i's angle is H_i(x_i) + sum_j C[i, j] y_j: with every joint on its desired angle,
    joint i's own model must give h_i = y_d,i - sum_j C[i, j] y_d,j, so each cycle
    x_i = H_i^-1(h_i), each H_i^-1 an :class:`InverseFeedforward` of joint i's model. The
    coupling acts through the other joints' angles (their cables' idlers turn with them), so
    it is taken from the desired angles, not from the other joints' commands (which jump by a
    backlash at every reversal that the joints do not make).

    It runs in the real-time C++ core (``step`` is noexcept and allocates nothing; a
    non-finite desired angle holds its joint's command, and the other joints' coupling terms
    use its last finite value).

    Parameters
    ----------
    model : Coupled
        The identified coupled model.
    **settings
        :class:`InverseFeedforward` settings (``smoothing``, ``limits``, ``input_range``, ...),
        the same for every joint.

    Raises
    ------
    TypeError
        A model that is not a Coupled model, or a joint model without an inverse.
    ValueError
        A bad setting (as InverseFeedforward says).
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    model: Coupled
    settings: dict[str, Any]

    # the keys of a saved file (to_json): the Coupled model whole and the joints' settings,
    # defaults resolved; tendonsheath/io/json_multi_input.hpp reads it
    # the joints' inverses (the C++ class's joints() counts them)
    joints: list[InverseFeedforward]  # type: ignore[assignment]
    _saved_settings = ("model", "smoothing", "limits", "input_range", "range_margin", "filter_hz")
    # absent input_range: each joint's own model's range (InverseFeedforward's "identified")
    _optional_settings = ("input_range",)

    def __init__(self, model: Coupled, **settings: Any):
        require_model("CoupledFeedforward", model, Coupled)
        self.model = model
        self.settings = dict(settings)
        # each joint's inverse, as built from its model and the settings (the C++ object
        # steps copies of them)
        self.joints = [InverseFeedforward(m, **settings) for m in model.models]
        self._coupling = model.coupling
        core.CoupledFeedforward.__init__(self, self.joints, self._coupling.ravel().tolist())

    @property
    def params(self) -> dict[str, Any]:
        """The constructor's arguments: the Coupled model and the settings given (a copy)."""
        return {"model": self.model, **self.settings}

    def _configuration(self) -> dict[str, Any]:
        # get_params (tendonsheath._util.pyobject)
        return self.params

    def _recipe(self):
        # pickled as its model and settings: an equal compensator at rest (_util.pyobject)
        return functools.partial(CoupledFeedforward, self.model, **self.settings), ()

    def own_targets(self, y_desired: ArrayLike) -> FloatArray:
        """What each joint's own model must output: y_d - C y_d (shape as y_desired).

        Parameters
        ----------
        y_desired : array_like of float, shape (J,) or (n, J)
            Desired joint angles.

        Returns
        -------
        numpy.ndarray of float
            The joints' own targets h.
        """
        yd = np.asarray(y_desired, dtype=np.float64)
        return yd - yd @ self._coupling.T

    def reset(self) -> None:
        """Every joint's inverse back to its initial state."""
        core.CoupledFeedforward.reset(self)

    def step(self, y_d: ArrayLike, dt: float) -> FloatArray:
        """One control cycle: one command per joint.

        Parameters
        ----------
        y_d : array_like of float, shape (J,)
            Desired joint angles (a non-finite one holds its joint's command).
        dt : float
            Time since the previous cycle (s), >= 0.

        Returns
        -------
        numpy.ndarray of float, shape (J,)
            The motor commands.

        Raises
        ------
        ValueError
            y_d of the wrong size, or a bad dt.
        """
        dt = checked_dt(dt)
        yd = np.ascontiguousarray(np.asarray(y_d, dtype=np.float64).reshape(-1))
        if yd.size != len(self.joints):
            raise ValueError(
                f"CoupledFeedforward.step: y_d must hold {len(self.joints)} angles, one per "
                f"joint (got {yd.size})"
            )
        return core.CoupledFeedforward.step(self, yd, dt)

    def status(self) -> Status:
        """The last cycle's :class:`~tendonsheath.Status`, all joints' flags together.

        Returns
        -------
        Status
            The union of the joints' flags.
        """
        return Status(core.CoupledFeedforward.status(self))

    def command(self, t: ArrayLike, y_desired: ArrayLike) -> SimulationResult:  # type: ignore[override]
        """Motor commands for whole trajectories, from the initial state (the streaming
        state is not touched), with each cycle's flags (all joints' together).

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing.
        y_desired : array_like of float, shape (n, J)
            Desired joint angles, one column per joint.

        Returns
        -------
        SimulationResult, shape (n, J)
            The motor commands (an array), with ``t``, ``input`` (y_desired) and ``status``
            (each cycle's :class:`~tendonsheath.Status` flags of every joint, uint8, shape (n,)).

        Raises
        ------
        ValueError
            Desired angles of the wrong shape or not finite, or a bad t.
        """
        yd = _joint_matrix(y_desired, len(self.joints), "y_desired", "CoupledFeedforward.command")
        ts = np.ascontiguousarray(as_vector(t, "t"))
        commands, flags = core.CoupledFeedforward.command(self, ts, yd)
        return SimulationResult(commands, t=ts, input=yd, status=flags)

    # -- persistence -----------------------------------------------------------------
    def to_dict(self) -> dict:
        """The compensator as a dict (format ``tendonsheath.compensator``): the Coupled model
        whole and the joints' settings, defaults resolved; ``input_range`` only when one was
        given (else each joint takes its own model's range).

        Returns
        -------
        dict
            What :func:`~tendonsheath.compensate.load_compensator` reads back.
        """
        settings = {k: v for k, v in self.joints[0].params.items() if k != "model"}
        if isinstance(self.settings.get("input_range", "identified"), str):
            del settings["input_range"]  # "identified": each joint's own, saved in its model
        return persistence.compensator_dict("CoupledFeedforward", {"model": self.model, **settings})

    @classmethod
    def _from_saved(cls, values: dict) -> CoupledFeedforward:
        settings = dict(values)
        return cls(settings.pop("model"), **settings)

    def __repr__(self) -> str:
        return f"CoupledFeedforward({self.model!r})"


__all__ = ["CoupledFeedforward"]
