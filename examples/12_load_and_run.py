"""12: a compensator identified in Python, loaded from its JSON file and run in a 1 kHz loop.

    python examples/12_load_and_run.py [COMPENSATOR.json]

The Python twin of examples/cpp/12_load_and_run.cpp: the same file (by default
examples/cpp/data/inverse_feedforward.json, written by make_inverse_feedforward.py), the same
self-check. The compensator steps at 1 kHz against its own identified Backlash driven by the
commands; it tracks a 1 rad, 0.5 Hz sine to 2 % of its amplitude (measured: 0.16 %, the
smoothing's rounding at each reversal; without the compensator the error is the dead band,
~10 %). The C++ program prints the same worst error: both step the same real-time core.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import tendonsheath as ts

DEFAULT_FILE = Path(__file__).resolve().parent / "cpp" / "data" / "inverse_feedforward.json"


def main(path: Path) -> int:
    ff = ts.compensate.load(path)  # the file's compensator; a bad file says which key
    inverse = isinstance(ff, ts.compensate.InverseFeedforward)
    if not inverse or type(ff.model) is not ts.models.Backlash:
        print("the self-check runs an InverseFeedforward of a Backlash", file=sys.stderr)
        return 2
    plant = ts.models.Backlash(**ff.model.params)  # the identified model, driven by the commands
    dt, amplitude, worst = 1e-3, 1.0, 0.0
    for k in range(5000):  # 5 s at 1 kHz
        y_d = amplitude * math.sin(2 * math.pi * 0.5 * k * dt)
        y = plant.step(ff.step(y_d, 0.0 if k == 0 else dt))
        if k >= 1000:
            worst = max(worst, abs(y - y_d))
    print(f"InverseFeedforward from {path.name}: worst tracking error {worst:.4g} "
          f"(amplitude {amplitude:.3g})")  # fmt: skip
    return 0 if worst < 0.02 * amplitude else 1


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_FILE))
