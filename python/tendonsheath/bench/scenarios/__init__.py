"""Built-in scenarios: each seed paper's experiment on the physics plant."""

from .common import ScenarioResult
from .do import do2015
from .lau import lau2015
from .sun import sun2015

SCENARIOS = {"do2015": do2015, "sun2015": sun2015, "lau2015": lau2015}

__all__ = ["SCENARIOS", "ScenarioResult", "do2015", "lau2015", "sun2015"]
