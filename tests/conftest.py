import signal

import numpy as np
import pytest

# A run started in the background of a shell without job control (or under nohup) has SIGINT
# ignored, and every command a test starts inherits that: the Ctrl-C tests' commands (the
# CLI, the ROS 2 nodes) would never see their Ctrl-C. A handled SIGINT is reset at exec.
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


@pytest.fixture(scope="session")
def scenario_results():
    """The three built-in scenarios at reduced length, run once per test session."""
    from tendonsheath.bench.scenarios import SCENARIOS

    return {name: run(scale=0.25, seed=0) for name, run in SCENARIOS.items()}


def pytest_collection_modifyitems(items):
    """Under pytest-xdist (``make test``: ``-n auto --dist loadgroup``) a file's tests share a
    worker, so a module's fixtures are built once, and every test of the session's scenario
    results shares one worker, so the scenarios run once."""
    for item in items:
        uses_scenarios = "scenario_results" in getattr(item, "fixturenames", ())
        group = "scenarios" if uses_scenarios else item.nodeid.split("::")[0]
        item.add_marker(pytest.mark.xdist_group(group))
