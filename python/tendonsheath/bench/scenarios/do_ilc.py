"""do2015 repeated: iterative learning control on the paper's reference, then the learned table
run without the tip sensor, and on a route it never learned on.

A surgeon repeats a motion: each trial runs the paper's feedforward (the InverseFeedforward
of the first calibration shape, fitted from the command) plus a learned correction table, the
tip sensor (1 ms latency, its noise drawn anew each trial) measures the error, and
:class:`~tendonsheath.compensate.IterativeLearning` updates the table. Its law (lead, gain,
robustness filter) comes from the loop dynamics identified on the first calibration shape at
that latency (the tip-sensor study's loop calibration), never from the test run. The learned
table is then run as a plain feedforward (no sensor) on the fixed route, and on a shifted
route: the nominal one with both arcs bent further (0.7 pi each instead of 0.5 pi).
"""

from __future__ import annotations

import math
from typing import Any

from ...compensate import IterativeLearning
from ...plant import PullPullPlant
from ...plant.route import Route
from ..run import run
from .common import ratio

#: learning updates at most (the target: >= 1000x within them)
MAX_TRIALS = 10
LATENCY_MS = 1.0
SHIFTED = Route.arcs([(0.5, 0.0), (0.5, 0.7 * math.pi), (0.5, 0.7 * math.pi)])


def study(do: Any, fits: dict, t, y_d, tip: dict, none_fixed: float, seed: int) -> dict:
    """The learning trials, the learned table's runs, and the factors over ``none_fixed`` (the
    uncompensated MSE on the fixed route)."""
    from .do_tip import tip_sensor

    plant = do.plants("pid")[0]
    loops = tip[LATENCY_MS]["designs"]["loops"]
    feedforward = fits["single command"].inverse_feedforward(smoothing=do.SMOOTHING)
    dt = float(t[1] - t[0])
    ilc = IterativeLearning.from_dynamics(
        feedforward, t, y_d, loops[0].dynamics, dt, max_trials=MAX_TRIALS
    )
    factors: list[float] = []
    while not ilc.stopped:
        sensor = tip_sensor(LATENCY_MS * 1e-3, seed + 700 + len(factors))
        r = run(plant, ilc.compensator(), t, y_d, noise=sensor)
        ilc.update(r.measured)
        factors.append(ratio(none_fixed, r.metrics["mse"]))
    learned = ilc.best_compensator()
    sensorless = run(plant, learned, t, y_d)
    shifted_plant = PullPullPlant(route=SHIFTED, motor=do.servo_motor("pid"), **do.physics())
    shifted = {
        "none": run(shifted_plant, None, t, y_d),
        "InverseFeedforward": run(shifted_plant, feedforward, t, y_d),
        "learned": run(shifted_plant, learned, t, y_d),
    }
    return {"ilc": ilc, "factors": factors, "sensorless": sensorless, "shifted": shifted,
            "none_fixed": none_fixed, "dynamics": loops[0].dynamics}  # fmt: skip


def as_record(s: dict) -> dict[str, Any]:
    """The study as JSON-ready data."""
    shifted = {k: r.metrics["mse"] for k, r in s["shifted"].items()}
    return {
        "design": s["ilc"].design.as_dict(),
        "designed_from": f"{s['ilc'].design.summary()}; from the loop identified on "
        f"calibration shape 1: {s['dynamics'].summary()}",
        "resonance_hz": s["dynamics"].resonance_hz,
        "delay_s": s["dynamics"].delay,
        "latency_ms": LATENCY_MS,
        "factor_by_trial": s["factors"],
        "trials": len(s["factors"]) - 1,
        "stop_reason": s["ilc"].stop_reason,
        "factor_learned_no_sensor": ratio(s["none_fixed"], s["sensorless"].metrics["mse"]),
        "shifted_route_mse": shifted,
        "shifted_route_factor": {
            k: ratio(shifted["none"], v) for k, v in shifted.items() if k != "none"
        },
    }


def targets(record: dict, target) -> list[dict]:
    """>= 1000x after at most 10 trials (the learned table run without the sensor), and the
    table on the shifted route no worse than the feedforward alone there (no divergence)."""
    learned = record["factor_learned_no_sensor"]
    on_shift = record["shifted_route_factor"]
    return [
        target(f"ILC on the do2015 reference: MSE reduction after {record['trials']} trials "
               f"(learned with a {LATENCY_MS:g} ms tip sensor, run without it)", ">= 1000x",
               learned, learned >= 1000 and record["trials"] <= MAX_TRIALS, "x"),
        target("ILC: the learned table on a shifted route (MSE reduction; the feedforward "
               f"alone: {on_shift['InverseFeedforward']:.3g}x)", "no divergence",
               on_shift["learned"], on_shift["learned"] >= on_shift["InverseFeedforward"], "x"),
    ]  # fmt: skip


__all__ = ["MAX_TRIALS", "SHIFTED", "as_record", "study", "targets"]
