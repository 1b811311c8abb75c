"""Loaded runs of a physics plant, outside every model class: a pull-pull pair (capstan friction
along a bent sheath, compliant tendons, sheath viscosity, tendon creep, an unequal pair, a
dynamic distal joint) under a distal load torque that is constant or a spring's (so it varies
with the output), with the load measured (the torque at the joint, with sensor noise) and the
output read by a noisy encoder. Shared by tests/test_loaded_bases.py and
benchmarks/loaded_bases.py."""

from __future__ import annotations

import warnings

import numpy as np

import tendonsheath as ts

#: the load scenarios, (name, torque preload N m, spring N m/rad): constant torques and springs
SCENARIOS = (
    ("const -0.03", -0.03, 0.0),
    ("const 0.00", 0.0, 0.0),
    ("const +0.02", 0.02, 0.0),
    ("const +0.04", 0.04, 0.0),
    ("const +0.05", 0.05, 0.0),
    ("spring 0.01+0.03q", 0.01, 0.03),
    ("spring -0.02+0.04q", -0.02, 0.04),
    ("spring 0.03+0.02q", 0.03, 0.02),
)
#: the training split: three constant loads and a spring; the other four are held out
TRAIN = ("const -0.03", "const +0.02", "const +0.05", "spring 0.01+0.03q")


def plant_parameters(seed: int) -> dict:
    """A drawn drive: friction, stiffness, pretension, route bend (the physics varies by seed)."""
    rng = np.random.default_rng(1000 + seed)
    return {
        "friction": float(rng.uniform(0.08, 0.14)),
        "stiffness": float(rng.uniform(4e3, 7e3)),
        "pretension": float(rng.uniform(9.0, 12.0)),
        "bend": float(rng.uniform(1.5, 2.5) * np.pi),
    }


def make_plant(params: dict, preload: float, spring: float, elements: int = 16):
    """The pull-pull pair under a constant torque (spring 0) or a torsional spring."""
    route = ts.Route.uniform(1.0, params["bend"])
    load = (
        ts.loads.TorsionalSpring(spring, preload=preload)
        if spring
        else ts.loads.ConstantTorque(preload)
    )
    return ts.PullPullPlant(
        route,
        friction=params["friction"],
        stiffness=params["stiffness"],
        pretension=params["pretension"],
        proximal_radius=5e-3,
        distal_radius=5e-3,
        elements=elements,
        load=load,
        distal_inertia=2e-6,
        distal_damping=2e-4,
        sheath_viscosity=8.0,
        relaxation_fraction=0.08,
        relaxation_time=1.5,
        friction2=1.15 * params["friction"],
        stiffness2=0.9 * params["stiffness"],
    )


def loaded_run(
    seed: int,
    scenario: tuple[str, float, float],
    *,
    seconds: float = 6.0,
    rate: float = 50.0,
    elements: int = 16,
) -> ts.io.Log:
    """One run: a two-tone input (rad) with a drawn phase, the plant's output plus 2 mrad of
    encoder noise, and the measured load (the joint torque, N m, plus 0.5 mN m of noise)."""
    name, preload, spring = scenario
    k = [s[0] for s in SCENARIOS].index(name)
    rng = np.random.default_rng(seed * 100 + k)
    params = plant_parameters(seed)
    t = np.arange(0.0, seconds, 1.0 / rate)
    f1 = rng.uniform(0.3, 0.6)
    x = 0.6 * np.sin(2 * np.pi * f1 * t + rng.uniform(0, 6)) + 0.2 * np.sin(
        2 * np.pi * 2.3 * f1 * t + rng.uniform(0, 6)
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        q = np.asarray(make_plant(params, preload, spring, elements).simulate(t, x).q_out)
    torque = preload + spring * q
    y = q + rng.normal(0.0, 2e-3, t.size)
    load = torque + rng.normal(0.0, 5e-4, t.size)
    return ts.io.Log(t, x, y, load=load)


def loaded_runs(seed: int, **kw) -> dict[str, ts.io.Log]:
    """Every scenario's run for one drawn drive."""
    return {s[0]: loaded_run(seed, s, **kw) for s in SCENARIOS}
