"""Type aliases of the public signatures."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from ..identify.data import Recording
    from ..io.log import Log

# an array of samples the package returns
FloatArray: TypeAlias = NDArray[np.float64]
# what an elementwise closed form returns: a NumPy scalar for scalar arguments, else an array
FloatOrArray: TypeAlias = np.float64 | NDArray[np.float64]
# one recording for identification: a Log, a Recording or a (t, x, y[, curve_angle]) tuple
RecordingLike: TypeAlias = "Log | Recording | tuple"
# one recording or a sequence of them
Recordings: TypeAlias = "RecordingLike | Sequence[RecordingLike]"

__all__ = ["ArrayLike", "FloatArray", "FloatOrArray", "RecordingLike", "Recordings"]
