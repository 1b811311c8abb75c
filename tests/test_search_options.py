"""The global search may take coarser numerical options than the fit (it needs the basin)."""

import numpy as np

import tendonsheath as ts
from tendonsheath.identify.problem import _search_base
from tendonsheath.identify.specs import BoucWenBacklashSpec, HystereticOscillatorSpec
from tendonsheath.models import BoucWenBacklash, HystereticOscillator


def test_search_coarsens_max_step_and_caps_substeps():
    opts = BoucWenBacklash().options
    base = _search_base(BoucWenBacklash, opts, BoucWenBacklashSpec.search_options)
    assert base.max_step == 0.1 and opts["max_step"] == 0.05
    # a user's coarser step is kept (the search never refines what the fit uses)
    assert (
        _search_base(BoucWenBacklash, {**opts, "max_step": 0.3}, {"max_step": 0.1}).max_step == 0.3
    )
    osc = HystereticOscillator().options
    capped = _search_base(HystereticOscillator, osc, HystereticOscillatorSpec.search_options)
    assert capped.max_substeps == 64 and osc["max_substeps"] == 4096


def test_fitted_bouc_wen_backlash_keeps_its_own_step_and_recovers_the_truth():
    t = np.linspace(0.0, 10.0, 1500)
    x = np.sin(2 * np.pi * 0.3 * t) * (1.0 + 0.5 * np.sin(2 * np.pi * 0.07 * t))
    truth = BoucWenBacklash(c_r=1.2, c_l=0.8, B_r=0.1, B_l=0.15, sigma=2.0, n=3.0)
    y = truth.simulate(t, x)
    fit = ts.identify(BoucWenBacklash, t, x, y, progress=False)
    assert fit.model.options["max_step"] == 0.05
    # noise-free data: the search's coarser sub-steps still land in the basin that the
    # refinement (at the model's own step) closes (measured: rmse 9e-12 of the range)
    assert fit.rmse < 1e-6 * np.ptp(y)
