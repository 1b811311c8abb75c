"""Cross-validation over recordings: each recording (or group of recordings) is held out in
turn, an unfitted clone of the estimator is fitted on the others and simulated over the
held-out ones from their start. :func:`evaluate_splits` is the loop that
:func:`~tendonsheath.apps.compare.compare_models` shares."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from .._util.typing import ArrayLike, RecordingLike, Recordings
from ..models import HysteresisModel
from .data import make_recordings
from .fit import metrics, simulate_model

#: a split: (training recordings, [(recording, first, end) scored on samples first:end])
Split = tuple[list, list[tuple[Any, int, int]]]
MAX_LEAVE_ONE_OUT = 10  # more recordings than this are grouped (default 5 groups)


@dataclass
class CrossValidation:
    """Result of :func:`cross_validate`: the pooled metrics, the fitted clones and the
    held-out predictions.

    The metrics are those of :func:`~tendonsheath.identify.metrics`: rmse, nrmse,
    fit_percent and max_abs.

    Parameters
    ----------
    held_out : dict of str to float
        Metrics pooled over every sample of every held-out recording of all folds (each
        simulated from its fold's model's rest state; no warm-up left out).
    train : dict of str to float
        Metrics pooled over each fold's training recordings, simulated by that fold's model
        (every sample but a Recording's ``skip``: the estimator's ``warmup`` samples count).
    estimators : list
        One fitted clone of the estimator per fold, its Fit in ``fit_``.
    held_out_indices : list of list of int
        The indices of the recordings each fold held out.
    predictions : list of numpy.ndarray of float
        The held-out predictions, one per held-out recording, fold by fold (in the order of
        ``held_out_indices`` flattened).
    description : str, default ""
        How the recordings were split, e.g. "cross-validation: leave one recording out
        (3 folds)".
    """

    held_out: dict[str, float]
    train: dict[str, float]
    estimators: list = field(repr=False)
    held_out_indices: list[list[int]]
    predictions: list[np.ndarray] = field(repr=False)
    description: str = ""


def recording_groups(n: int, folds: int | None = None) -> tuple[list[list[int]], str]:
    """The held-out recording indices of each fold and a description: leave one recording
    out (``folds`` None and at most 10 recordings), else round-robin into ``folds`` (default
    5) groups."""
    if n < 2:
        raise ValueError(f"cross-validation over recordings needs at least 2 (got {n})")
    if folds is not None:
        if isinstance(folds, bool) or not isinstance(folds, int | np.integer):
            raise TypeError(f"folds must be an integer (got {folds!r})")
        if folds < 2:
            raise ValueError(f"folds: at least 2 are needed (got {folds})")
    k = n if n <= MAX_LEAVE_ONE_OUT and folds is None else min(folds or 5, n)
    groups = [list(range(g, n, k)) for g in range(k)]
    what = "recording" if k == n else "group of recordings"
    return groups, f"cross-validation: leave one {what} out ({k} folds)"


def recording_splits(recs: list, folds: int | None = None) -> tuple[list[Split], str]:
    """The splits of :func:`recording_groups`: train on the others, score every sample of
    the held-out recordings."""
    groups, what = recording_groups(len(recs), folds)
    splits = []
    for g in groups:
        train = [r for i, r in enumerate(recs) if i not in g]
        splits.append((train, [(recs[i], 0, recs[i].n) for i in g]))
    return splits, what


def evaluate_splits(
    splits: list[Split],
    fit_split: Callable[[list], Callable[[Any], np.ndarray]],
    on_fold: Callable[[int], None] | None = None,
):
    """Fit on every split's training part (``fit_split(train)`` returns ``predict(rec)``, the
    model's output over a whole recording) and score: (training metrics, held-out metrics,
    held-out predictions). ``on_fold(k)`` is called after fold k's fit (it may raise)."""
    ys, yh, ts_, th, preds = [], [], [], [], []
    for k, (train, evals) in enumerate(splits):
        predict = fit_split(train)
        if on_fold is not None:
            on_fold(k)
        for r in train:
            ts_.append(r.y[r.skip :])
            th.append(predict(r)[r.skip :])
        for r, a, b in evals:
            p = predict(r)
            ys.append(r.y[a:b])
            yh.append(p[a:b])
            preds.append(p[a:b])
    train_metrics = metrics(np.concatenate(ts_), np.concatenate(th))
    return train_metrics, metrics(np.concatenate(ys), np.concatenate(yh)), preds


class Estimator(Protocol):
    """What :func:`cross_validate` needs of an estimator (an Identifier, or one of the user's):
    ``clone()`` an unfitted copy, ``fit(recordings)``, then ``model_`` the fitted model."""

    model_: HysteresisModel

    def clone(self) -> Estimator: ...

    def fit(self, recordings: Recordings) -> Any: ...


def estimator_split(estimator, fitted: list):
    """``fit_split`` for :func:`evaluate_splits`: an unfitted clone of ``estimator`` fitted
    on the training recordings (appended to ``fitted``), predicting over a recording."""

    def fit_split(train):
        est = estimator.clone()
        est.fit(train)
        fitted.append(est)
        model = est.model_
        return lambda r: simulate_model(model, r.t, r.x, r.angle_input, getattr(r, "load", None))

    return fit_split


def cross_validate(
    estimator: Estimator,
    recordings: Sequence[RecordingLike],
    *,
    folds: int | None = None,
    curve_angle: ArrayLike | None = None,
) -> CrossValidation:
    """Cross-validate an estimator over recordings: fit on some, predict the others.

    Each fold holds out one recording (leave one out: ``folds`` None and at most 10
    recordings) or a group of recordings (round-robin: fold g holds out recordings g, g + k,
    g + 2k, ... of k folds), fits an unfitted clone of ``estimator`` on the other recordings
    and simulates its model over the held-out ones from its rest state, every sample scored.

    Parameters
    ----------
    estimator : Identifier
        An unfitted or fitted :class:`~tendonsheath.identify.Identifier`, or any object with
        ``clone()``, ``fit(recordings)`` and ``model_``; it is not changed.
    recordings : sequence of Log, Recording or tuple
        At least two recordings: Logs, Recordings, or (t, x, y) or (t, x, y, curve_angle)
        tuples.
    folds : int, optional
        The number of groups of recordings (at least 2; more than the recordings gives leave
        one out). Default: leave one out up to 10 recordings, else 5 groups.
    curve_angle : float or array_like of float, optional
        The curve angle (rad) of the recordings that carry none, for models that take one.

    Returns
    -------
    CrossValidation
        The held-out and training metrics, the fitted clones, the held-out predictions and
        a description of the split.

    Raises
    ------
    ValueError
        Fewer than two recordings, ``folds`` below 2, or bad data or settings (the message
        names them).
    """
    recs = make_recordings(recordings=list(recordings), curve_angle=curve_angle)
    groups, what = recording_groups(len(recs), folds)
    splits, _ = recording_splits(recs, folds)
    fitted: list = []
    train, held_out, preds = evaluate_splits(splits, estimator_split(estimator, fitted))
    return CrossValidation(held_out, train, fitted, groups, preds, what)


__all__ = [
    "CrossValidation",
    "Estimator",
    "MAX_LEAVE_ONE_OUT",
    "Split",
    "cross_validate",
    "estimator_split",
    "evaluate_splits",
    "recording_groups",
    "recording_splits",
]
