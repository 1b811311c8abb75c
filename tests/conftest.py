import numpy as np
import pytest


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


@pytest.fixture(scope="session")
def scenario_results():
    """The three built-in scenarios at reduced length, run once per test session."""
    from tendonsheath.bench.scenarios import SCENARIOS

    return {name: run(scale=0.25, seed=0) for name, run in SCENARIOS.items()}
