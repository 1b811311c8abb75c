"""A plain NumPy/SciPy implementation of the spec A.5 pull-pull simulator.

It is the reference the C++ plant is checked against (tests) and timed against (benchmarks):
the textbook active-set loop, a banded solve (scipy.linalg.solve_banded) of the whole chain
on every iteration, no shortcuts. It follows the same discretisation as the C++ core (lumped
node angles, h_j = tanh(mu dtheta_j / 2), the same tolerances) but is slow: use it only on
short runs.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import solve_banded


class ReferencePullPull:
    def __init__(
        self,
        route,
        friction=0.1,
        stiffness=2.4e4,
        pretension=10.0,
        proximal_radius=5e-3,
        distal_radius=5e-3,
        elements=100,
        load_torque=0.0,
        load_stiffness=0.0,
        route2=None,
        max_increment=None,
        max_substeps=64,
    ):
        route2 = route if route2 is None else route2
        N = int(elements)
        M = 2 * N
        self.N, self.M = N, M
        self.mu = float(friction)
        self.rp, self.rd = float(proximal_radius), float(distal_radius)
        self.k = np.zeros(M + 2)
        self.k[1 : N + 1] = stiffness * N / route2.length
        self.k[N + 1 : M + 1] = stiffness * N / route.length
        self.T0 = np.zeros(M + 2)
        self.T0[1 : M + 1] = pretension
        self.driven = np.zeros(M + 1, bool)
        self.driven[[0, M]] = True
        self.F0 = load_torque / self.rd
        self.kL = load_stiffness / self.rd**2
        self.h = np.zeros(M + 1)
        self.set_route(route, route2)
        if max_increment is None:
            L = max(route.length, route2.length)
            th = max(route.curve_angle, route2.curve_angle)
            e = pretension * L * math.tanh(0.5 * self.mu * th) / stiffness
            max_increment = e / 20 if e > 0 else 0.0
        self.max_increment = max_increment
        self.max_substeps = max_substeps
        self.reset()

    def set_route(self, route, route2=None):
        route2 = route if route2 is None else route2
        N = self.N
        a1 = route.node_angles(N)
        a2 = route2.node_angles(N)
        dtheta = np.zeros(self.M + 1)
        dtheta[1:N] = a2
        dtheta[2 * N - np.arange(1, N)] = a1
        self.h = np.tanh(0.5 * self.mu * dtheta)

    def reset(self):
        self.u = np.zeros(self.M + 1)
        self.sig = np.zeros(self.M + 1, dtype=int)
        self.x = 0.0
        self.started = False

    def tensions(self, u):
        T = np.zeros(self.M + 2)
        T[1 : self.M + 1] = self.T0[1 : self.M + 1] + self.k[1 : self.M + 1] * np.diff(u)
        return T

    def _solve(self, xt, sig):
        M, N = self.M, self.N
        j = np.arange(M + 1)
        kl, kr = self.k[j], self.k[j + 1]
        hs = self.h * sig
        p, q = 1 - hs, 1 + hs
        lower, upper = q * kl, p * kr
        diag = -(upper + lower)
        rhs = -(p * self.T0[j + 1] - q * self.T0[j])
        # load node (distal pulley)
        lower[N], upper[N] = kl[N], kr[N]
        diag[N] = -(kl[N] + kr[N] + self.kL)
        rhs[N] = -(self.T0[N + 1] - self.T0[N]) + self.F0
        fixed = self.driven | ((self.h > 0) & (sig == 0))
        fixed[N] = False
        lower[fixed], upper[fixed], diag[fixed] = 0.0, 0.0, 1.0
        rhs[fixed] = np.where(self.driven[fixed], xt, self.u[fixed])
        ab = np.zeros((3, M + 1))
        ab[0, 1:] = upper[:-1]
        ab[1] = diag
        ab[2, :-1] = lower[1:]
        return solve_banded((1, 1), ab, rhs)

    def _increment(self, xt, max_it):
        sig = self.sig.copy()
        sheath = self.h > 0
        for _ in range(max_it):
            w = self._solve(xt, sig)
            T = self.tensions(w)
            Tl, Tr = T[:-1], T[1:]
            net = Tr - Tl
            cap = self.h * np.maximum(Tl + Tr, 0.0)
            tol = 1e-9 * (np.abs(Tl) + np.abs(Tr)) + 1e-12
            du = w - self.u
            eps = 1e-13 * (np.abs(self.u) + np.abs(w)) + 1e-18
            stuck_v = sheath & (sig == 0) & (np.abs(net) > cap + tol)
            slip_v = sheath & (sig != 0) & (du * sig < -eps)
            if not (stuck_v.any() or slip_v.any()):
                self.u, self.sig, self.x = w, sig, xt
                return True
            sig = np.where(stuck_v, np.where(net > 0, 1, -1), np.where(slip_v, 0, sig))
        self.u, self.sig, self.x = w, sig, xt
        return False

    def step(self, q_in):
        x = self.rp * float(q_in)
        if not self.started:
            self.u += x - self.x
            self.x = x
            self.started = True
            self._increment(x, 2 * self.M + 50)
        dx = x - self.x
        n = 1
        if self.max_increment > 0:
            n = int(min(max(math.ceil(abs(dx) / self.max_increment), 1), self.max_substeps))
        x0 = self.x
        for i in range(1, n + 1):
            xi = x if i == n else x0 + dx * i / n
            self._increment(xi, 2 * self.M + 50)
        return self.u[self.N] / self.rd

    def simulate(self, q_in):
        self.reset()
        return np.array([self.step(q) for q in q_in])
