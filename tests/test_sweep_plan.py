"""Sweep plans: reproducible from the seed, the distributions, LHS strata, grids, bad input."""

import math

import numpy as np
import pytest

from tendonsheath.sweep import (
    Choice,
    Grid,
    Integers,
    LatinHypercube,
    LogNormal,
    MonteCarlo,
    Normal,
    Relative,
    Saltelli,
    Seed,
    Uniform,
    make_plan,
)
from tendonsheath.sweep.distributions import as_design

SPEC = {
    "friction": Relative(0.1, 0.3),
    "pretension": Normal(10.0, 1.0),
    "stiffness": LogNormal(2.4e4, 0.2),
    "pieces": Integers(1, 4),
    "shape": Choice(["a", "b", "c"]),
    "elements": 20,
}


def test_same_seed_same_plan_and_prefix_stable():
    a = make_plan(as_design(SPEC), 50, seed=7)
    b = make_plan(as_design(dict(reversed(list(SPEC.items())))), 50, seed=7)
    assert a.runs == b.runs  # the order of the dict does not matter
    c = make_plan(as_design(SPEC), 20, seed=7)
    assert a.runs[:20] == c.runs  # run i depends on (seed, i) only
    d = make_plan(as_design(SPEC), 50, seed=8)
    assert a.runs != d.runs
    assert all(r["elements"] == 20 for r in a.runs)
    assert all(type(r["friction"]) is float and type(r["pieces"]) is int for r in a.runs)


def test_seed_none_is_recorded_and_reproduces():
    a = make_plan(MonteCarlo(SPEC), 10, seed=None)
    assert make_plan(MonteCarlo(SPEC), 10, seed=a.seed).runs == a.runs


def test_distributions_have_the_right_moments(rng):
    u = rng.random(200_000)
    x = Uniform(2.0, 5.0).ppf(u)
    assert x.min() >= 2.0 and x.max() < 5.0 and abs(x.mean() - 3.5) < 0.01
    r = Relative(10.0, 0.3)
    assert (r.lo, r.hi) == pytest.approx((7.0, 13.0))
    x = Normal(1.0, 0.5).ppf(u)
    assert abs(x.mean() - 1.0) < 0.01 and abs(x.std() - 0.5) < 0.01
    x = Normal(0.0, 1.0, lo=-0.5, hi=2.0).ppf(u)
    assert x.min() >= -0.5 and x.max() <= 2.0
    x = LogNormal(3.0, 0.25).ppf(u)
    assert abs(np.median(x) - 3.0) < 0.02 and abs(np.log(x).std() - 0.25) < 0.005
    k = Integers(1, 4).ppf(u)
    assert set(np.unique(k)) == {1, 2, 3, 4}
    counts = np.bincount(k)[1:] / k.size
    assert np.allclose(counts, 0.25, atol=0.01)
    c = Choice(["x", "y"]).ppf(u)
    assert set(c) == {"x", "y"}
    s = Seed().ppf(u)
    assert s.min() >= 0 and s.max() < 2**31


def test_latin_hypercube_hits_every_stratum_once():
    n = 40
    design = LatinHypercube({"a": Uniform(0.0, 1.0), "b": Relative(10.0, 0.5), "c": 3})
    plan = make_plan(design, n, seed=1)
    for name, (lo, hi) in {"a": (0.0, 1.0), "b": (5.0, 15.0)}.items():
        x = np.array([r[name] for r in plan.runs])
        strata = np.floor((x - lo) / (hi - lo) * n).astype(int)
        assert sorted(strata) == list(range(n)), name
    assert make_plan(design, n, seed=1).runs == plan.runs
    assert make_plan(design, n, seed=2).runs != plan.runs


def test_grid_is_the_full_factorial_first_axis_slowest():
    grid = Grid({"friction": [0.05, 0.1], "load": np.array([0.0, 1.0, 2.0]), "elements": 20})
    plan = make_plan(grid, None, seed=0)
    assert len(plan) == grid.size == 6
    assert [(r["friction"], r["load"]) for r in plan.runs] == [
        (0.05, 0.0), (0.05, 1.0), (0.05, 2.0), (0.1, 0.0), (0.1, 1.0), (0.1, 2.0)
    ]  # fmt: skip
    assert all(r["elements"] == 20 for r in plan.runs)
    assert plan.drawn == ["friction", "load"]
    with pytest.raises(ValueError, match="n=5 does not match"):
        make_plan(grid, 5, seed=0)


def test_saltelli_design_size_and_problem():
    design = Saltelli({"a": Uniform(0, 1), "b": Normal(0, 1), "c": 1.0})
    plan = make_plan(design, 16, seed=3)
    assert len(plan) == 16 * (2 + 2)
    assert plan.salib_problem["names"] == ["a", "b"]
    assert make_plan(design, 16, seed=3).runs == plan.runs


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: Uniform(1.0, 1.0), "empty range"),
        (lambda: Uniform(2.0, 1.0), "empty range"),
        (lambda: Uniform(0.0, math.nan), "finite"),
        (lambda: Relative(1.0, 0.0), "fraction"),
        (lambda: Normal(0.0, 0.0), "std"),
        (lambda: Normal(0.0, 1.0, lo=2.0, hi=1.0), "empty"),
        (lambda: LogNormal(-1.0, 0.2), "median"),
        (lambda: Integers(3, 2), "empty range"),
        (lambda: Choice([]), "empty"),
        (lambda: Grid({"a": []}), "empty list"),
        (lambda: Grid({"a": Uniform(0, 1)}), "distribution"),
        (lambda: Saltelli({"a": Choice(["x", "y"])}), "numeric"),
        (lambda: make_plan(MonteCarlo({"a": Uniform(0, 1)}), 0, seed=1), "positive"),
        (lambda: make_plan(MonteCarlo({"a": Uniform(0, 1)}), None, seed=1), "required"),
        (lambda: make_plan(MonteCarlo({"a": Uniform(0, 1)}), 3, seed=-1), "seed"),
        (lambda: as_design([1, 2]), "expected"),
    ],
)
def test_bad_input_is_a_clear_error(make, match):
    with pytest.raises(ValueError, match=match):
        make()
