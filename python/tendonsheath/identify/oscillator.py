"""Identification of the HystereticOscillator in three stages that find the basin.

1. Best linear approximation (BLA): the frequency response G = Y/U at the excited lines of
   a periodic record (averaged over its steady-state periods), or Welch's H1 estimate
   otherwise, fitted by 1/G = k_e - m w^2 + i c_e w (linear least squares): m, c_e, k_e.
2. Equation error (the prediction error of the force balance, with the displacement and its
   derivatives taken from the measured output): u = m y'' + c y' + k y + alpha w(y; G, D, nu)
   where w = z / alpha depends only on the displacement path (rate-independent) and on
   G = alpha^(nu-1) beta gamma, D = alpha^(nu-1) beta delta. (m, c, k, alpha) >= 0 follow
   from non-negative least squares for every candidate (variable projection); (G, D, nu)
   are searched by differential evolution in G (Y/2)^nu, D (Y/2)^nu in [-30, 30] (both
   signs: softening and hardening loops alike, a box, no wall), then polished.
3. Simulation error: least squares (:func:`~tendonsheath.identify.refine.refine`, shared with
   every identification path) on the free-run simulation of every recording, from the
   equation-error estimate. With band-limited input the Jacobian comes from forward
   sensitivities (the tangent-linear model of the RK4 scheme, in C++: exact for the simulated
   output); with "hold" or "linear" from forward differences in one batched C++ call.

Stage 2 plays the role of multiple shooting: its residual is the one-step force balance on
the measured displacement, so it has no long free-run simulation to trap it in a local
minimum, and stage 3 starts in the basin of the simulation error.

What limits the accuracy: at the optimum the simulation-error estimate is the maximum-
likelihood one for white output noise, so its spread is set by the information in the record
(the Cramer-Rao bound). With noise at 1e-3 of the output range, the validation error that the
parameter spread adds is about noise * sqrt(7 / N) for N samples: ~2e-7 m at N = 3 072, larger
than the model's own discretisation error (~5e-8 to 3e-7 m); benchmarks/identify.py
--oscillator prints the ratio expected from the bound next to the one measured.

The input reconstruction between samples, when neither ``input_interpolation`` nor
``initial`` is given, is read from the input (:mod:`~tendonsheath.identify.interpolation`):
band-limited for a multisine or a sweep (the Bouc-Wen benchmark's floor needs it), held for a
staircase, linear otherwise; ``input_interpolation`` overrides it.

Multi-period records (an input that repeats exactly) are detected: stages 1 and 2 use the
average of the steady-state periods (the first period, the transient, is dropped); stage 3
simulates the whole record from rest, as the data was taken.
"""

from __future__ import annotations

import time
import warnings

import numpy as np

from .._util.sampling import fft_upsample, is_periodic, uniform_step
from ..models import HystereticOscillator
from ._bound import (
    RecordingSet,
    bouc_wen_paths,
    oscillator_sensitivity_dense,
    reconstruct_bandlimited,
)
from .data import check_for_fit
from .fit import Fit, fit_quality
from .interpolation import detect_for_recordings
from .problem import DirectProblem
from .refine import TimeBudget, forward_jacobian, refine

_PENALTY = 1e100


class _Stages:
    """Progress: one line per stage (rich), with the elapsed time; silent when disabled."""

    def __init__(self, enabled: bool, budget: TimeBudget):
        self.budget = budget
        self.status = None
        if enabled:
            from rich.console import Console

            self.status = Console(stderr=True).status("identify HystereticOscillator")
            self.status.start()

    def over(self) -> bool:
        return self.budget.over()

    def stage(self, text: str) -> None:
        if self.status is not None:
            b = self.budget.seconds
            left = "" if b is None else f" (budget {b:.0f} s)"
            self.status.update(
                f"identify HystereticOscillator: {text}, {self.budget.elapsed():.1f} s{left}"
            )

    def close(self) -> None:
        if self.status is not None:
            self.status.stop()


