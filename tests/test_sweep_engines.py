"""Sweep engines: serial, local pool and Dask give identical tables; a worker that dies loses
no run and counts none twice; bad input fails before any work."""

import os
import signal
import sys
import threading
import time

import cloudpickle
import numpy as np
import pandas as pd
import pytest

import tendonsheath as ts
from reference.stand_in_study import compensator_study, tracking_mse
from tendonsheath.sweep import Grid, Relative, Seed, SweepError, Uniform

distributed = pytest.importorskip("distributed")

# test-local run functions travel to the Dask workers by value
cloudpickle.register_pickle_by_value(sys.modules[__name__])

SPEC = {
    "friction": Relative(0.1, 0.3),
    "pretension": Relative(10.0, 0.3),
    "route_angle": Uniform(1.5, 4.5),
    "route_seed": Seed(),
    "route_pieces": 3,
    "elements": 12,
    "samples": 200,
}


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cl:
        yield cl


@pytest.fixture(scope="module")
def client(cluster):
    with distributed.Client(cluster) as c:
        c.wait_for_workers(2)
        yield c


@pytest.fixture(scope="module")
def reference():
    return ts.sweep(compensator_study, SPEC, n=24, seed=11, engine="serial")


def test_table_is_tidy(reference):
    t = reference.table
    assert list(t.columns[:5]) == ["run", "friction", "pretension", "route_angle", "route_seed"]
    assert reference.compensators == ["none", "curve_angle", "inverse_backlash"]
    assert len(t) == 24 * 3 and t["run"].tolist() == sorted(t["run"].tolist())
    assert set(reference.metrics) >= {"mse", "rmse", "max_abs"}
    assert np.isfinite(t[reference.metrics].to_numpy()).all()
    # the compensators are tuned for the nominal plant: the uncompensated sine is worse
    med = t.groupby("compensator")["mse"].median()
    assert med["curve_angle"] < med["none"] and med["inverse_backlash"] < med["none"]


def test_local_pool_equals_serial_for_any_worker_count(reference):
    for workers, batch in [(2, None), (1, 5)]:
        res = ts.sweep(
            compensator_study, SPEC, n=24, seed=11, engine="local", workers=workers,
            batch_size=batch,
        )  # fmt: skip
        pd.testing.assert_frame_equal(res.table, reference.table)
        assert res.engine["workers"] == workers


def test_dask_equals_local(reference, client, cluster):
    res = ts.sweep(compensator_study, SPEC, n=24, seed=11, engine=client, batch_size=5)
    pd.testing.assert_frame_equal(res.table, reference.table)
    assert res.engine["engine"] == "dask" and res.engine["batches"] == 5
    # by address: the sweep connects, runs and closes its own client
    res = ts.sweep(compensator_study, SPEC, n=24, seed=11, engine=cluster.scheduler_address)
    pd.testing.assert_frame_equal(res.table, reference.table)


class Slow:
    """A run that takes at least ``delay`` seconds (so a worker can die mid-sweep)."""

    parameters = compensator_study.parameters

    def __init__(self, delay):
        self.delay = delay

    def __call__(self, params):
        time.sleep(self.delay)
        return tracking_mse(params)


def test_a_worker_killed_mid_sweep_loses_no_run(client):
    spec = {k: v for k, v in SPEC.items() if k != "route_pieces"}
    expected = ts.sweep(tracking_mse, spec, n=40, seed=5, engine="serial").table
    pids = client.run(os.getpid)
    box = {}
    thread = threading.Thread(
        target=lambda: box.update(
            res=ts.sweep(Slow(0.08), spec, n=40, seed=5, engine=client, batch_size=2)
        )
    )
    thread.start()
    time.sleep(1.0)  # about half of the runs are done
    assert thread.is_alive(), "the sweep ended before the worker could be killed"
    victim = next(iter(pids.values()))
    os.kill(victim, signal.SIGKILL)
    thread.join(timeout=60)
    assert not thread.is_alive()
    res = box["res"]
    assert res.table["run"].tolist() == list(range(40))  # every run, exactly once
    pd.testing.assert_frame_equal(res.table, expected)
    assert victim not in client.run(os.getpid).values()
    client.wait_for_workers(2, timeout=30)  # the nanny restarts it for later tests


def test_unreachable_scheduler_fails_fast():
    start = time.perf_counter()
    with pytest.raises(ConnectionError, match="cannot reach the Dask scheduler"):
        ts.sweep(compensator_study, SPEC, n=4, seed=1, engine="tcp://127.0.0.1:1",
                 connect_timeout=1)  # fmt: skip
    assert time.perf_counter() - start < 10


CALLS = []


def counting_run(params):
    CALLS.append(params)
    return {"y": params["a"] ** 2}


counting_run.parameters = ("a", "b")


