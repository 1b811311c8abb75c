"""Type aliases of the public signatures."""

from __future__ import annotations

from typing import TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

# an array of samples the package returns
FloatArray: TypeAlias = NDArray[np.float64]
# what an elementwise closed form returns: a NumPy scalar for scalar arguments, else an array
FloatOrArray: TypeAlias = np.float64 | NDArray[np.float64]

__all__ = ["ArrayLike", "FloatArray", "FloatOrArray"]
