"""An encoder-like sensor: quantisation and seeded Gaussian noise (C++: plant/sensor.hpp)."""

from __future__ import annotations

import numpy as np

from . import _core as core
from ._args import integer, number, python_names
from ._typing import ArrayLike, FloatArray
from .status import Status


class Sensor:
    """Reading y = quantise(x + noise): noise ~ N(0, noise_std^2), steps of ``resolution``.

    ``resolution`` 0 means no quantisation. The noise sequence is fixed by ``seed`` (the same
    on every platform); :meth:`reset` restarts it.

    Parameters
    ----------
    resolution : float, default 0.0
        Quantisation step (unit of x), >= 0; 0 means none.
    noise_std : float, default 0.0
        Standard deviation of the Gaussian noise (unit of x), >= 0.
    seed : int, default 0
        Seed of the noise sequence, >= 0.

    Raises
    ------
    ValueError
        A negative or non-finite value.
    """

    def __init__(self, resolution: float = 0.0, noise_std: float = 0.0, seed: int = 0):
        p = core.SensorParams()
        p.resolution = number("Sensor", "resolution", resolution)
        p.noise_std = number("Sensor", "noise_std", noise_std)
        if integer("Sensor", "seed", seed) < 0:
            raise ValueError(f"Sensor: seed must be >= 0 (got {seed})")
        p.seed = int(seed)
        self._params = p
        with python_names("Sensor"):
            self._engine = core.Sensor(p)  # validates

    @property
    def resolution(self) -> float:
        """Quantisation step (0: none)."""
        return self._params.resolution

    @property
    def noise_std(self) -> float:
        """Standard deviation of the noise."""
        return self._params.noise_std

    @property
    def seed(self) -> int:
        """Seed of the noise sequence."""
        return self._params.seed

    def reset(self) -> None:
        """Restart the noise sequence from its seed."""
        self._engine.reset()

    def measure(self, x: ArrayLike) -> float | FloatArray:
        """One reading per value of x (scalar or array), continuing the noise sequence.

        Parameters
        ----------
        x : float or array_like of float
            True value(s).

        Returns
        -------
        float or numpy.ndarray of float
            The reading(s), shaped as x.
        """
        arr = np.asarray(x, dtype=np.float64)
        if arr.ndim == 0:
            return self._engine.measure(float(arr))
        return self._engine.measure_many(np.ascontiguousarray(arr.ravel())).reshape(arr.shape)

    def status(self) -> Status:
        """The last reading's :class:`~tendonsheath.Status` (held when x was not finite).

        Returns
        -------
        Status
            The flags of the last reading.
        """
        return Status(self._engine.status())

    def __repr__(self) -> str:
        return (
            f"Sensor(resolution={self.resolution:g}, noise_std={self.noise_std:g}, "
            f"seed={self.seed})"
        )
