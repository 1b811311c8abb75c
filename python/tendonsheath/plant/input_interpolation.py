"""Input reconstruction between samples for the plants' batch simulation.

With distal inertia and damping, sheath viscosity, creep or motor dynamics a plant is a
continuous-time system: its output at a sample depends on the input's path since the last
one, not only on the samples. ``"hold"`` (the default, and what the streaming ``step()``
does) applies each new sample at once for the whole step; ``"linear"`` ramps between
samples; ``"bandlimited"`` treats the input as band-limited, as HystereticOscillator does:
exact FFT upsampling of a periodic record (whole periods, detected or ``periodic=True``),
otherwise the same Kaiser-windowed sinc of half-width ``lookahead`` samples (the C++
``reconstruct_bandlimited``). The plant then runs its own step on the grid ``substeps`` times
finer and the output is read at the original sample times.

Only batch ``simulate()`` reconstructs: the streaming ``step()`` stays causal (hold, no
look-ahead, no delay), so a control loop sees no added latency.
"""

from __future__ import annotations

import numpy as np

from .._util.sampling import fft_upsample, is_periodic, uniform_step
from . import _bound as core

INTERPOLATIONS = ("hold", "linear", "bandlimited")
DEFAULT_SUBSTEPS = 8
DEFAULT_LOOKAHEAD = 16


def check_interpolation(mode: str, substeps: int, lookahead: int, who: str) -> None:
    if mode not in INTERPOLATIONS:
        raise ValueError(
            f"{who}: input_interpolation must be one of {INTERPOLATIONS} (got {mode!r})"
        )
    if int(substeps) != substeps or substeps < 1:
        raise ValueError(f"{who}: interpolation_substeps must be an integer >= 1 (got {substeps})")
    if int(lookahead) != lookahead or lookahead < 2:
        raise ValueError(f"{who}: lookahead must be an integer >= 2 (got {lookahead})")


def fine_grid(t, u, mode, substeps, lookahead, periodic, who):
    """(t_fine, u_fine, how): the input on a grid ``substeps`` times finer, sample k of the
    original record at index k * substeps; ``how`` says which reconstruction ran."""
    dt = uniform_step(t, who)
    n = u.size
    tf = t[0] + dt / substeps * np.arange(n * substeps)
    if mode == "linear":
        return tf, np.interp(tf, t, u), "linear"
    if periodic is None:
        periodic = is_periodic(u)
    if periodic:
        return tf, fft_upsample(u, substeps), "bandlimited (periodic: FFT)"
    uf = core.reconstruct_bandlimited(np.ascontiguousarray(u, dtype=float), substeps, lookahead)
    return tf, uf, "bandlimited (windowed sinc)"


__all__ = [
    "DEFAULT_LOOKAHEAD",
    "DEFAULT_SUBSTEPS",
    "INTERPOLATIONS",
    "check_interpolation",
    "fine_grid",
]
