"""Coupled joints: each joint's own hysteresis model of its own input, plus terms linear in the
other joints' positions (cables that run over other joints' pulleys, as in a wrist)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from .._util.args import is_format_version
from .._util.atomic import write_text
from .._util.json_source import naming_the_file, read_json_source
from .._util.pyobject import PythonObject
from .._util.typing import ArrayLike, FloatArray
from ..plant.coupled import _coupling_matrix, _joint_matrix
from ..simulation_result import SimulationResult
from .base import HysteresisModel, load_model

FORMAT_NAME = "tendonsheath.coupled_model"
FORMAT_VERSION = 1


class Coupled(PythonObject):
    """A multi-input model of J coupled joints: y_i = H_i(x_i) + sum_j C[i, j] y_j.

    ``H_i`` is joint i's own single-input model (any :class:`HysteresisModel`) of its own input
    x_i (its motor angle); ``C`` (zero diagonal) is the coupling: how much joint i turns per
    radian of joint j. The joints' angles are then y = (I - C)^-1 h with h_i = H_i(x_i).

    Parameters
    ----------
    models : sequence of HysteresisModel
        One model per joint.
    coupling : array_like, shape (J, J)
        C[i, j]: joint i's angle per radian of joint j (zero diagonal, I - C invertible).

    Raises
    ------
    TypeError
        A joint model that is not a tendonsheath model.
    ValueError
        No models, or a coupling of the wrong shape, not finite, with a non-zero diagonal or
        with I - C singular.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    models: list[HysteresisModel]

    def __init__(self, models: Sequence[HysteresisModel], coupling: ArrayLike):
        self.models = list(models)
        if not self.models:
            raise ValueError("Coupled: give at least one joint model")
        for i, m in enumerate(self.models):
            if not isinstance(m, HysteresisModel):
                raise TypeError(
                    f"Coupled: joint {i}'s model must be a tendonsheath model "
                    f"(got {type(m).__name__})"
                )
        self._coupling = _coupling_matrix(coupling, len(self.models), "Coupled")
        self._solve = np.linalg.inv(np.eye(self.joints) - self._coupling)

    @property
    def joints(self) -> int:
        """The number of joints J."""
        return len(self.models)

    @property
    def coupling(self) -> FloatArray:
        """The coupling matrix C (a copy)."""
        return self._coupling.copy()

    def own(self, t: ArrayLike | None, x: ArrayLike) -> FloatArray:
        """Each joint's own model on its own input, h_i = H_i(x_i) (no coupling).

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); None for rate-independent joint models.
        x : array_like of float, shape (n, J)
            One column of inputs per joint.

        Returns
        -------
        numpy.ndarray of float, shape (n, J)
            The joints' own outputs.
        """
        return np.column_stack([np.asarray(r) for r in self._own_runs(t, x)[1]])

    def _own_runs(self, t, x) -> tuple[FloatArray, list]:
        """(the inputs as a matrix, each joint model's simulate result on its column)."""
        xs = _joint_matrix(x, self.joints, "x", "Coupled")
        return xs, [m.simulate(t, xs[:, i]) for i, m in enumerate(self.models)]

    def simulate(self, t: ArrayLike | None, x: ArrayLike) -> SimulationResult:
        """The joints' angles from their inputs alone: y = (I - C)^-1 h.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); None for rate-independent joint models.
        x : array_like of float, shape (n, J)
            One column of inputs per joint.

        Returns
        -------
        SimulationResult, shape (n, J)
            The joints' angles (an array), with ``t``, ``input`` (x) and ``status`` (each
            sample's flags of every joint model together, uint8, shape (n,); None when no joint
            model reports any).
        """
        xs, runs = self._own_runs(t, x)
        own = np.column_stack([np.asarray(r) for r in runs])
        flags = [r.status for r in runs if getattr(r, "status", None) is not None]
        status = np.bitwise_or.reduce(np.stack(flags), axis=0) if flags else None
        ts = None if t is None else np.asarray(t, dtype=np.float64)
        return SimulationResult(own @ self._solve.T, t=ts, input=xs, status=status)

    def predict(self, t: ArrayLike | None, x: ArrayLike, y: ArrayLike) -> FloatArray:
        """Each joint's angle from its own input and the other joints' measured angles,
        H_i(x_i) + sum_j C[i, j] y_j (what :func:`~tendonsheath.identify.identify_coupled`
        fits).

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s).
        x : array_like of float, shape (n, J)
            The joints' inputs.
        y : array_like of float, shape (n, J)
            The joints' measured angles.

        Returns
        -------
        numpy.ndarray of float, shape (n, J)
            The predicted angles.
        """
        ys = _joint_matrix(y, self.joints, "y", "Coupled.predict")
        return self.own(t, x) + ys @ self._coupling.T

    def with_coupling(self, coupling: ArrayLike) -> Coupled:
        """The same joint models with another coupling matrix.

        Parameters
        ----------
        coupling : array_like, shape (J, J)
            The new C (zero diagonal).

        Returns
        -------
        Coupled
            A new model; this one is unchanged.
        """
        return Coupled(self.models, coupling)

    # -- saving ----------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """The model as a JSON-ready dict (each joint's model saved whole).

        Returns
        -------
        dict
            What :meth:`from_dict` reads back.
        """
        return {
            "format": FORMAT_NAME,
            "version": FORMAT_VERSION,
            "models": [m.to_dict() for m in self.models],
            "coupling": self._coupling.tolist(),
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Coupled:
        """The model saved by :meth:`to_dict`.

        Parameters
        ----------
        data : dict
            A saved coupled model.

        Returns
        -------
        Coupled
            The saved model.

        Raises
        ------
        ValueError
            Not a saved coupled model: a missing or unknown key, models not a list of model
            objects, or coupling not rows of numbers.
        """
        if not isinstance(data, dict) or data.get("format") != FORMAT_NAME:
            raise ValueError(f"Coupled.from_dict: not a {FORMAT_NAME!r} file")
        if not is_format_version(data.get("version"), FORMAT_VERSION):
            raise ValueError(
                f"Coupled.from_dict: version {data.get('version')!r} is not supported "
                f"(expected {FORMAT_VERSION})"
            )
        _check_saved_keys(data)
        return cls([load_model(m) for m in data["models"]], data["coupling"])

    def to_json(self, path: str | Path | None = None) -> str:
        """The model as JSON text; also written to `path` when one is given.

        Parameters
        ----------
        path : str or Path, optional
            A file to write the JSON to (atomically).

        Returns
        -------
        str
            The JSON text.
        """
        text = json.dumps(self.to_dict(), indent=2)
        if path is not None:
            write_text(Path(path), text)
        return text

    @classmethod
    def load(cls, source: str | Path | dict) -> Coupled:
        """A model saved with :meth:`to_json`.

        Parameters
        ----------
        source : str, Path or dict
            A path to a JSON file, JSON text, or the dict itself.

        Returns
        -------
        Coupled
            The saved model.

        Raises
        ------
        ValueError
            An unreadable source or not a saved coupled model.
        """
        data = source if isinstance(source, dict) else read_json_source(source, "coupled model")
        with naming_the_file(source):
            return cls.from_dict(data)

    def __repr__(self) -> str:
        names = ", ".join(type(m).__name__ for m in self.models)
        return f"Coupled([{names}], coupling={self._coupling.tolist()})"


_SAVED_KEYS = ("format", "version", "models", "coupling")


def _check_saved_keys(data: dict[str, Any]) -> None:
    """Strict, like the C++ loader: every key known and present, models a non-empty list of
    objects, coupling a list of rows of numbers (not booleans)."""
    unknown = sorted(set(data) - set(_SAVED_KEYS))
    if unknown:
        raise ValueError(f"Coupled file: unknown key(s) {unknown}; expected {list(_SAVED_KEYS)}")
    missing = [k for k in _SAVED_KEYS if k not in data]
    if missing:
        raise ValueError(f"Coupled file: key(s) {missing} missing")
    models = data["models"]
    if not isinstance(models, list) or not models or not all(isinstance(m, dict) for m in models):
        raise ValueError("Coupled file: 'models' must be a non-empty list of model objects")
    rows = data["coupling"]
    if not isinstance(rows, list) or not all(
        isinstance(r, list)
        and all(isinstance(v, int | float) and not isinstance(v, bool) for v in r)
        for r in rows
    ):
        got = json.dumps(rows)[:60]
        raise ValueError(f"Coupled file: 'coupling' must be a list of rows of numbers (got {got})")


__all__ = ["Coupled", "FORMAT_NAME", "FORMAT_VERSION"]
