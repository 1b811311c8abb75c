"""The identifiable parameterisation of ``Chain(Backlash or BoucWenBacklash, Polynomial)``
with a full polynomial: one direction of the dead bands and the polynomial's offset is fixed.

Shifting the first model's output by d (B_r -> B_r - d / c_r, B_l -> B_l + d / c_l; the
Bouc-Wen state does not depend on the dead bands) is undone exactly by re-expanding the
polynomial about the shifted point (p'(v) = p(v - d)), so one direction of (B_r, B_l,
a_0..a_K) is not identifiable from input/output data. The fit is therefore expressed in the
gauge B_r = B_l (the dead band symmetric about x = 0, the polynomial carrying the offset),
which every chain reaches by one such shift (d = (B_r - B_l) / (1/c_r + 1/c_l) keeps both
dead bands positive: the common value is a weighted mean of B_r and B_l). In that gauge the
parameters are identifiable; :func:`groups` reports them in ``Fit.groups``.
"""

from __future__ import annotations

import numpy as np

from ..models import Backlash, BoucWenBacklash, Chain, Polynomial

TIED = "first.B_r = first.B_l"  # the label of the gauge's one dead-band parameter


def applies(chain) -> bool:
    """Whether ``chain`` has the exact output-shift degeneracy."""
    return (
        isinstance(chain, Chain)
        and isinstance(chain.first, Backlash | BoucWenBacklash)
        and isinstance(chain.second, Polynomial)
        and not bool(chain.second.options["odd"])
    )


def canonical(chain: Chain) -> Chain:
    """The same input-output map with B_r = B_l (see the module)."""
    p = chain.first.params
    d = (p["B_r"] - p["B_l"]) / (1.0 / p["c_r"] + 1.0 / p["c_l"])
    if d == 0.0:
        return chain
    half = p["B_r"] - d / p["c_r"]
    a = np.asarray(chain.second.params["coefficients"], dtype=float)
    shifted = np.polynomial.Polynomial(a)(np.polynomial.Polynomial([-d, 1.0])).coef
    coef = np.zeros(a.size)
    coef[: min(a.size, shifted.size)] = shifted[: a.size]
    return Chain(
        chain.first.with_params(B_r=half, B_l=half),
        Polynomial(coefficients=coef, odd=False),
    )


def entry_names(free: list[str]) -> list[str]:
    """The chain's identified quantities in the gauge: B_r and B_l as one."""
    names = [f"first.{n}" for n in free if n not in ("B_r", "B_l")]
    return [*names, TIED, "second.coefficients"]


def groups(model: Chain, standard_errors: dict) -> dict:
    """The gauge's identifiable quantities with their standard errors, for ``Fit.groups``."""
    out = {
        "dead_band_half_width": {
            "value": float(model.params["first.B_r"]),
            "se": _float(standard_errors.get("first.B_r")),
            "unit": "input units (B_r = B_l: dead band symmetric about x = 0)",
            "identified": True,
        }
    }
    coefs = model.params["second.coefficients"]
    ses = standard_errors.get("second.coefficients") or [None] * len(coefs)
    for k, (a, s) in enumerate(zip(coefs, ses, strict=True)):
        out[f"a{k}"] = {
            "value": float(a),
            "se": _float(s),
            "unit": f"polynomial coefficient of u^{k} in the gauge B_r = B_l",
            "identified": True,
        }
    return out


def _float(v):
    return None if v is None else float(v)


__all__ = ["TIED", "applies", "canonical", "entry_names", "groups"]
