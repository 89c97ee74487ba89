"""The clutch over its life (issue 38): the time of ``cf.life(concept4 default, starts=N)`` and
the error of its answers against the same run with half the wear step (the step control of
:func:`clutchfem.durability.integrate_wear`: ``max_step`` and ``rate_change`` both halved).

Printed for the run and the half-step run: the time, the wear states, the step limits, and
the answers at the end (engagement, slip, torque and contact arc at the rpm of maximum engine
torque, deepest worn depth); then the largest difference of each answer between the two runs
over the life (the coarse run's states against the fine run interpolated at the same
starts), and the largest state-to-state change of the contact arc after wear-in (the jitter
the step control removes).  ``--fraction`` sets the coarse run's step limits as a share of the defaults.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/bench_life.py [--starts 100000] [--fraction 0.25]
"""

from __future__ import annotations

import argparse
import os
import platform
import time
from datetime import datetime, timezone

import numpy as np

import clutchfem as cf
from clutchfem.lifetime.run import REBUILD_DEPTH

KEYS = (("engagement_rpm", "rpm", ".1f"), ("slip_rpm", "rpm", ".1f"), ("torque_at_max_engine_torque_Nm", "N m", ".4f"),
        ("contact_arc_deg", "deg", ".2f"), ("slip_energy_per_start_J", "J", ".3f"))


def run(design, starts, fraction, rebuild):
    """A life whose step limits are ``fraction`` times the defaults (max_step, rate_change)."""
    w0 = cf.WearParams()
    wear = cf.WearParams(max_step=fraction * w0.max_step, rate_change=fraction * w0.rate_change)
    t0 = time.perf_counter()
    L = cf.life(design, starts=starts, wear=wear, rebuild_depth=rebuild)
    return L, time.perf_counter() - t0


def jitter(L) -> float:
    """Largest departure of the contact arc at a state from the straight line through its two
    neighbours (its second difference: a smooth growth leaves ~0), after the first tenth of the
    life (wear-in done), in deg."""
    sel = L.starts >= 0.1 * L.starts[-1]
    n, a = L.starts[sel], L.contact_arc_deg[sel]
    if len(a) < 3:
        return 0.0
    mid = a[:-2] + (a[2:] - a[:-2]) * (n[1:-1] - n[:-2]) / (n[2:] - n[:-2])
    return float(np.max(np.abs(a[1:-1] - mid)))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--concept", default="concept4")
    ap.add_argument("--starts", type=float, default=100_000)
    ap.add_argument("--fraction", type=float, default=1.0, help="the coarse run's step limits as a share of the "
                    "defaults (max_step, rate_change)")
    ap.add_argument("--mesh-size", default=None, help="e.g. 3mm (default: the concept's default mesh)")
    ap.add_argument("--no-rebuild", action="store_true", help="keep the wear in the contact gaps (no re-mesh)")
    a = ap.parse_args()
    print(f"{datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC, {platform.node()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}, OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS')}, "
          f"fidelity {os.environ.get('CLUTCHFEM_FIDELITY', 'best')}")
    ms = cf.MeshSettings(size=a.mesh_size) if a.mesh_size else None
    t0 = time.perf_counter()
    d = cf.Design.from_concept(a.concept, mesh=ms)
    d.case()
    print(f"design built (mesh, factorisation): {time.perf_counter() - t0:.1f} s")
    rebuild = None if a.no_rebuild else REBUILD_DEPTH
    runs = {}
    for f in (a.fraction, 0.5 * a.fraction):
        L, sec = run(d, a.starts, f, rebuild)
        runs[f] = L
        lim = L.wear_steps["step_limit_m"]
        print(f"\nstep limits x {f:g} (max_step {f * cf.WearParams().max_step * 1e6:g} um, rate_change "
              f"{f * cf.WearParams().rate_change:g}): {sec:.1f} s, {L.wear_steps['states']} states, step limit "
              f"{1e6 * lim['min']:.3f}..{1e6 * lim['max']:.3f} um, rebuilds at {L.rebuilds_at_starts}, "
              f"energy balance {L.energy_balance:.1e}")
        for k, u, fmt in KEYS:
            print(f"  {k:34s} new {getattr(L, k)[0]:{fmt}} {u}, at {L.starts[-1]:.0f} starts "
                  f"{getattr(L, k)[-1]:{fmt}} {u}")
        print(f"  deepest worn depth {1e6 * L.worn_profile_m[-1].max():.3f} um, drum {1e6 * L.drum_worn_m[-1]:.3f} um")
        print(f"  first misses: {L.first_miss}")
        print(f"  contact-arc jitter after wear-in (largest departure from its neighbours' line): {jitter(L):.3f} deg")
    c, f = runs[a.fraction], runs[0.5 * a.fraction]
    print(f"\nerror of the run with step limits x {a.fraction:g} against x {0.5 * a.fraction:g} (largest over its states):")
    for k, u, fmt in KEYS:
        yc, yf = getattr(c, k), np.interp(c.starts, f.starts, getattr(f, k))
        ok = np.isfinite(yc) & np.isfinite(yf)
        e = float(np.max(np.abs(yc[ok] - yf[ok]), initial=0.0))
        e_end = float(abs(yc[-1] - getattr(f, k)[-1]))
        print(f"  {k:34s} {e:{fmt}} {u} (at the end {e_end:{fmt}} {u})")
    wc = c.worn_profile_m[-1]
    wf = f.worn_profile_m[-1]
    print(f"  worn profile at the end: {1e6 * np.max(np.abs(wc - wf)):.3f} um of {1e6 * wf.max():.3f} um")


if __name__ == "__main__":
    main()
