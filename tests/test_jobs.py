"""tendonsheath._util.jobs: the demo's jobs on worker processes give what a serial run gives (the
values, the progress lines, the warnings), and a failing job is named."""

import os
import warnings

import pytest

from tendonsheath._util.jobs import Job, run_jobs, travels


class JobWarning(UserWarning):
    pass


def square(x, progress):
    progress(f"square {x}")
    warnings.warn(f"squared {x}", JobWarning, stacklevel=1)
    return {"value": x * x, "pid": os.getpid()}


def blas_threads(progress):
    import threadpoolctl

    return [i["num_threads"] for i in threadpoolctl.threadpool_info() if i["user_api"] == "blas"]


def fail(progress):
    progress("about to fail")
    raise ValueError("no good")


def _jobs(n=4):
    return [Job(f"square {x}", square, {"x": x}, cost=x) for x in range(n)]


def _run(jobs, workers):
    lines = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        done = run_jobs(jobs, workers, lines.append)
    said = [str(w.message) for w in caught if issubclass(w.category, JobWarning)]
    return done, lines, said


def test_workers_give_what_a_serial_run_gives():
    serial, serial_lines, serial_said = _run(_jobs(), 1)
    parallel, lines, said = _run(_jobs(), 2)
    assert {k: v["value"] for k, (v, _) in parallel.items()} == {
        k: v["value"] for k, (v, _) in serial.items()
    }
    assert {v["pid"] for v, _ in serial.values()} == {os.getpid()}
    assert os.getpid() not in {v["pid"] for v, _ in parallel.values()}
    # every line said once; the warnings raised here in the order of the jobs, as serially
    assert sorted(lines) == sorted(serial_lines) == [f"square {x}" for x in range(4)]
    assert said == serial_said == [f"squared {x}" for x in range(4)]
    assert all(seconds >= 0 for _, seconds in parallel.values())


def test_the_blas_runs_on_one_thread_here_and_in_the_workers():
    jobs = [Job("blas", blas_threads), *_jobs(2)]
    for workers in (1, 2):
        done, _, _ = _run(jobs, workers)
        assert set(done["blas"][0]) <= {1}


def test_a_failing_job_is_named_and_its_error_kept():
    with pytest.raises(ValueError, match="no good") as info:
        _run([Job("the failing one", fail), *_jobs(2)], 2)
    assert any("the failing one" in note for note in getattr(info.value, "__notes__", []))
    assert "fail" in str(info.value.__cause__)  # the worker's traceback


def test_a_job_that_cannot_travel_runs_here():
    here = []

    def local(progress):
        here.append(os.getpid())
        progress("local")
        return "done"

    assert not travels(local) and travels(square)
    done, lines, _ = _run([Job("local", local), *_jobs(2)], 2)
    assert done["local"][0] == "done" and here == [os.getpid()]
    assert "local" in lines


def _numbers(path):
    """metrics.json less what is a clock reading (the time of writing, seconds taken)."""
    import json

    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if k != "generated" and "seconds" not in k}
        if isinstance(x, list):
            return [strip(v) for v in x]
        return x

    return strip(json.loads(path.read_text()))


def test_the_demo_on_two_workers_writes_what_it_writes_on_one(tmp_path):
    """do2015 in its parts (each servo on a worker, put together here) and the other jobs side
    by side: every figure of metrics.json equal, to the last bit, to the serial run's."""
    from tendonsheath.apps.demo import run_demo

    written = {}
    for workers in (1, 2):
        out = tmp_path / f"w{workers}"
        written[workers] = run_demo(
            out, scale=0.1, scenarios=["do2015"], robustness=False, workers=workers
        )
    assert _numbers(written[1]["metrics"]) == _numbers(written[2]["metrics"])
    assert [p.name for p in written[1]["figures"]] == [p.name for p in written[2]["figures"]]
