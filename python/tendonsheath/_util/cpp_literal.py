"""A double as a C++ literal, for the headers ``export --cpp`` writes (export_cpp.py and
export_cpp_multi.py)."""

from __future__ import annotations

import math

INF = "std::numeric_limits<double>::infinity()"


def cpp_number(value: float) -> str:
    """``value`` as a C++ double literal that reads back to the same double (``repr``; an
    infinity as ``std::numeric_limits``); NaN is refused, naming the command."""
    value = float(value)
    if math.isnan(value):
        raise ValueError("export --cpp: a parameter is NaN")
    if math.isinf(value):
        return INF if value > 0 else f"-{INF}"
    return repr(value)
