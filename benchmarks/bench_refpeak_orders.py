"""The peak-stress reference's through-thickness order (issue 20): concepts 4 and 1 at their
defaults refined at the peak as ``bench_accuracy.py --part refpeak`` does (the sequence
follows the order-6 peak), every level's raw vertex peak at 14 000 rpm with the thick plane
model at orders 4, 6 and 8 (2 mm ring drum, pre-stress); a solve the checks refuse (order 8
on the finest levels: condition estimate > 1e14) is printed as refused.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_refpeak_orders.py [concept ...]
"""

import sys

from accuracy_refpeak import peak_at_rpm
from bench_accuracy import RPM_S, WALL

from clutchfem.core import ClutchfemError
from clutchfem.fe import peak_stress_converged
from clutchfem.geometry import MeshSettings, get_concept

ORDERS = (4, 6, 8)


def main(names):
    for name in names:
        evs = {o: peak_at_rpm(name, {}, RPM_S, WALL, order=o) for o in ORDERS}

        def ev(cm, name=name, evs=evs):
            out = {}
            for o, e in evs.items():
                try:
                    out[o] = v, x = e(cm)
                    print(f"{name} {cm.n_elements} elements, order {o}: {v / 1e6:.2f} MPa at ({x[0] * 1e3:.2f}, "
                          f"{x[1] * 1e3:.2f}) mm", flush=True)
                except ClutchfemError as exc:
                    print(f"{name} {cm.n_elements} elements, order {o}: refused: {str(exc)[:100]}", flush=True)
            return out[6] if 6 in out else evs[6](cm)
        c = get_concept(name)
        peak_stress_converged(c, c.params(), ms=MeshSettings.preset("best"), evaluate=ev, tol=0.01)


if __name__ == "__main__":
    main(sys.argv[1:] or ["concept4", "concept1"])
