"""What a sweep draws: per-parameter distributions and the designs that combine them.

Every distribution maps a uniform number u in (0, 1) to a value through its inverse CDF
(:meth:`Distribution.ppf`), so plain Monte Carlo, Latin hypercube and Saltelli designs all
share one definition of each parameter. Values that are not a :class:`Distribution` are
constants, passed to every run unchanged.

Designs:

* a plain ``dict`` or :class:`MonteCarlo`: independent random draws, ``n`` of them;
* :class:`LatinHypercube`: ``n`` stratified draws (scipy.stats.qmc), each parameter's range
  cut into ``n`` equal-probability strata and every stratum hit once;
* :class:`Grid`: the full factorial of value lists (``n`` is not needed);
* :class:`Saltelli`: the Sobol/Saltelli design of SALib, ``n`` base samples giving
  ``n * (d + 2)`` runs, analysed with Sobol indices by :meth:`SweepResult.sensitivity`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

_EPS = 1e-12


def _finite(value, what: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a number (got {value!r})") from None
    if not math.isfinite(x):
        raise ValueError(f"{what} must be finite (got {value!r})")
    return x


class Distribution:
    """One parameter's distribution: ``ppf(u)`` maps uniform numbers in (0, 1) to values."""

    numeric = True
    #: False for labels such as seeds, which a sensitivity ranking must not regress on
    ranked = True

    def ppf(self, u: np.ndarray) -> np.ndarray:  # pragma: no cover - abstract
        """The inverse CDF; each distribution defines it.

        Parameters
        ----------
        u : array_like of float
            Uniform numbers in (0, 1).

        Returns
        -------
        numpy.ndarray
            The values, shaped as u.
        """
        raise NotImplementedError

    def sample(self, rng: np.random.Generator, size: int | None = None) -> Any:
        """Independent draws from ``rng``.

        Parameters
        ----------
        rng : numpy.random.Generator
            The random generator.
        size : int, optional
            Number of draws; None for one value.

        Returns
        -------
        value or numpy.ndarray
            One value, or an array of ``size`` values.
        """
        u = rng.random(size)
        out = self.ppf(np.atleast_1d(u))
        return out if size is not None else out[0]

    def __eq__(self, other) -> bool:
        return type(self) is type(other) and self.__dict__ == other.__dict__

    def __hash__(self):
        return hash((type(self).__name__, repr(self)))


class Uniform(Distribution):
    """Uniform on [lo, hi) (hi > lo).

    Parameters
    ----------
    lo : float
        Lower bound.
    hi : float
        Upper bound, > lo.

    Raises
    ------
    ValueError
        A bound not finite, or hi <= lo.
    """

    def __init__(self, lo: float, hi: float):
        self.lo = _finite(lo, "Uniform: lo")
        self.hi = _finite(hi, "Uniform: hi")
        if not self.hi > self.lo:
            raise ValueError(f"Uniform: empty range [{self.lo:g}, {self.hi:g}] (need hi > lo)")

    def ppf(self, u: ArrayLike) -> np.ndarray:
        """lo + (hi - lo) u.

        Parameters
        ----------
        u : array_like of float
            Uniform numbers in (0, 1).

        Returns
        -------
        numpy.ndarray
            The values, shaped as u.
        """
        return self.lo + (self.hi - self.lo) * np.asarray(u, dtype=np.float64)

    def __repr__(self) -> str:
        return f"Uniform({self.lo:g}, {self.hi:g})"


class Relative(Uniform):
    """Uniform within +/- ``fraction`` of ``nominal``: Relative(10.0, 0.3) is Uniform(7, 13).

    Parameters
    ----------
    nominal : float
        The nominal value, not 0.
    fraction : float
        The relative half-width, > 0.

    Raises
    ------
    ValueError
        A value not finite, nominal 0 or fraction not > 0.
    """

    def __init__(self, nominal: float, fraction: float):
        self.nominal = _finite(nominal, "Relative: nominal")
        self.fraction = _finite(fraction, "Relative: fraction")
        if not 0 < self.fraction:
            raise ValueError(f"Relative: fraction must be > 0 (got {self.fraction:g})")
        if self.nominal == 0:
            raise ValueError("Relative: nominal must be non-zero (use Uniform around 0)")
        a = self.nominal * (1 - self.fraction)
        b = self.nominal * (1 + self.fraction)
        super().__init__(min(a, b), max(a, b))

    def __repr__(self) -> str:
        return f"Relative({self.nominal:g}, {self.fraction:g})"


