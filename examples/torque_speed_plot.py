"""Torque vs engine speed of concepts 1 and 4 and today's spring clutch against an engine
curve (the thesis's figure 25), through the Python API.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python examples/torque_speed_plot.py [ENGINE.csv] [--out DIR] [--mesh-size M]

With CLUTCHFEM_EXAMPLE_SMALL=1 (tests/test_examples.py) the mesh is coarse (4 mm) unless
--mesh-size is given: the same answers, roughly, in a second or two.

Without a CSV the built-in 56.5 cc saw curve is used: its SHAPE IS ASSUMED (only 3.40 N m at
8000 rpm and 3.20 N m at 9072 rpm come from the sources).  The requirement factors a = 1.3,
b = 1.0 are ASSUMED defaults.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

from clutchfem.analysis import Requirements, analyze
from clutchfem.clutch import EngineCurve
from clutchfem.geometry import MeshSettings
from clutchfem.loadcase import Design
from clutchfem.report import comparison_plot, summary_rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("engine", nargs="?", type=Path, help="engine CSV (columns rpm, torque [N m])")
    ap.add_argument("--out", type=Path, default=Path("out/examples"))
    ap.add_argument("--a", type=float, default=1.3, help="engagement > a x idle (ASSUMED default)")
    ap.add_argument("--b", type=float, default=1.0, help="slip < b x rpm of max torque (ASSUMED default)")
    ap.add_argument("--mesh-size", type=float, default=None, help="global element size [m] (default 1.2e-3)")
    args = ap.parse_args(argv)
    if args.mesh_size is None and os.environ.get("CLUTCHFEM_EXAMPLE_SMALL") == "1":
        args.mesh_size = 4e-3  # small run (examples/README.md)
    engine = EngineCurve.from_csv(args.engine) if args.engine else EngineCurve.default()
    req = Requirements(a=args.a, b=args.b)
    analyses = {}
    for name in ("concept1", "concept4"):
        ms = MeshSettings() if args.mesh_size is None else MeshSettings(size=args.mesh_size)
        analyses[name] = an = analyze(Design.from_concept(name, mesh=ms), engine=engine, requirements=req)
        print(f"\n{name}")
        for q, v in summary_rows(an):
            print(f"  {q:<75} {v}")
        for w in an.warnings:
            print(f"  WARNING: {w}")
    args.out.mkdir(parents=True, exist_ok=True)
    path = comparison_plot(analyses, engine, args.out / "torque_speed.png")
    print(f"\nwrote {path}")


if __name__ == "__main__":
    main()
