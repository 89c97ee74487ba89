"""Numerical stress test (issue 12): every case of :mod:`support.solver_edges` (tests/support) with its
outcome (answer or refusal), engagement speed, largest equilibrium residual and torque-balance
error, condition estimate, the check against its reference and the message of a refusal.
Prints the Markdown table kept in BENCHMARKS.md.

    .venv/bin/python benchmarks/bench_stress.py
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

# the solver edge cases and verification shapes live with the tests (tests/support), not in the library
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import platform
import time

from support import solver_edges as S

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")


def main() -> None:
    t0 = time.perf_counter()
    out = S.all_cases()
    print(f"machine: {platform.machine()}, {platform.python_version()}; {len(out)} cases in "
          f"{time.perf_counter() - t0:.1f} s\n")
    print("| " + " | ".join(S.HEADERS) + " |")
    print("|" + "---|" * len(S.HEADERS))
    for o in out:
        row = list(o.row())
        extra = {k: v for k, v in o.extra.items() if k != "result"}
        if extra:
            row[-1] = (row[-1] + " " if row[-1] else "") + ", ".join(
                f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in extra.items())
        print("| " + " | ".join(str(x).replace("|", "/") for x in row) + " |")


if __name__ == "__main__":
    main()
