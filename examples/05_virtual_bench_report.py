"""05: run one of the built-in seed experiments and write its report.

python examples/05_virtual_bench_report.py --scenario lau2015 --out example-out
"""

from __future__ import annotations

import argparse
from pathlib import Path

from tendonsheath.bench.scenarios import SCENARIOS
from tendonsheath.report.build import write


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", choices=sorted(SCENARIOS), default="lau2015")
    parser.add_argument("--scale", type=float, default=0.5, help="run length factor")
    parser.add_argument("--out", type=Path, default=Path("example-out"))
    args = parser.parse_args()
    result = SCENARIOS[args.scenario](scale=args.scale)
    for row in result.table:
        print(row)
    written = write(args.out, [result], None, title=result.title)
    print(f"wrote {written['report']} and {written['metrics']}")


if __name__ == "__main__":
    main()
