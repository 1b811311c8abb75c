"""Closed forms of the uniform-curvature pull-pull tendon-sheath mechanism (spec A.7, B1).

All quantities are linear (tendon level, metres) and SI; angles in rad. ``a = mu * Theta``;
for ``a -> 0`` the series ``tanh(a/2) ~ a/2 - a^3/24`` and ``tanh(a/2)/a ~ 1/2 - a^2/24``
are used (spec pitfall 7).
"""

from __future__ import annotations

import numpy as np

_SMALL = 1e-4


def _tanh_half(a):
    a = np.asarray(a, dtype=float)
    small = np.abs(a) < _SMALL
    return np.where(small, 0.5 * a - a**3 / 24.0, np.tanh(0.5 * a))


def _tanh_half_over(a):
    a = np.asarray(a, dtype=float)
    small = np.abs(a) < _SMALL
    safe = np.where(small, 1.0, a)
    return np.where(small, 0.5 - a**2 / 24.0, np.tanh(0.5 * safe) / safe)


def _out(value):
    return float(value) if np.ndim(value) == 0 else value


def backlash_half_width(mu, total_angle, pretension, length, stiffness):
    """e_b = (T0 L / EA) tanh(mu Theta / 2): half the input dead-zone width, m (spec B1)."""
    a = np.asarray(mu, dtype=float) * np.abs(np.asarray(total_angle, dtype=float))
    return _out(np.asarray(pretension) * np.asarray(length) / np.asarray(stiffness) * _tanh_half(a))


def load_offset(mu, total_angle, load_force, length, stiffness):
    """e_L = (F_L L / EA) tanh(mu Theta / 2) / (mu Theta): shift of both branches, m (spec B1)."""
    a = np.asarray(mu, dtype=float) * np.abs(np.asarray(total_angle, dtype=float))
    return _out(
        np.asarray(load_force) * np.asarray(length) / np.asarray(stiffness) * _tanh_half_over(a)
    )


def spring_slope(mu, total_angle, spring, length, stiffness):
    """Branch slope c = 1 / (1 + k_e C_L) with C_L = L tanh(a/2) / (EA a) (spec A.4)."""
    a = np.asarray(mu, dtype=float) * np.abs(np.asarray(total_angle, dtype=float))
    c_l = np.asarray(length) / np.asarray(stiffness) * _tanh_half_over(a)
    return _out(1.0 / (1.0 + np.asarray(spring) * c_l))
