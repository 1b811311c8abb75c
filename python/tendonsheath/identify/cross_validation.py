"""Cross-validation over recordings: each recording (or group of recordings) is held out in
turn, an unfitted clone of the estimator is fitted on the others and simulated over the
held-out ones from their start. :func:`evaluate_splits` is the loop that
:func:`~tendonsheath.compare.compare_models` shares."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from .._typing import ArrayLike, RecordingLike, Recordings
from ..models import HysteresisModel
from .data import make_recordings
from .fit import metrics, simulate_model

#: a split: (training recordings, [(recording, first, end) scored on samples first:end])
Split = tuple[list, list[tuple[Any, int, int]]]
MAX_LEAVE_ONE_OUT = 10  # more recordings than this are grouped (default 5 groups)


@dataclass
class CrossValidation:
    """Result of :func:`cross_validate`: ``held_out`` and ``train`` metrics (rmse, nrmse,
    fit_percent, max_abs; held-out pooled over every held-out sample, training over the
    fitted samples of every fold), ``estimators`` (one fitted clone per fold, its Fit in
    ``fit_``), ``held_out_indices`` (the recordings each fold held out), ``predictions``
    (per held-out recording, fold by fold) and ``description``."""

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
    k = n if n <= MAX_LEAVE_ONE_OUT and folds is None else min(folds or 5, n)
    if k < 2:
        raise ValueError(f"folds: at least 2 are needed (got {folds})")
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
        return lambda r: simulate_model(model, r.t, r.x, r.curve_angle)

    return fit_split


def cross_validate(
    estimator: Estimator,
    recordings: Sequence[RecordingLike],
    *,
    folds: int | None = None,
    curve_angle: ArrayLike | None = None,
) -> CrossValidation:
    """Cross-validate ``estimator`` (an :class:`~tendonsheath.identify.Identifier`, or any
    object with ``clone()``, ``fit(recordings)`` and ``model_``) over ``recordings`` (at least
    two Logs, Recordings or (t, x, y[, curve_angle]) tuples): leave one recording out, or
    ``folds`` groups of recordings (round-robin). Each fold's clone runs over its held-out
    recordings from its rest state, every sample scored."""
    recs = make_recordings(recordings=list(recordings), curve_angle=curve_angle)
    groups, what = recording_groups(len(recs), folds)
    splits, _ = recording_splits(recs, folds)
    fitted: list = []
    train, held_out, preds = evaluate_splits(splits, estimator_split(estimator, fitted))
    return CrossValidation(held_out, train, fitted, groups, preds, what)