def period_count(x: np.ndarray, rtol: float = 1e-9) -> int:
    """The number of exact repetitions of the input (1 if it does not repeat)."""
    n = x.size
    span = float(np.ptp(x)) or 1.0
    for p in range(n // 16, 1, -1):
        if n % p:
            continue
        d = n // p
        if np.max(np.abs(x[d:] - x[:-d])) <= rtol * span:
            return p
    return 1


def _derivatives(y: np.ndarray, dt: float, f_max: float, periodic: bool, fine: int):
    """y, y', y'' at the samples and y on a grid `fine` times finer, low-passed to f_max (FFT;
    a non-periodic record has its end-to-end ramp removed first)."""
    n = y.size
    ramp = np.zeros(n)
    if not periodic:
        ramp = y[0] + (y[-1] - y[0]) * np.arange(n) / (n - 1)
    r = y - ramp
    Y = np.fft.rfft(r)
    f = np.fft.rfftfreq(n, dt)
    Y[f > f_max] = 0.0
    w = 2j * np.pi * f
    slope = 0.0 if periodic else (y[-1] - y[0]) / ((n - 1) * dt)
    y0 = np.fft.irfft(Y, n) + ramp
    y1 = np.fft.irfft(Y * w, n) + slope
    y2 = np.fft.irfft(Y * w * w, n)
    y_fine = fft_upsample(np.fft.irfft(Y, n), fine)
    if not periodic:
        y_fine = y_fine + np.interp(np.arange(n * fine) / fine, np.arange(n), ramp)
    return y0, y1, y2, y_fine


class _Segment:
    """Data for stages 1-2: one steady period (averaged) or a whole non-periodic record."""

    def __init__(self, t, x, y, periodic_input: bool):
        self.dt = uniform_step(t, "identify HystereticOscillator")
        self.periods = period_count(x) if periodic_input else 1
        self.periodic = periodic_input
        if self.periods >= 2:
            d = x.size // self.periods
            self.x = x[:d].copy()
            self.y = y[d:].reshape(self.periods - 1, d).mean(axis=0)
            self.mask = np.ones(d, dtype=bool)
        else:
            self.x, self.y = x.copy(), y.copy()
            self.mask = np.ones(x.size, dtype=bool)
            if not periodic_input:  # edges of the FFT derivatives
                e = max(1, x.size // 20)
                self.mask[:e] = self.mask[-e:] = False


def _bla(segments) -> tuple[float, float, float, float]:
    """m, c_e, k_e and the highest excited frequency from the frequency response."""
    from scipy.signal import csd, welch

    rows_re, rows_im, rhs_re, rhs_im, f_top = [], [], [], [], 0.0
    for s in segments:
        n = s.x.size
        f = np.fft.rfftfreq(n, s.dt)
        if s.periodic:
            X, Y = np.fft.rfft(s.x), np.fft.rfft(s.y)
            lines = np.nonzero(np.abs(X) > 1e-3 * np.abs(X).max())[0]
            lines = lines[lines > 0]
            G, w = Y[lines] / X[lines], 2 * np.pi * f[lines]
        else:
            nper = min(n, 1024)
            fw, Puu = welch(s.x, fs=1 / s.dt, nperseg=nper)
            _, Puy = csd(s.x, s.y, fs=1 / s.dt, nperseg=nper)
            lines = np.nonzero(Puu > 1e-3 * Puu.max())[0]
            lines = lines[lines > 0]
            G, w = Puy[lines] / Puu[lines], 2 * np.pi * fw[lines]
        if lines.size == 0:
            continue
        f_top = max(f_top, float(w.max() / (2 * np.pi)))
        inv = 1.0 / G
        wt = np.abs(G)  # output-error weighting
        rows_re.append(np.column_stack([np.ones_like(w), -(w**2)]) * wt[:, None])
        rhs_re.append(inv.real * wt)
        rows_im.append((w * wt)[:, None])
        rhs_im.append(inv.imag * wt)
    if not rows_re:
        raise ValueError("identify HystereticOscillator: the input excites no frequency")
    ke, m = np.linalg.lstsq(np.vstack(rows_re), np.concatenate(rhs_re), rcond=None)[0]
    (ce,) = np.linalg.lstsq(np.vstack(rows_im), np.concatenate(rhs_im), rcond=None)[0]
    return float(m), float(ce), float(ke), f_top


class _EquationError:
    """Variable projection of the force balance over (G, D, nu) (module docstring, stage 2)."""

    PATH_FINE = 4

    def __init__(self, segments, f_top: float, workers: int):
        u, A, paths, masks = [], [], [], []
        for s in segments:
            f_max = min(0.45 / s.dt, max(2.0 * f_top, 1.0 / (20 * s.dt)))
            y0, y1, y2, yf = _derivatives(s.y, s.dt, f_max, s.periodic, self.PATH_FINE)
            if s.periodic:  # start the path one period early so that w is in steady state
                yf = np.concatenate([yf, yf])
            u.append(s.x[s.mask])
            A.append(np.column_stack([y2, y1, y0])[s.mask])
            paths.append(yf)
            masks.append(s.mask)
        self.segments = segments
        self.u = np.concatenate(u)
        self.A = np.vstack(A)
        self.paths = paths
        self.masks = masks
        self.workers = workers
        self.half = 0.5 * max(float(np.ptp(s.y)) for s in segments)

    def _w(self, G, D, nu):
        """w at the fitted samples for each candidate: (P, n_fit), NaN where it overflowed."""
        params = np.ascontiguousarray(np.column_stack([G, D, nu]), dtype=float)
        cols = []
        for s, yf, mask in zip(self.segments, self.paths, self.masks, strict=True):
            W = bouc_wen_paths(np.ascontiguousarray(yf), params, self.workers)
            n = s.x.size * self.PATH_FINE
            W = W[:, -n:][:, :: self.PATH_FINE]
            cols.append(W[:, mask])
        return np.hstack(cols)

    def natural(self, U):
        U = np.atleast_2d(U)
        nu = U[:, 2]
        scale = self.half**nu
        return U[:, 0] / scale, U[:, 1] / scale, nu

    def solve(self, w):
        """Non-negative (m, c, k, alpha) and the residual for one w column."""
        from scipy.optimize import nnls

        M = np.column_stack([self.A, w])
        col = np.linalg.norm(M, axis=0)
        col[col == 0] = 1.0
        theta, _ = nnls(M / col, self.u)
        theta = theta / col
        return theta, self.u - M @ theta

    def costs(self, U):
        W = self._w(*self.natural(U))
        out = np.empty(W.shape[0])
        for i, w in enumerate(W):
            if not np.all(np.isfinite(w)):
                out[i] = _PENALTY
                continue
            _, r = self.solve(w)
            out[i] = float(r @ r)
        return out

    def residual(self, u):
        w = self._w(*self.natural(u))[0]
        if not np.all(np.isfinite(w)):
            return np.full(self.u.size, 1e3 * (np.ptp(self.u) + 1.0))
        return self.solve(w)[1]

    def params(self, u):
        G, D, nu = (float(v[0]) for v in self.natural(u))
        w = self._w([G], [D], [nu])[0]
        (m, c, k, alpha), _ = self.solve(w)
        a = max(alpha, 1e-300) ** (nu - 1.0)
        return {"m": m, "c": c, "k": k, "alpha": alpha, "bg": G / a, "bd": D / a, "nu": nu}


def _setup(initial, input_interpolation, fixed, free):
    """(options, values with the held ones, held, free names) of the fit."""
    cls = HystereticOscillator
    if initial is None:
        initial = cls()
    elif type(initial) is not cls:
        raise ValueError(f"initial must be a HystereticOscillator (got {type(initial).__name__})")
    options = dict(initial.options)
    if input_interpolation is not None:
        options["input_interpolation"] = input_interpolation
        cls(**options)  # validates the name
    values = dict(initial.params)
    free_set = set(free or ())
    unknown = (free_set | set(fixed or {})) - set(cls.param_names)
    if unknown:
        raise ValueError(
            f"unknown parameter(s) {sorted(unknown)} of HystereticOscillator; "
            f"expected {list(cls.param_names)}"
        )
    held = {} if "beta" in free_set else {"beta": values["beta"]}
    held.update({k: float(v) for k, v in (fixed or {}).items()})
    values.update(held)
    if "beta" not in held:
        raise ValueError(
            "HystereticOscillator: beta is not identifiable (only beta gamma and beta delta "
            "are); keep it fixed"
        )
    return options, values, held, [n for n in cls.param_names if n not in held]


def _equation_error_stage(ee, held, seed, popsize, maxiter, budget, counter):
    """Differential evolution over (G, D, nu) then a least-squares polish: the search
    coordinates and the DE result."""
    from scipy.optimize import differential_evolution, least_squares

    nu_lo, nu_hi = (1.0, 3.0) if "nu" not in held else (held["nu"], held["nu"])
    ee_bounds = [(-30.0, 30.0), (-30.0, 30.0), (nu_lo, max(nu_hi, nu_lo + 1e-12))]
    fixed_nu = "nu" in held

    def ee_cost(U):
        U = np.array(U, dtype=float).T
        if fixed_nu:
            U[:, 2] = held["nu"]
        counter["evaluations"] += U.shape[0]
        return ee.costs(U)

    res = differential_evolution(
        ee_cost,
        ee_bounds,
        vectorized=True,
        updating="deferred",
        popsize=max(popsize, 10),
        maxiter=max(maxiter, 30),
        tol=1e-6,
        seed=seed,
        polish=False,
        init="latinhypercube",
        callback=lambda intermediate_result: budget.over(),
    )
    u_ee = res.x
    lo = np.array([b[0] for b in ee_bounds])
    hi = np.array([b[1] for b in ee_bounds])
    if budget.over():
        return u_ee, res
    keep = slice(0, 2) if fixed_nu else slice(0, 3)
    try:
        ls = least_squares(
            lambda v: ee.residual(np.r_[v, u_ee[2:]][:3]),
            np.clip(u_ee[keep], lo[keep] + 1e-9, hi[keep] - 1e-9),
            bounds=(lo[keep], hi[keep]),
            x_scale="jac",
            max_nfev=60,
        )
        counter["evaluations"] += int(ls.nfev)
        u_ee = np.r_[ls.x, u_ee[ls.x.size :]]
    except (ValueError, np.linalg.LinAlgError):
        pass
    return u_ee, res


def _start_values(p_ee, m0, ce0, beta, held):
    start = {
        "m": p_ee["m"] if p_ee["m"] > 0 else m0,
        "c": max(p_ee["c"], 1e-6 * max(ce0, 1e-300)),
        "k": p_ee["k"],
        "alpha": p_ee["alpha"],
        "beta": beta,
        "gamma": p_ee["bg"] / beta,
        "delta": p_ee["bd"] / beta,
        "nu": p_ee["nu"],
    }
    start.update(held)
    return start


def _simulation_bounds(start, ce0, beta, bounds):
    k_tot = start["k"] + start["alpha"]
    g = max(abs(start["gamma"]), abs(start["delta"]), 1e-300)
    out = {
        "m": (0.2 * start["m"], 5.0 * start["m"]),
        "c": (1e-3 * max(ce0, start["c"]), 5.0 * max(ce0, start["c"])),
        "k": (0.0, 3.0 * k_tot),
        "alpha": (0.0, 3.0 * k_tot),
        "beta": (0.1 * beta, 10.0 * beta),
        "gamma": (-10.0 * g, 10.0 * g),
        "delta": (-10.0 * g, 10.0 * g),
        "nu": (1.0, 3.0),
    }
    for name, b in (bounds or {}).items():
        if name not in out or len(tuple(b)) != 2:
            raise ValueError(f"bounds[{name!r}] must be (low, high) of a parameter")
        out[name] = (float(b[0]), float(b[1]))
    return out


def _simulation_problem(recs, per, warmup, start, free_names, se_bounds, options, workers):
    """The simulation-error problem over the whole records (band-limited input reconstructed
    once, on the grid of the RK4 sub-steps), a note on the reconstruction, and the dense
    input (per-recording grids, points per sample) or None."""
    mode = options["input_interpolation"]
    problem = DirectProblem(
        HystereticOscillator,
        recs,
        warmup,
        start,
        free_names,
        se_bounds,
        frozenset({"m", "c"}),
        options,
        None,
        workers,
    )
    if mode != "bandlimited":
        return problem, f"input reconstruction {mode}", None
    model = HystereticOscillator(**start, **options)
    steps = (model.substeps(float(r.t[1] - r.t[0])) for r in recs)
    fine = 2 * max(int(options["substeps"]), max(int(n) for n in steps))
    grids = [
        fft_upsample(r.x, fine)
        if p
        else reconstruct_bandlimited(r.x, fine, int(options["lookahead"]))
        for r, p in zip(recs, per, strict=True)
    ]
    x_fine = np.concatenate(grids)
    problem.rs = RecordingSet(
        np.concatenate([r.t for r in recs]),
        np.concatenate([r.x for r in recs]),
        np.concatenate([r.y for r in recs]),
        None,
        [r.n for r in recs],
        [int(warmup)] * len(recs),
        np.ascontiguousarray(x_fine),
        fine,
    )
    note = (
        "input reconstruction bandlimited ("
        + ", ".join("periodic: FFT" if p else "windowed sinc" for p in per)
        + f"), {fine // 2} RK4 sub-steps per sample"
    )
    return problem, note, (grids, fine)


def identify_oscillator(
    recs, *, warmup: int, bounds, fixed, free, initial, search, input_interpolation, periodic
) -> Fit:
    """The staged identification of a HystereticOscillator (see the module docstring) with the
    :class:`~tendonsheath.identify.settings.Search` settings ``search``."""
    cls = HystereticOscillator
    notes: list[str] = []
    if input_interpolation is None and initial is None:
        input_interpolation, why = detect_for_recordings(recs, periodic)
        notes.append(why)
    options, values, held, free_names = _setup(initial, input_interpolation, fixed, free)
    mode = options["input_interpolation"]
    check_for_fit(recs, warmup, len(free_names), True, False)
    stages = _Stages(search.progress, search.budget)
    start = time.perf_counter()
    counter = {"evaluations": 0}
    try:
        per, segments = _segments(recs, mode, periodic, notes)
        stages.stage("best linear approximation")
        m0, ce0, ke0, f_top = _bla_stage(segments, notes)
        stages.stage("equation error (force balance on the measured displacement)")
        ee = _EquationError(segments, f_top, search.n_workers)
        u_ee, res = _equation_error_stage(
            ee, held, search.seed, search.popsize, search.maxiter, search.budget, counter
        )
        beta = values["beta"]
        start_values = _start_values(ee.params(u_ee), m0, ce0, beta, held)
        notes.append(
            "equation error: "
            + ", ".join(f"{k} {start_values[k]:.4g}" for k in cls.param_names if k in free_names)
        )
        stages.stage("simulation error (least squares)")
        se_bounds = _simulation_bounds(start_values, ce0, beta, bounds)
        problem, note, dense = _simulation_problem(
            recs, per, warmup, start_values, free_names, se_bounds, options, search.n_workers
        )
        notes.append(note)
        model, msg = _simulation_stage(problem, recs, dense, start_values, search, counter)
    finally:
        stages.close()
    seconds = time.perf_counter() - start
    run = dict(recs=recs, per=per, warmup=warmup, held=held, mode=mode, counter=counter)
    message = "; ".join([*notes, f"least squares: {msg}"])
    return _fit(run, model, problem, se_bounds, seconds, int(res.nit), message)


def _segments(recs, mode: str, periodic, notes: list[str]):
    """Data: whether each record is whole periods, and its steady periods (averaged)."""
    per = []
    for r in recs:
        if mode == "bandlimited" or periodic is not None:
            uniform_step(r.t, "identify HystereticOscillator")
        per.append(is_periodic(r.x) if periodic is None else bool(periodic))
    segments = [_Segment(r.t, r.x, r.y, p) for r, p in zip(recs, per, strict=True)]
    for i, s in enumerate(segments):
        if s.periods >= 2:
            notes.append(f"recording {i}: {s.periods} periods, {s.periods - 1} averaged")
    return per, segments


def _bla_stage(segments, notes: list[str]):
    """The best linear approximation (m, c, k + alpha, and the force's top), checked."""
    m0, ce0, ke0, f_top = _bla(segments)
    if not (m0 > 0 and ke0 > 0):
        raise ValueError(
            f"identify HystereticOscillator: the best linear approximation is not a "
            f"mass-spring-damper (m = {m0:.4g}, k = {ke0:.4g}): is the output a displacement "
            "driven by the input force?"
        )
    notes.append(f"BLA m {m0:.4g}, c {ce0:.4g}, k+alpha {ke0:.4g}")
    return m0, ce0, ke0, f_top


def _simulation_stage(problem, recs, dense, start_values, search, counter):
    """Simulation-error least squares from the equation-error estimate: (model, message)."""
    space = problem.space
    u0 = np.clip(space.search([start_values[n] for n in problem.free]), space.lower, space.upper)
    if search.polish and not search.budget.over():
        u_best, msg = refine(
            problem,
            space,
            u0,
            counter,
            budget=search.budget,
            jacobian=_jacobian(problem, space, recs, dense),
            max_nfev=200,
            xtol=1e-12,
            gtol=1e-12,
        )
    else:
        why = "time budget spent" if search.polish else "polish=False"
        u_best, msg = u0, f"skipped ({why})"
    return problem.model(space.natural(u_best)), msg


def _jacobian(problem, space, recs, dense):
    """The residuals' Jacobian in search coordinates: forward sensitivities of the RK4
    scheme (C++, exact for the simulated output) with the band-limited input on its fine grid;
    otherwise forward differences with steps relative to the coordinates (the parameters span
    many decades: k ~ 1e4, m ~ 1), one batched call per Jacobian."""
    span = space.upper - space.lower

    def differences(u):
        return forward_jacobian(problem, space, u, 1e-7 * np.maximum(np.abs(u), 1e-3 * span))

    if dense is None:
        return differences
    grids, fine = dense
    cols = [HystereticOscillator.param_names.index(n) for n in problem.free]

    def sensitivities(u):
        v = space.natural(u)
        try:
            params = problem.model(v).params_struct()
        except ValueError:
            return differences(u)
        S = np.vstack(
            [
                oscillator_sensitivity_dense(
                    params, float(r.t[1] - r.t[0]), r.n, np.ascontiguousarray(g), fine
                )[1]
                for r, g in zip(recs, grids, strict=True)
            ]
        )
        J = -S[problem.mask][:, cols] * np.where(space.log, v, 1.0)[None, :]
        return J if np.all(np.isfinite(J)) else differences(u)

    return sensitivities


def _fit(run: dict, model, problem, se_bounds, seconds, generations, message) -> Fit:
    recs, warmup, free_names = run["recs"], run["warmup"], problem.free
    predictions = [
        model.simulate(r.t, r.x, periodic=p) for r, p in zip(recs, run["per"], strict=True)
    ]
    quality = fit_quality(recs, predictions, warmup)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            se = problem.standard_errors(problem.coefficients_of(model), quality.sse, quality.n)
            ses = {n: float(s) for n, s in zip(free_names, se, strict=True)}
        except ValueError:
            ses = {n: float("nan") for n in free_names}
    model.check_bounded(max(float(np.ptp(r.y)) for r in recs), "the measured displacement")
    return Fit.from_quality(
        model,
        quality,
        standard_errors=ses,
        identified=list(free_names),
        fixed=run["held"],
        evaluations=run["counter"]["evaluations"],
        seconds=seconds,
        generations=generations,
        method="best linear approximation + equation error (differential evolution, variable "
        f"projection) + simulation-error least squares; input reconstruction {run['mode']}",
        message=message,
        warmup=warmup,
        bounds={n: se_bounds[n] for n in free_names},
        recordings=recs,
        predictions=predictions,
    )


__all__ = ["identify_oscillator", "period_count"]