def test_bad_input_fails_before_any_run():
    CALLS.clear()
    with pytest.raises(ValueError, match=r"unknown parameter name\(s\) \['frction'\]"):
        ts.sweep(counting_run, {"frction": Uniform(0, 1)}, n=3, seed=1, engine="serial")
    with pytest.raises(ValueError, match="unknown parameter"):
        ts.sweep(lambda p: {"y": 1.0}, {"x": Uniform(0, 1)}, n=3, parameters=["a"])
    with pytest.raises(ValueError, match="empty range"):
        ts.sweep(counting_run, {"a": Uniform(1, 1)}, n=3, seed=1, engine="serial")
    with pytest.raises(ValueError, match="engine"):
        ts.sweep(counting_run, {"a": Uniform(0, 1)}, n=3, seed=1, engine="cluster")
    with pytest.raises(ValueError, match="workers"):
        ts.sweep(counting_run, {"a": Uniform(0, 1)}, n=3, seed=1, workers=0)
    assert CALLS == []


def flaky(params):
    if params["a"] > 0.5:
        raise RuntimeError("diverged")
    return {"y": params["a"]}


def test_a_failing_run_is_reported_or_recorded():
    with pytest.raises(SweepError, match=r"run \d+ with \{'a': .*RuntimeError: diverged"):
        ts.sweep(flaky, {"a": Uniform(0, 1)}, n=10, seed=2, engine="serial")
    res = ts.sweep(flaky, {"a": Uniform(0, 1)}, n=10, seed=2, engine="serial", on_error="record")
    bad = res.table["a"] > 0.5
    assert bad.any() and res.table.loc[bad, "y"].isna().all()
    assert res.table.loc[bad, "error"].str.contains("diverged").all()
    assert res.summary(bound=0.3).loc[0, "failed"] == bad.sum()


def test_grid_and_flat_metrics_and_summary():
    res = ts.sweep(counting_run, Grid({"a": [1.0, 2.0, 3.0], "b": 0}), engine="serial")
    assert res.table.to_dict("list") == {"run": [0, 1, 2], "a": [1.0, 2.0, 3.0], "y": [1, 4, 9]}
    s = res.summary(bound={"y": 4.0})
    assert s.loc[0, "within_bound"] == pytest.approx(2 / 3)
    assert s.loc[0, "median"] == 4.0


def die(params):
    os._exit(3)


def test_local_pool_is_kept_and_a_dead_worker_is_a_clear_error():
    res = ts.sweep(tracking_mse, {"friction": Relative(0.1, 0.3), "elements": 12}, n=4, seed=1,
                   workers=2)  # fmt: skip
    assert res.engine["compute_seconds"] > 0
    from tendonsheath.sweep import engines

    assert len(engines._POOLS) >= 1
    with pytest.raises(SweepError, match="local worker process died"):
        ts.sweep(die, {"a": Uniform(0, 1)}, n=2, seed=1, workers=2)
    again = ts.sweep(tracking_mse, {"friction": Relative(0.1, 0.3), "elements": 12}, n=4, seed=1,
                     workers=2)  # fmt: skip
    pd.testing.assert_frame_equal(again.table, res.table)


def test_lambdas_and_closures_travel_by_value(reference):
    scale = 3.0
    res = ts.sweep(lambda p: {"y": scale * p["a"]}, {"a": Uniform(0, 1)}, n=6, seed=2, workers=2)
    assert np.allclose(res.table["y"], 3 * res.table["a"])
    serial = ts.sweep(lambda p: {"y": scale * p["a"]}, {"a": Uniform(0, 1)}, n=6, seed=2,
                      engine="serial")  # fmt: skip
    pd.testing.assert_frame_equal(res.table, serial.table)


def thread_caps(params):
    """What a run sees of its worker's thread limits."""
    import threadpoolctl

    blas = [p["num_threads"] for p in threadpoolctl.threadpool_info() if p["user_api"] == "blas"]
    return {
        "blas": float(max(blas, default=0)),
        "ours": float(os.environ.get("TENDONSHEATH_NUM_THREADS", "0")),
    }


def test_local_workers_share_the_cores_out():
    # a fit inside a run uses the worker's share of the cores, in our batched calls and in
    # the BLAS: two workers each spinning the BLAS on every core made fits 4x slower
    cores = os.cpu_count() or 1
    res = ts.sweep(thread_caps, {"a": Uniform(0, 1)}, n=4, seed=1, workers=2)
    share = max(1, cores // 2)
    assert (res.table["ours"] == share).all()
    assert (res.table["blas"] <= share).all() and (res.table["blas"] >= 1).all()


def test_the_thread_setting_is_checked(monkeypatch):
    from tendonsheath.identify.settings import default_threads

    monkeypatch.setenv("TENDONSHEATH_NUM_THREADS", "3")
    assert default_threads() == 3
    monkeypatch.delenv("TENDONSHEATH_NUM_THREADS")
    assert default_threads() == 0
    for bad in ("0", "two", "-1"):
        monkeypatch.setenv("TENDONSHEATH_NUM_THREADS", bad)
        with pytest.raises(ValueError, match="TENDONSHEATH_NUM_THREADS must be a positive"):
            default_threads()
