"""An encoder-like sensor: latency, quantisation and seeded Gaussian noise (C++:
plant/sensor.hpp)."""

from __future__ import annotations

import functools
import inspect

import numpy as np

from .._util.args import core_errors_as, integer, number
from .._util.arrays import as_vector, checked_dt
from .._util.param_table import TABLE, table_constructor
from .._util.pyobject import PythonObject, bound_attribute
from .._util.typing import ArrayLike, FloatArray
from .._util.units import warn_unit_slips
from ..status import Status
from . import _bound as core


@table_constructor(core.SensorParams)
class Sensor(PythonObject, core.Sensor):  # type: ignore[misc]
    """Reading y = quantise(x(t - delay) + noise): noise ~ N(0, noise_std^2), steps of
    ``resolution``, ``delay`` seconds of latency.

    ``resolution`` 0 means no quantisation. The noise sequence is fixed by ``seed`` (the same
    on every platform); :meth:`reset` restarts it. With ``delay`` > 0 each reading is of the
    true value ``delay`` seconds before, linearly interpolated between the last ``history``
    samples (the first sample until there is enough history); a delay longer than the history
    covers reads the oldest sample kept and flags ``Status.INPUT_CLAMPED``. ``bench.run`` feeds
    the controller this delayed reading.

    Raises
    ------
    ValueError
        A negative or non-finite value, or a history out of range.
    """

    def __init__(
        self,
        resolution: float = TABLE,
        noise_std: float = TABLE,
        seed: int = TABLE,
        delay: float = TABLE,
        history: int = TABLE,
    ):
        p = core.SensorParams()
        p.resolution = number("Sensor", "resolution", resolution)
        p.noise_std = number("Sensor", "noise_std", noise_std)
        if integer("Sensor", "seed", seed) < 0:
            raise ValueError(f"Sensor: seed must be >= 0 (got {seed})")
        p.seed = int(seed)
        p.delay = number("Sensor", "delay", delay)
        if not 1 <= integer("Sensor", "history", history) <= core.Sensor.MAX_HISTORY:
            raise ValueError(
                f"Sensor: history must be in [1, {core.Sensor.MAX_HISTORY}] samples (got {history})"
            )
        p.history = int(history)
        with core_errors_as("Sensor"):
            core.Sensor.__init__(self, p)  # validates
        warn_unit_slips("Sensor", p)

    def _recipe(self):
        # pickled as its settings: an equal sensor at rest (tendonsheath._util.pyobject)
        return functools.partial(Sensor, **self.params), ()

    @property
    def params(self) -> dict:  # type: ignore[override]
        """The sensor's settings by the names of its constructor (a copy)."""
        p = self._struct()
        return {k: getattr(p, k) for k in inspect.signature(Sensor).parameters}

    @property
    def resolution(self) -> float:
        """Quantisation step (0: none)."""
        return self._struct().resolution

    @property
    def noise_std(self) -> float:
        """Standard deviation of the noise."""
        return self._struct().noise_std

    @property
    def seed(self) -> int:
        """Seed of the noise sequence."""
        return self._struct().seed

    @property
    def delay(self) -> float:
        """Latency (s): a reading is of the true value this long before (0: none)."""
        return self._struct().delay

    @property
    def history(self) -> int:
        """Samples kept for the delay."""
        return self._struct().history

    def _struct(self) -> core.SensorParams:
        """The C++ parameter struct (the bound class's ``params``)."""
        return bound_attribute(self, "params")

    def engine(self) -> core.Sensor:
        """A copy of the C++ sensor engine this sensor built (and validated) once, at rest (its
        noise sequence from the seed): what a plant's simulation and
        :func:`tendonsheath.bench.run` read the output with.

        Returns
        -------
        tendonsheath._core.Sensor
            An independent engine (reading with it leaves this sensor's own state alone).
        """
        copy = core.Sensor(self)
        copy.reset()
        return copy

    def reset(self) -> None:
        """Restart the noise sequence from its seed and empty the history."""
        core.Sensor.reset(self)

    def measure(  # type: ignore[override]
        self, x: ArrayLike, t: ArrayLike | None = None, dt: float = 0.0
    ) -> float | FloatArray:
        """One reading per value of x (scalar or array), continuing the noise sequence and
        the history.

        A scalar x is one sample, ``dt`` seconds after the previous call (0: no time passes,
        and it replaces the previous sample). An array is a sequence of samples at the times
        ``t`` (required when ``delay`` > 0), its first sample ``dt`` after the previous call.

        Parameters
        ----------
        x : float or array_like of float
            True value(s).
        t : array_like of float, optional
            The sample times of an array x (s), finite and increasing, shaped as x.
        dt : float, default 0.0
            Time since the previous call (s), >= 0: a scalar's, or an array's first sample's.

        Returns
        -------
        float or numpy.ndarray of float
            The reading(s), shaped as x.

        Raises
        ------
        ValueError
            t missing for an array when ``delay`` > 0, given for a scalar, or not finite,
            increasing and shaped as x; a negative or non-finite dt.
        """
        arr = np.asarray(x, dtype=np.float64)
        step = checked_dt(dt)
        if arr.ndim == 0:
            if t is not None:
                raise ValueError("Sensor.measure: t is for an array x; a scalar x takes dt")
            return core.Sensor.measure(self, float(arr), step)
        times = self._times(t, arr)
        flat = np.ascontiguousarray(arr.ravel())
        return self.measure_many(flat, times, step).reshape(arr.shape)

    def _times(self, t: ArrayLike | None, arr: np.ndarray) -> np.ndarray | None:
        """The checked sample times of an array reading (None when not given and not needed)."""
        if t is None:
            if self.delay > 0.0 and arr.size > 1:
                raise ValueError(
                    f"Sensor.measure: a sensor with delay {self.delay:g} s needs the sample "
                    "times t of an array x"
                )
            return None
        times = as_vector(t, "t")
        if times.size != arr.size:
            raise ValueError(
                f"Sensor.measure: t and x have different sizes ({times.size} and {arr.size})"
            )
        if not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0.0):
            raise ValueError("Sensor.measure: t must be finite and strictly increasing")
        return times

    def status(self) -> Status:
        """The last reading's :class:`~tendonsheath.Status`: held when x was not finite,
        input_clamped when the history was too short for the delay.

        Returns
        -------
        Status
            The flags of the last reading.
        """
        return Status(core.Sensor.status(self))

    def __repr__(self) -> str:
        extra = f", delay={self.delay:g}, history={self.history}" if self.delay > 0.0 else ""
        return (
            f"Sensor(resolution={self.resolution:g}, noise_std={self.noise_std:g}, "
            f"seed={self.seed}{extra})"
        )


__all__ = ["Sensor"]