class Normal(Distribution):
    """Normal(mean, std) (std > 0), optionally truncated to [lo, hi].

    Parameters
    ----------
    mean : float
        Mean.
    std : float
        Standard deviation, > 0.
    lo, hi : float, optional
        Truncation bounds (default none).

    Raises
    ------
    ValueError
        A value not finite, std not > 0, or a truncation range with no probability mass.
    """

    def __init__(self, mean: float, std: float, lo: float | None = None, hi: float | None = None):
        from scipy import stats

        self.mean = _finite(mean, "Normal: mean")
        self.std = _finite(std, "Normal: std")
        if not self.std > 0:
            raise ValueError(f"Normal: std must be > 0 (got {self.std:g})")
        self.lo = -math.inf if lo is None else _finite(lo, "Normal: lo")
        self.hi = math.inf if hi is None else _finite(hi, "Normal: hi")
        if not self.hi > self.lo:
            raise ValueError(f"Normal: empty truncation range [{self.lo:g}, {self.hi:g}]")
        self._cdf_lo = float(stats.norm.cdf(self.lo, self.mean, self.std))
        self._cdf_hi = float(stats.norm.cdf(self.hi, self.mean, self.std))
        if not self._cdf_hi > self._cdf_lo:
            raise ValueError(
                f"Normal: truncation range [{self.lo:g}, {self.hi:g}] has no probability mass"
            )

    def ppf(self, u: ArrayLike) -> np.ndarray:
        """The (truncated) normal inverse CDF.

        Parameters
        ----------
        u : array_like of float
            Uniform numbers in (0, 1).

        Returns
        -------
        numpy.ndarray
            The values, shaped as u.
        """
        from scipy import stats

        u = np.clip(np.asarray(u, dtype=np.float64), _EPS, 1 - _EPS)
        q = self._cdf_lo + (self._cdf_hi - self._cdf_lo) * u
        return np.clip(stats.norm.ppf(q, self.mean, self.std), self.lo, self.hi)

    def __repr__(self) -> str:
        extra = ""
        if math.isfinite(self.lo) or math.isfinite(self.hi):
            extra = f", lo={self.lo:g}, hi={self.hi:g}"
        return f"Normal({self.mean:g}, {self.std:g}{extra})"


class LogNormal(Distribution):
    """Log-normal: ln X ~ Normal(ln median, sigma); median > 0, sigma > 0 (e.g. 0.2 ~ 20 %).

    Parameters
    ----------
    median : float
        Median, > 0.
    sigma : float
        Standard deviation of ln X, > 0.

    Raises
    ------
    ValueError
        A value not finite or not > 0.
    """

    def __init__(self, median: float, sigma: float):
        self.median = _finite(median, "LogNormal: median")
        self.sigma = _finite(sigma, "LogNormal: sigma")
        if not self.median > 0:
            raise ValueError(f"LogNormal: median must be > 0 (got {self.median:g})")
        if not self.sigma > 0:
            raise ValueError(f"LogNormal: sigma must be > 0 (got {self.sigma:g})")

    def ppf(self, u: ArrayLike) -> np.ndarray:
        """median exp(sigma Phi^-1(u)).

        Parameters
        ----------
        u : array_like of float
            Uniform numbers in (0, 1).

        Returns
        -------
        numpy.ndarray
            The values, shaped as u.
        """
        from scipy import stats

        u = np.clip(np.asarray(u, dtype=np.float64), _EPS, 1 - _EPS)
        return self.median * np.exp(self.sigma * stats.norm.ppf(u))

    def __repr__(self) -> str:
        return f"LogNormal({self.median:g}, {self.sigma:g})"


