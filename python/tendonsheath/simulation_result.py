"""One result type for every run (a plant's or a model's ``simulate``, a compensator's
``command``, a closed loop of ``bench.run``): the output as an array, plus its time, input,
success, message and ``.plot()``; a closed loop's also its reference and metrics.

It is a NumPy array subclass holding the output samples, so code that used the array a
``simulate`` returned (``np.asarray(res)``, ``res[k]``, ``res - y``, ``np.mean(res)``) runs
unchanged; indexing and arithmetic give plain arrays. A plant's result also has the plant's
fields (``q_out``, ``q_in``, ``measured``, ``slack``, ...).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, SubFigure

# the fields a result may carry besides t and input (then a plant's, then a closed loop's)
FIELDS = (
    "success",
    "message",
    "status",
    "command",
    "q_in",
    "q_motor",
    "measured",
    "slack",
    "tensions",
    "nonconverged",
    "input_interpolation",
    "reference",
    "metrics",
)


class SimulationResult(np.ndarray):
    """The output of a simulation (an array) with what produced it.

    Attributes: ``t`` (s, or None), ``input``, ``output`` (the same samples as a plain
    array), ``success`` (False when the output cannot be trusted: non-finite samples, a slack
    tendon, an unconverged step), ``message`` (why, or ""), ``status`` (each sample's
    :class:`~tendonsheath.Status` flags, uint8, where the simulate reports them).

    A plant's result also has ``command`` (what was given, = ``input``), ``q_in`` (the plant
    input after the motor: the proximal pulley angle), ``q_motor`` (the motor shaft angle its
    encoder reads: ``q_in`` plus the gear play), ``q_out`` (= output), ``measured`` (the
    sensor reading of q_out), ``slack`` (a per-sample flag), ``tensions`` (the final tensions;
    rows: tendons, proximal to distal), ``nonconverged`` (accepted but unconverged active-set
    increments, 0 in normal use) and ``input_interpolation``. A closed loop's
    (:class:`tendonsheath.bench.Result`) has ``reference`` (the desired output) and
    ``metrics``.

    Parameters
    ----------
    output : array_like of float
        The output samples.
    t : array_like of float, optional
        Sample times (s); None for a rate-independent model simulated without them.
    input : array_like of float, optional
        The input samples.
    **fields : Any
        The other attributes by name (``success``, ``message``, ``status`` and a plant's
        fields above); ``success`` and ``message`` default to an assessment of the output,
        ``slack`` and ``nonconverged``.

    Raises
    ------
    TypeError
        A field name that is none of these (it is named).
    """

    _info: dict[str, Any]
    _fields: tuple[str, ...] = FIELDS  # the fields this kind of result takes

    def __new__(cls, output, t=None, input=None, **fields: Any) -> SimulationResult:
        unknown = [name for name in fields if name not in cls._fields]
        if unknown:
            raise TypeError(
                f"{cls.__name__}() got an unexpected keyword argument {unknown[0]!r} "
                f"(fields: {', '.join(cls._fields)})"
            )
        obj = np.asarray(output, dtype=float).view(cls)
        out = obj.view(np.ndarray)
        success, message = _assess(out, fields)
        obj._info = {
            "t": t,
            "input": input,
            "success": fields.pop("success", success),
            "message": fields.pop("message", message),
            "status": fields.pop("status", None),
            **fields,
        }
        return obj

    def __array_finalize__(self, obj) -> None:
        self._info = getattr(obj, "_info", {})

    def __array_wrap__(self, arr, context=None, return_scalar=False):
        out = arr.view(np.ndarray)  # arithmetic and reductions give plain arrays
        return out[()] if return_scalar else out

    def __getitem__(self, key):
        return self.view(np.ndarray)[key]

    def __getattr__(self, name: str):
        if name.startswith("_"):
            raise AttributeError(name)
        info = self.__dict__.get("_info", {})
        if name in info:
            return info[name]
        raise AttributeError(f"{type(self).__name__!r} has no attribute {name!r}")

    def __reduce__(self):
        base = super().__reduce__()
        return (base[0], base[1], (base[2], self._info))

    def __setstate__(self, state) -> None:
        array_state, self._info = state
        super().__setstate__(array_state)

    def __repr__(self) -> str:
        ok = "success" if self.success else f"failed: {self.message}"
        return f"{type(self).__name__}({self.size} samples, {ok})"

    @property
    def output(self) -> np.ndarray:
        """The output samples as a plain array."""
        return self.view(np.ndarray)

    @property
    def q_out(self) -> np.ndarray:
        """The output samples as a plain array (a plant's name for :attr:`output`)."""
        return self.output

    @property
    def any_slack(self) -> bool:
        """Whether a tendon went slack at any sample (False without a ``slack`` field)."""
        slack = self._info.get("slack")
        return bool(slack is not None and np.any(slack))

    @property
    def first_slack_index(self) -> int | None:
        """Index of the first slack sample (None when there is none, or no ``slack`` field)."""
        slack = self._info.get("slack")
        idx = np.flatnonzero(slack) if slack is not None else np.array([], dtype=int)
        return int(idx[0]) if idx.size else None

    def plot(self, ax: Sequence[Axes] | None = None) -> Figure | SubFigure:
        """Input and output against time (or sample), and output against input.

        The figure's title is the message when the result failed.

        Parameters
        ----------
        ax : sequence of two matplotlib.axes.Axes, optional
            The axes to draw into (default: a new figure with two).

        Returns
        -------
        matplotlib.figure.Figure
            The figure drawn into.
        """
        import matplotlib.pyplot as plt

        fig: Figure | SubFigure
        if ax is None:
            fig, ax = plt.subplots(1, 2, figsize=(9, 3.5), constrained_layout=True)
        else:
            fig = ax[0].figure
        x = np.arange(self.size) if self.t is None else self.t
        if self.input is not None:
            ax[0].plot(x, self.input, label="input")
            ax[1].plot(self.input, self.output, lw=1)
        ax[0].plot(x, self.output, label="output")
        ax[0].set_xlabel("sample" if self.t is None else "t (s)")
        ax[0].legend()
        ax[1].set_xlabel("input")
        ax[1].set_ylabel("output")
        if not self.success:
            fig.suptitle(self.message)
        return fig


def _assess(output: np.ndarray, fields: dict) -> tuple[bool, str]:
    """success and message from the output and the plant's flags."""
    bad = int(np.count_nonzero(~np.isfinite(output)))
    if bad:
        return False, f"{bad} non-finite output sample(s)"
    slack = fields.get("slack")
    if slack is not None and np.any(slack):
        k = int(np.flatnonzero(slack)[0])
        return False, f"a tendon went slack (tension <= 0) first at sample {k}"
    if fields.get("nonconverged"):
        return False, f"{fields['nonconverged']} step(s) did not converge"
    return True, ""


__all__ = ["FIELDS", "SimulationResult"]
