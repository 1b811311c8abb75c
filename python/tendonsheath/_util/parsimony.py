"""The parsimony rule of :func:`~tendonsheath.apps.compare.compare_models`: a candidate with more
parameters wins only by a stated margin.

Among the eligible candidates (``_util.eligibility``; the affine map y = a x + b is one,
with 2 parameters), let ``best`` be the one with the lowest error of the objective (val_nrmse,
or inv_nrmse for "compensation"). With ``parsimony`` p, the winner is the candidate with the
fewest parameters whose error is at most (1 + p) times the best's; among those with that
number of parameters, the one with the lowest error. p = 0 is the plain ranking: the best
wins (a tie in error goes to the fewer parameters).

The default is 0: the held-out error already charges a candidate for the parameters that only
fit noise (it is measured on data the fit did not see), and what share of error is worth a
simpler model is the user's call (5 % of a 0.1 deg error is nothing, 5 % of a 3 deg one is
not). The comparison still says when a smaller candidate is within
:data:`HINT` of the winner, so the user can ask for it (``parsimony=``, ``--parsimony``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

#: a smaller candidate this close to the winner (a share of the winner's error) is pointed out
HINT = 0.05


def check_parsimony(parsimony: Any) -> float:
    """``parsimony``: a finite number >= 0 (a share of the best error; ValueError otherwise)."""
    ok = isinstance(parsimony, int | float) and not isinstance(parsimony, bool)
    if not (ok and np.isfinite(parsimony) and parsimony >= 0):
        raise ValueError(
            f"parsimony must be a number >= 0 (a share of the best candidate's error, e.g. "
            f"0.05 for 5 %) (got {parsimony!r})"
        )
    return float(parsimony)


def _metric(objective: str) -> tuple[str, str]:
    if objective == "compensation":
        return "inv_nrmse", "inverse error"
    return "val_nrmse", "held-out error"


def _eligible(rows: list[dict], key: str) -> list[int]:
    """Indices of the rows that may win and have a finite error of the objective."""
    return [
        i
        for i, r in enumerate(rows)
        if not r.get("error")
        and r.get("eligible", False)
        and r.get(key) is not None
        and np.isfinite(r[key])
    ]


def choose(rows: list[dict], objective: str, parsimony: float) -> tuple[int, str]:
    """The winner's index in ``rows`` under the parsimony rule (see the module docstring) and
    the choice in words ("" where the best candidate wins outright and none smaller is within
    :data:`HINT` of it). Falls back to row 0 where no row may win (rows sorted by
    :func:`tendonsheath._util.eligibility.sort_key`)."""
    key, what = _metric(objective)
    ok = _eligible(rows, key)
    if not ok:
        return 0, ""
    best = min(ok, key=lambda i: rows[i][key])
    limit = (1.0 + parsimony) * rows[best][key]
    within = [i for i in ok if rows[i][key] <= limit]
    win = min(within, key=lambda i: (rows[i]["n_params"], rows[i][key]))
    if win != best:
        w, b = rows[win], rows[best]
        return win, (
            f"{w['model']} wins: its {what} is within {_share(w[key], b[key])} of "
            f"{b['model']}'s with {w['n_params']} parameters instead of {b['n_params']} "
            f"(parsimony {100 * parsimony:g} %)"
        )
    return win, _hint(rows, ok, win, key, what, parsimony)


def _hint(rows, ok: list[int], win: int, key: str, what: str, parsimony: float) -> str:
    """A smaller eligible candidate within HINT of the winner that the parsimony did not
    choose: what --parsimony would choose it ("" if none)."""
    w = rows[win]
    smaller = [
        i
        for i in ok
        if rows[i]["n_params"] < w["n_params"] and rows[i][key] <= (1.0 + HINT) * w[key]
    ]
    if not smaller:
        return ""
    s = rows[min(smaller, key=lambda i: (rows[i]["n_params"], rows[i][key]))]
    return (
        f"{w['model']} wins by the {what} (parsimony {100 * parsimony:g} %); {s['model']} has "
        f"{s['n_params']} parameters instead of {w['n_params']} and is within "
        f"{_share(s[key], w[key])} of it: a parsimony of {_enough(s[key], w[key])} % would "
        "choose it"
    )


def _share(value: float, best: float) -> str:
    """How far ``value`` is above ``best``, in percent."""
    if best <= 0:
        return "0 %" if value <= best else "inf %"
    return f"{100 * (value / best - 1.0):.1f} %"


def _enough(value: float, best: float) -> int:
    """The smallest whole percent p with value <= (1 + p / 100) best (value > best > 0)."""
    p = max(int(np.ceil(100 * (value / best - 1.0) - 1e-9)), 0)
    while value > (1.0 + p / 100) * best:
        p += 1
    return p