class Integers(Distribution):
    """Uniform integers lo, lo + 1, ..., hi (inclusive); e.g. a seed for a random route.

    Parameters
    ----------
    lo : int
        Lowest value.
    hi : int
        Highest value, >= lo.

    Raises
    ------
    ValueError
        A bound that is not an integer, or hi < lo.
    """

    def __init__(self, lo: int, hi: int):
        if int(lo) != lo or int(hi) != hi:
            raise ValueError(f"Integers: bounds must be integers (got {lo!r}, {hi!r})")
        self.lo, self.hi = int(lo), int(hi)
        if self.hi < self.lo:
            raise ValueError(f"Integers: empty range [{self.lo}, {self.hi}] (need hi >= lo)")

    def ppf(self, u: ArrayLike) -> np.ndarray:
        """The integer of the stratum u falls in.

        Parameters
        ----------
        u : array_like of float
            Uniform numbers in (0, 1).

        Returns
        -------
        numpy.ndarray
            The values, shaped as u.
        """
        k = np.floor(np.asarray(u, dtype=np.float64) * (self.hi - self.lo + 1)).astype(np.int64)
        return self.lo + np.clip(k, 0, self.hi - self.lo)

    def __repr__(self) -> str:
        return f"Integers({self.lo}, {self.hi})"


class Seed(Integers):
    """A random integer seed per run (e.g. for a random route): drawn like Integers(0, 2**31 - 1)
    but left out of sensitivity rankings, since its value has no order that means anything."""

    ranked = False

    def __init__(self):
        super().__init__(0, 2**31 - 1)

    def __repr__(self) -> str:
        return "Seed()"


class Choice(Distribution):
    """One of ``values``, each equally likely (values may be numbers or strings).

    Parameters
    ----------
    values : sequence
        The choices, at least one.

    Raises
    ------
    ValueError
        Not a list, or an empty one.
    """

    def __init__(self, values: Sequence[Any]):
        if isinstance(values, str | bytes) or not isinstance(values, Iterable):
            raise ValueError(f"Choice: values must be a list (got {values!r})")
        self.values = list(values)
        if not self.values:
            raise ValueError("Choice: empty list of values")
        self.numeric = all(
            isinstance(v, int | float | np.integer | np.floating) and not isinstance(v, bool)
            for v in self.values
        )
        self.ranked = self.numeric

    def ppf(self, u: ArrayLike) -> np.ndarray:
        """The value of the stratum u falls in.

        Parameters
        ----------
        u : array_like of float
            Uniform numbers in (0, 1).

        Returns
        -------
        numpy.ndarray
            The values, shaped as u.
        """
        k = np.floor(np.asarray(u, dtype=np.float64) * len(self.values)).astype(np.int64)
        k = np.clip(k, 0, len(self.values) - 1)
        return np.array([self.values[i] for i in k], dtype=object if not self.numeric else None)

    def __repr__(self) -> str:
        return f"Choice({self.values!r})"


# -- designs -------------------------------------------------------------------------------


def _split(spec: Mapping[str, Any], what: str) -> tuple[dict[str, Distribution], dict[str, Any]]:
    if not isinstance(spec, Mapping):
        raise ValueError(f"{what}: expected a mapping of parameter names (got {type(spec)})")
    drawn: dict[str, Distribution] = {}
    fixed: dict[str, Any] = {}
    for name, value in spec.items():
        if not isinstance(name, str) or not name:
            raise ValueError(f"{what}: parameter names must be non-empty strings (got {name!r})")
        (drawn if isinstance(value, Distribution) else fixed)[name] = value
    return drawn, fixed


class Design:
    """A set of parameters and how to combine their draws into runs.

    Parameters
    ----------
    parameters : mapping of str to Distribution or value
        Parameter name -> a :class:`Distribution` (drawn) or any other value (a constant).

    Raises
    ------
    ValueError
        Not a mapping, or a parameter name that is not a non-empty string.
    """

    kind = "design"

    def __init__(self, parameters: Mapping[str, Any]):
        self.distributions, self.fixed = _split(parameters, type(self).__name__)

    @property
    def names(self) -> list[str]:
        """The parameter names, drawn ones first."""
        return [*self.distributions, *self.fixed]

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in {**self.distributions, **self.fixed}.items())
        return f"{type(self).__name__}({inner})"


class MonteCarlo(Design):
    """Independent random draws of every distribution (what a plain dict means).

    Parameters
    ----------
    parameters : mapping of str to Distribution or value
        Parameter name -> a :class:`Distribution` (drawn) or any other value (a constant).

    Raises
    ------
    ValueError
        Not a mapping, or a parameter name that is not a non-empty string.
    """

    kind = "random"


