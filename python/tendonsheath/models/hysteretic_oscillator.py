"""Single-degree-of-freedom oscillator with a Bouc-Wen restoring force."""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np

from .._util.arrays import as_time_and_signal
from .._util.sampling import fft_upsample, is_periodic, uniform_step
from .._util.typing import ArrayLike
from ..simulation_result import SimulationResult
from . import _bound as core
from ._param_table import from_table
from .base import HysteresisModel

_INTERPOLATIONS = ("linear", "hold", "bandlimited")
_CODES = {"hold": 0, "linear": 1, "bandlimited": 2}


class UnboundedStateWarning(UserWarning):
    """The displacement range of a simulation or data set exceeds the range over which the
    hysteretic force z of a HystereticOscillator stays bounded."""


@from_table  # param_names, option_names, the signature, the defaults, the Parameters section
class HystereticOscillator(HysteresisModel, core.HystereticOscillator):  # type: ignore[misc]
    """Bouc-Wen oscillator: m y'' + c y' + k y + z = u, with the hysteretic force z:

    z' = alpha y' - beta (gamma |y'| |z|^(nu-1) z + delta y' |z|^nu).

    Force u in, displacement y out, starting at rest. RK4 with at least ``substeps``
    sub-steps per sample (raised automatically for stability, at most ``max_substeps``).

    Any sign of ``gamma + delta`` is accepted: ``beta (gamma + delta) < 0`` is a softening
    loop (z grows with the displacement, as in the Bouc-Wen benchmark system), bounded over
    a bounded excitation when unloading contracts it. :meth:`z_bound` bounds |z| over a
    displacement range; :meth:`simulate` warns (:class:`UnboundedStateWarning`) when the
    simulated displacement leaves the range where that bound is finite, and raises a
    ValueError when z actually diverges.

    ``input_interpolation`` (the input reconstruction between samples):

    - ``"linear"`` (the default) or ``"hold"``;
    - ``"bandlimited"``: the input is treated as band-limited. :meth:`simulate` upsamples a
      periodic record exactly by FFT zero padding (``periodic=True``, or detected: the
      record's periodic extension has no energy above 0.4 of the sampling rate) and
      otherwise uses a Kaiser-windowed sinc of half-width ``lookahead`` samples. The
      streaming :meth:`step` uses the same windowed sinc, so its output lags the input by
      :attr:`delay` = ``lookahead - 1`` samples. Needs uniform sampling.

    Raises
    ------
    ValueError
        An unknown input_interpolation or a parameter the C++ core rejects.
    """

    _core_params = core.HystereticOscillatorParams
    rate_independent = False  # type: ignore[misc]

    @classmethod
    def _core_values(cls, values: dict[str, Any]) -> dict[str, Any]:
        if "input_interpolation" not in values:
            return values
        mode = values["input_interpolation"]
        if mode not in _INTERPOLATIONS:
            raise ValueError(
                f"HystereticOscillator: input_interpolation must be one of {_INTERPOLATIONS} "
                f"(got {mode!r})"
            )
        return {**values, "input_interpolation": _CODES[mode]}

    @classmethod
    def _python_value(cls, name: str, value: Any) -> Any:
        if name == "input_interpolation":  # the C++ field holds its code
            return {code: mode for mode, code in _CODES.items()}[value]
        return super()._python_value(name, value)

    @property
    def input_interpolation(self) -> str:
        """The input reconstruction between samples: "linear", "hold" or "bandlimited"."""
        return self.options["input_interpolation"]

    @property
    def delay(self) -> int:  # type: ignore[override]
        """Samples by which :meth:`step`'s output lags its input (``lookahead - 1`` when
        band-limited, else 0). :meth:`simulate` compensates it."""
        return int(core.HystereticOscillator.delay(self))

    def z_bound(self, displacement_range: float) -> float:
        """A bound on |z| while the displacement stays within an interval of that width: the
        largest |z| on the outer loop of repeated full-range excursions (and on the first
        loading from rest); ``inf`` when z is not bounded over that range (the loop ratchets
        from cycle to cycle, escapes, or would exceed 1e12 alpha * range).

        Parameters
        ----------
        displacement_range : float
            Width of the displacement interval (output unit).

        Returns
        -------
        float
            The bound on |z| (force unit), or ``inf``.
        """
        return float(core.HystereticOscillator.z_bound(self, float(displacement_range)))

    def _simulate(  # periodic is its own
        self, t: ArrayLike | None, x: ArrayLike, periodic: bool | None = None
    ) -> SimulationResult:
        """Output for the input samples x at times t, from rest.

        ``periodic`` matters only for ``input_interpolation="bandlimited"``: True upsamples
        the record exactly by FFT (it must be a whole number of periods), False uses the
        windowed sinc, None (default) detects it (see :func:`is_periodic`).

        Raises ValueError when the hysteretic force diverges during the simulation; warns
        (:class:`UnboundedStateWarning`) when the simulated displacement range leaves the
        range over which z is bounded (:meth:`z_bound`). The result's ``status`` holds each
        sample's Status flags (all OK on the dense periodic path: its input is checked finite
        and a divergence raises).

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing; required (uniform for "bandlimited").
        x : array_like of float, shape (n,)
            Input force samples.
        periodic : bool, optional
            Whether the record is a whole number of periods (band-limited input only).

        Returns
        -------
        SimulationResult, shape (n,)
            Displacements, with ``status`` each sample's flags.

        Raises
        ------
        ValueError
            t missing, bad samples, non-uniform sampling with "bandlimited", or z diverging.
        """
        if t is None:
            raise ValueError("HystereticOscillator is rate-dependent: t is required")
        ts, xs = as_time_and_signal(t, x)
        assert ts is not None  # t was given
        y: Any  # the core's output, or (output, flags)
        try:
            if self.input_interpolation == "bandlimited" and xs.size > 1:
                dt = uniform_step(ts, "HystereticOscillator (bandlimited input)")
                if periodic is None:
                    periodic = is_periodic(xs)
                if periodic:
                    fine = 2 * int(self.substeps(dt))
                    upsampled = fft_upsample(xs, fine)
                    dense = self.simulate_dense(dt, xs.size, upsampled, fine)
                    y = (dense, np.zeros(xs.size, dtype=np.uint8))
                else:
                    y = core.HystereticOscillator.simulate(self, ts, xs, True)
            else:
                y = core.HystereticOscillator.simulate(self, ts, xs, True)
        except ValueError as exc:
            if "diverged" not in str(exc):
                raise
            p = self.params
            raise ValueError(
                f"{exc}: the hysteretic force z grew without bound (beta (gamma + delta) = "
                f"{p['beta'] * (p['gamma'] + p['delta']):.4g}, beta (gamma - delta) = "
                f"{p['beta'] * (p['gamma'] - p['delta']):.4g}, nu = {p['nu']:.4g}); this "
                "excitation drives the displacement beyond the range where this softening "
                "Bouc-Wen loop is bounded"
            ) from None
        self.check_bounded(float(np.ptp(y[0])), "the simulated displacement")
        return SimulationResult(y[0], status=y[1])

    def check_bounded(self, displacement_range: float, what: str = "the displacement") -> bool:
        """Warn (:class:`UnboundedStateWarning`) and return False when z has no finite bound
        over ``displacement_range``.

        Parameters
        ----------
        displacement_range : float
            Width of the displacement interval.
        what : str, default "the displacement"
            What spans that range, for the warning's message.

        Returns
        -------
        bool
            True when z is bounded over the range (or beta = 0, or the range is not > 0).
        """
        p = self.params
        if p["beta"] == 0.0 or not displacement_range > 0:
            return True
        if math.isfinite(self.z_bound(displacement_range)):
            return True
        warnings.warn(
            f"HystereticOscillator: {what} spans {displacement_range:.4g}, beyond the range "
            f"over which the hysteretic force z stays bounded (beta (gamma + delta) = "
            f"{p['beta'] * (p['gamma'] + p['delta']):.4g}): under repeated excursions of this "
            "range z ratchets up or escapes, so simulations may diverge",
            UnboundedStateWarning,
            stacklevel=3,
        )
        return False


__all__ = [
    "HystereticOscillator",
    "UnboundedStateWarning",
]
