"""read_log on ROS bags: CPU and wall time per message. A bag of each kind (ROS 1, ROS 2
sqlite3, ROS 2 MCAP) holds a JointState topic at 1 kHz (the input) and a PointStamped topic at
100 Hz (the output) for SECONDS; read_log reads both and aligns them. The bags are written with
the tests' writer (tests/_rosbag_helpers.py), so what is timed is what is tested.

    .venv/bin/python benchmarks/read_rosbag.py [--seconds 60]

Printed and written to benchmarks/results/read_rosbag.json.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from _common import write_results

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
from _rosbag_helpers import EPOCH_NS, KINDS, joint_state, point_stamped, write_bag  # noqa: E402

import tendonsheath as ts  # noqa: E402


def _bag(folder: Path, kind: str, seconds: float) -> tuple[Path, int]:
    in_ns = EPOCH_NS + np.arange(int(seconds * 1000), dtype=np.int64) * 1_000_000
    out_ns = EPOCH_NS + 500_000 + np.arange(int(seconds * 100), dtype=np.int64) * 10_000_000
    topics = {
        "/motor/joint_states": [
            (s, joint_state(kind, s, [np.sin(k / 100), 0.0])) for k, s in enumerate(in_ns)
        ],
        "/tip/point": [(s, point_stamped(kind, s, 0.1)) for s in out_ns],
    }
    return write_bag(folder / kind, kind, topics), in_ns.size + out_ns.size


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0)
    args = parser.parse_args()
    out = {"seconds": args.seconds, "kinds": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for kind in KINDS:
            path, messages = _bag(Path(tmp), kind, args.seconds)
            w, c = time.perf_counter(), time.process_time()
            log = ts.io.read_log(path, input="/motor/joint_states:position[0]",
                                 output="/tip/point:point.x")  # fmt: skip
            wall, cpu = time.perf_counter() - w, time.process_time() - c
            out["kinds"][kind] = {
                "messages": messages,
                "samples": len(log),
                "wall_s": wall,
                "cpu_s": cpu,
                "cpu_us_per_message": 1e6 * cpu / messages,
            }
            print(f"{kind:8s} {messages} messages -> {len(log)} samples: {wall:.2f} s wall, "
                  f"{cpu:.2f} s CPU ({1e6 * cpu / messages:.1f} us/message)")  # fmt: skip
    print(f"written to {write_results('read_rosbag', out)}")


if __name__ == "__main__":
    main()
