"""Run time of the whole validation report (every validation module that exists, its figures
and the Markdown report), as `clutchfem validate --docs` writes it.  Budget: well under 60 s
on a 2-core machine (it used to be asserted in tests/test_validation_runner.py, where a loaded
machine made a timing a flaky test: speed is measured here, the test checks the report).

    PYTHONPATH=src python benchmarks/bench_validation.py [--repeat 3]

Prints the wall and CPU seconds of each run and exits 1 if the best wall time is over the
budget.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
import warnings
from pathlib import Path

os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

BUDGET_S = 60.0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    from clutchfem.validation import runner

    walls = []
    for i in range(args.repeat):
        with tempfile.TemporaryDirectory() as tmp:
            t0, c0 = time.perf_counter(), time.process_time()
            with warnings.catch_warnings():  # a missing module is the report's business, not the timing's
                warnings.simplefilter("ignore", runner.ValidationModuleWarning)
                md = runner.write_report(Path(tmp) / "out", Path(tmp) / "validation.md")
            wall, cpu = time.perf_counter() - t0, time.process_time() - c0
            size = md.stat().st_size
        walls.append(wall)
        print(f"run {i + 1}: {wall:.1f} s wall, {cpu:.1f} s CPU (this process), report {size} bytes")
    best = min(walls)
    print(f"best {best:.1f} s against a budget of {BUDGET_S:.0f} s: {'OK' if best < BUDGET_S else 'OVER'}")
    return 0 if best < BUDGET_S else 1


if __name__ == "__main__":
    sys.exit(main())
