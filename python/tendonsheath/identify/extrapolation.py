"""What an identified model does past its training inputs: the envelopes of a
GeneralizedPrandtlIshlinskii continue along their tangent lines beyond the training inputs'
range instead of saturating (a tanh fitted inside the data flattens out past it, predicting a
saturation the data never showed: on a longer stroke its error grows without bound)."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..models import Chain, GeneralizedPrandtlIshlinskii, HysteresisModel, LinearBlock, Scaled
from ..models.generalized_prandtl_ishlinskii import GeneralizedPrandtlIshlinskiiInverse

_GPI = (GeneralizedPrandtlIshlinskii, GeneralizedPrandtlIshlinskiiInverse)


def bounded_to_training(model: HysteresisModel, lo: float, hi: float) -> HysteresisModel:
    """``model`` with every GeneralizedPrandtlIshlinskii in it extrapolating beyond the
    training inputs' range [lo, hi] (data units) along its envelopes' tangents (its
    ``envelope_range``); other models are returned as they are.

    Parameters
    ----------
    model : HysteresisModel
        An identified model: a GeneralizedPrandtlIshlinskii, a Scaled one (its range in the
        inner model's units) or a Chain with one (a unit-gain linear block before it keeps
        the range).
    lo, hi : float
        The training inputs' range.

    Returns
    -------
    HysteresisModel
        The model with its envelope range set (a new object where one changed).
    """
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        return model
    if isinstance(model, _GPI):
        return model.with_params(envelope_range=(float(lo), float(hi)))
    if isinstance(model, Scaled):
        c, s = model.map["input_offset"], model.map["input_scale"]
        inner = bounded_to_training(model.inner, (lo - c) / s, (hi - c) / s)
        if inner is model.inner:
            return model
        return Scaled(inner, *model.map.values())
    if isinstance(model, Chain):
        first = bounded_to_training(model.first, lo, hi)
        second = model.second
        if isinstance(model.first, LinearBlock):  # Wiener: a unit-gain lag, then the operator
            second = bounded_to_training(second, lo, hi)
        if first is model.first and second is model.second:
            return model
        return Chain(first, second)
    return model


def with_training_range(fit, recs):
    """The Fit with its model bounded to the recordings' input range (see
    :func:`bounded_to_training`); the Fit itself when nothing changed."""
    lo = min(float(np.min(r.x)) for r in recs)
    hi = max(float(np.max(r.x)) for r in recs)
    model = bounded_to_training(fit.model, lo, hi)
    return fit if model is fit.model else dataclasses.replace(fit, model=model)


__all__ = ["bounded_to_training", "with_training_range"]
