"""Torque vs engine speed of concepts 1 and 4 and today's spring clutch against an engine
curve (the thesis's figure 25), through the Python API.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python examples/torque_speed_plot.py [ENGINE.csv] [--out DIR]

Without a CSV the built-in 56.5 cc saw curve is used: its SHAPE IS ASSUMED (only 3.40 N m at
8000 rpm and 3.20 N m at 9072 rpm come from the sources).  The requirement factors a = 1.3,
b = 1.0 are ASSUMED defaults.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from clutchfem.clutch.analyze import Requirements, analyze
from clutchfem.clutch.engine import EngineCurve
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.materials import get_material
from clutchfem.mesh import mesh_concept
from clutchfem.report import comparison_plot, summary_rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("engine", nargs="?", type=Path, help="engine CSV (columns rpm, torque [N m])")
    ap.add_argument("--out", type=Path, default=Path("out/examples"))
    ap.add_argument("--a", type=float, default=1.3, help="engagement > a x idle (ASSUMED default)")
    ap.add_argument("--b", type=float, default=1.0, help="slip < b x rpm of max torque (ASSUMED default)")
    args = ap.parse_args(argv)
    engine = EngineCurve.from_csv(args.engine) if args.engine else EngineCurve.default()
    req = Requirements(a=args.a, b=args.b)
    analyses = {}
    for name in ("concept1", "concept4"):
        c = get_concept(name)
        p = c.params()
        cm = mesh_concept(c, p, MeshSettings())
        analyses[name] = an = analyze(cm, p, get_material("51CrV4"), engine=engine, requirements=req, design=name)
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
