"""Built-in scenarios: each seed paper's experiment on the physics plant."""

from .common import ScenarioResult
from .do2015 import do2015
from .lau2015 import lau2015
from .sun2015 import sun2015

SCENARIOS = {"do2015": do2015, "sun2015": sun2015, "lau2015": lau2015}

__all__ = ["SCENARIOS", "ScenarioResult", "do2015", "lau2015", "sun2015"]
