"""Pure-Python models with the C++ core's numerics, for the benchmarks that time a Python
implementation against the core (models.py: per sample; identify.py: a Python-only fit)."""

from __future__ import annotations

import math

import numpy as np


def bouc_wen_backlash(x, c_r, c_l, B_r, B_l, rho, sigma, n, max_step=0.05, max_substeps=256):
    """BoucWenBacklash as models/bouc_wen_backlash.hpp computes it: w integrated in x by RK4
    (sub-steps of rho |dx| <= max_step, at most max_substeps), saturation skipped, w snapped
    onto +-1 within 1e-12 of it."""

    def f(w, s):
        a = abs(w)
        q = a ** (n - 1.0) if a > 0.0 else (1.0 if n == 1.0 else 0.0)
        return rho * (s - sigma * q * w + (sigma - 1.0) * s * q * a)

    def clamp(v):
        return 1.0 if v > 1.0 else (-1.0 if v < -1.0 else v)

    y = np.empty(len(x))
    w, xp = 0.0, float(x[0])
    for k in range(len(x)):
        xk = float(x[k])
        dx = xk - xp
        saturated = (dx > 0 and w >= 1.0) or (dx < 0 and w <= -1.0)  # fixed point: skip
        if dx != 0.0 and not saturated:
            s, travel = (1.0 if dx > 0 else -1.0), abs(dx)
            m = math.ceil(rho * travel / max_step)
            m = 1 if not m >= 1 else min(m, max_substeps)
            h = travel / m
            for _ in range(m):
                k1 = f(w, s)
                k2 = f(clamp(w + 0.5 * h * k1), s)
                k3 = f(clamp(w + 0.5 * h * k2), s)
                k4 = f(clamp(w + h * k3), s)
                w = clamp(w + h * (k1 + 2 * k2 + 2 * k3 + k4) / 6.0)
                if w * s >= 1.0 - 1e-12:  # at the fixed point: the rest cannot leave it
                    break
            if 1.0 - abs(w) < 1e-12:  # snap onto the fixed point, as the core does
                w = 1.0 if w > 0 else -1.0
        xp = xk
        phi = 0.5 * (1.0 + w)
        y[k] = phi * c_r * (xk - B_r) + (1.0 - phi) * c_l * (xk + B_l)
    return y
