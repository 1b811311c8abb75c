"""Sweep throughput: runs per second on 1 and 2 local workers and a two-worker Dask LocalCluster.

    python benchmarks/sweep.py [--runs 200]

The run is the do2015 scenario at reduced length (tendonsheath.bench.scenarios.do:
robustness_run: 10 s of the do2015 reference on a plant with drawn friction, pretension and
random-arc route; none, InverseFeedforward and AdaptiveController, calibrated once per process
on the nominal plant). Prints a table and writes benchmarks/results/sweep.json.

Figures:
* "a run": the run called directly in a loop in this process.
* speedup = runs * (a run) / wall time. The local pool is started by a first tiny sweep and
  kept (as a Dask cluster is), so start-ups are reported apart, not in the table.
* overhead per run = (wall time * workers - the runs' own time) / the runs' own time, with
  each run timed on its worker: the worker-time a run costs beyond its compute (transfer,
  scheduling, idle tails). It does not depend on how fast the machine is, but other
  processes competing for the cores raise it.
"""

from __future__ import annotations

import argparse
import os
import time

import tendonsheath as ts
from _common import write_results
from tendonsheath.bench.scenarios.do import robustness_run
from tendonsheath.sweep import MonteCarlo, Relative, Seed, Uniform, make_plan

RUN = robustness_run
RUN_NAME = "do2015 at reduced length (bench.scenarios.do:robustness_run)"


def design() -> dict:
    return {
        "friction": Relative(0.1, 0.3),
        "pretension": Relative(20.0, 0.3),
        "route_angle": Uniform(0.5 * 3.14159, 1.5 * 3.14159),
        "route_seed": Seed(),
        "route_pieces": 3,
    }


def timed(engine, spec, runs, **kw):
    start = time.perf_counter()
    res = ts.sweep(RUN, spec, n=runs, seed=1, engine=engine, progress=False, **kw)
    return time.perf_counter() - start, res


def row(name, workers, wall, res, runs, per_run, **extra):
    e = res.engine
    return {
        "engine": name,
        "workers": workers,
        "wall_s": wall,
        "runs_per_second": runs / wall,
        "mean_run_s": e["compute_seconds"] / runs,
        "overhead_per_run": e.get("overhead_per_run", float("nan")),
        "speedup_vs_one_run_at_a_time": per_run * runs / wall,
        "batches": e["batches"],
        **extra,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=200)
    args = ap.parse_args()
    spec = design()
    cores = os.cpu_count() or 1
    load = os.getloadavg()[0]
    print(f"run: {RUN_NAME}")
    print(f"{args.runs} runs, {cores} cores, "
          f"load average before: {load:.2f}")  # fmt: skip

    import pandas  # noqa: F401 - imported once up front, not inside the first timed sweep

    # a run, timed directly in this process (no engine at all)
    params = make_plan(MonteCarlo(spec), 20, seed=1).runs
    RUN(params[0])
    start = time.perf_counter()
    for p in params:
        RUN(p)
    per_run = (time.perf_counter() - start) / len(params)

    rows = []
    wall, ref = timed("serial", spec, args.runs)
    rows.append(row("serial (this process)", 1, wall, ref, args.runs, per_run))
    for workers in (1, 2):
        # starts the pool; every worker calibrates its nominal model once (as a warm cluster)
        startup, _ = timed("local", spec, 8 * workers, workers=workers)
        wall, res = timed("local", spec, args.runs, workers=workers)
        assert res.table.equals(ref.table)
        rows.append(row("local pool", workers, wall, res, args.runs, per_run,
                        first_sweep_s=startup))  # fmt: skip

    from distributed import Client, LocalCluster

    start = time.perf_counter()
    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        Client(cluster) as client,
    ):
        client.wait_for_workers(2)
        cluster_start = time.perf_counter() - start
        timed(client, spec, 16)  # workers import and calibrate once (like a warm cluster)
        wall, res = timed(client, spec, args.runs)
        assert res.table.equals(ref.table)
        rows.append(row("dask LocalCluster", 2, wall, res, args.runs, per_run))

    print(f"\na run, called directly: {1e3 * per_run:.1f} ms")
    print(f"start-up (not in the table): Dask LocalCluster {cluster_start:.1f} s; " + ", ".join(
        f"local pool of {r['workers']} {r['first_sweep_s']:.2f} s"
        for r in rows if "first_sweep_s" in r
    ))  # fmt: skip
    print(f"{'engine':22s} {'workers':>7s} {'wall':>7s} {'runs/s':>7s} {'speedup':>8s} "
          f"{'run (on worker)':>16s} {'overhead/run':>13s}")  # fmt: skip
    for r in rows:
        print(
            f"{r['engine']:22s} {r['workers']:7d} {r['wall_s']:6.2f}s {r['runs_per_second']:7.1f} "
            f"{r['speedup_vs_one_run_at_a_time']:7.2f}x {1e3 * r['mean_run_s']:13.1f} ms "
            f"{100 * r['overhead_per_run']:12.1f}%"
        )
    dask2 = rows[-1]
    verdict = "within" if dask2["overhead_per_run"] < 0.10 else "ABOVE"
    print(f"Dask overhead per run: {100 * dask2['overhead_per_run']:.1f}% of a run "
          f"({verdict} the 10 % target)")  # fmt: skip
    print(f"load average after: {os.getloadavg()[0]:.2f} (other processes on the machine "
          "slow the runs down and hide the scaling)")  # fmt: skip
    path = write_results(
        "sweep",
        {
            "run": RUN_NAME,
            "runs": args.runs,
            "cores": cores,
            "load_average_before": load,
            "seconds_per_run_direct": per_run,
            "dask_cluster_start_seconds": cluster_start,
            "rows": rows,
        },
    )
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