class LatinHypercube(Design):
    """Latin hypercube draws (scipy.stats.qmc.LatinHypercube), mapped through each ppf.

    Parameters
    ----------
    parameters : mapping of str to Distribution or value
        Parameter name -> a :class:`Distribution` (drawn; at least one) or a constant.
    optimization : str, optional
        scipy's ``optimization`` of the hypercube (e.g. "random-cd").

    Raises
    ------
    ValueError
        Not a mapping, a bad name, or no distribution.
    """

    kind = "lhs"

    def __init__(self, parameters: Mapping[str, Any], optimization: str | None = None):
        super().__init__(parameters)
        if not self.distributions:
            raise ValueError("LatinHypercube: needs at least one distribution")
        self.optimization = optimization


class Saltelli(Design):
    """SALib's Saltelli/Sobol design: ``n`` base samples (a power of 2) -> n * (d + 2) runs,
    first-order and total Sobol indices in :meth:`SweepResult.sensitivity`.

    Parameters
    ----------
    parameters : mapping of str to Distribution or value
        Parameter name -> a numeric :class:`Distribution` (at least one) or a constant.

    Raises
    ------
    ValueError
        Not a mapping, a bad name, no distribution, or a non-numeric one.
    """

    kind = "saltelli"

    def __init__(self, parameters: Mapping[str, Any]):
        super().__init__(parameters)
        if not self.distributions:
            raise ValueError("Saltelli: needs at least one distribution")
        for name, d in self.distributions.items():
            if not d.numeric:
                raise ValueError(f"Saltelli: parameter {name!r} must be numeric (got {d!r})")


class Grid(Design):
    """The full factorial of value lists: Grid({"friction": [0.05, 0.1], "load": [0, 1, 2]})
    is 6 runs; the first parameter varies slowest. Scalars are constants.

    Parameters
    ----------
    parameters : mapping of str to list or value
        Parameter name -> a list of values (an axis) or a scalar (a constant).

    Raises
    ------
    ValueError
        Not a mapping, a bad name, a distribution, or an empty list.
    """

    kind = "grid"

    def __init__(self, parameters: Mapping[str, Any]):
        if not isinstance(parameters, Mapping):
            raise ValueError(f"Grid: expected a mapping of parameter names (got {parameters!r})")
        self.axes: dict[str, list] = {}
        self.fixed = {}
        self.distributions = {}
        for name, value in parameters.items():
            if not isinstance(name, str) or not name:
                raise ValueError(f"Grid: parameter names must be non-empty strings ({name!r})")
            if isinstance(value, Distribution):
                raise ValueError(
                    f"Grid: {name!r} is a distribution ({value!r}); give a list of values "
                    "(or use a random or Latin hypercube design)"
                )
            if isinstance(value, str | bytes) or not isinstance(value, Iterable):
                self.fixed[name] = value
                continue
            values = (
                list(np.asarray(value).tolist()) if isinstance(value, np.ndarray) else list(value)
            )
            if not values:
                raise ValueError(f"Grid: {name!r} has an empty list of values")
            self.axes[name] = values

    @property
    def names(self) -> list[str]:
        """The parameter names, axes first."""
        return [*self.axes, *self.fixed]

    @property
    def size(self) -> int:
        """The number of runs (the product of the axes' lengths)."""
        return math.prod(len(v) for v in self.axes.values())

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in {**self.axes, **self.fixed}.items())
        return f"Grid({inner})"


def as_design(spec) -> Design:
    """A design from a Design or a plain mapping (plain mapping: Monte Carlo)."""
    if isinstance(spec, Design):
        return spec
    if isinstance(spec, Mapping):
        return MonteCarlo(spec)
    raise ValueError(
        "sweep: expected a Grid, MonteCarlo, LatinHypercube, Saltelli or a dict of "
        f"parameter -> distribution (got {type(spec).__name__})"
    )


__all__ = [
    "Choice",
    "Design",
    "Distribution",
    "Grid",
    "Integers",
    "LatinHypercube",
    "LogNormal",
    "MonteCarlo",
    "Normal",
    "Relative",
    "Saltelli",
    "Seed",
    "Uniform",
    "as_design",
]
