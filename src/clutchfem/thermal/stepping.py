"""Time stepping of the heat model: Crank-Nicolson with a Rannacher start in every segment,
the energy tallies, and the steady state without friction.

Crank-Nicolson (second order, A-stable) with a fixed step, each slip event and each pause
being one :class:`Segment` of equal steps.  The load is piecewise constant in time and jumps
at segment ends, which sit on step boundaries.  A jump excites the stiff (fine-scale)
modes, which Crank-Nicolson does not damp (amplification -> -1): every segment therefore
starts with two backward-Euler half steps (Rannacher start).  Backward Euler with dt/2 has
the matrix 2 M/dt + A = 2 (M/dt + A/2), the Crank-Nicolson matrix: **one factorisation per
step size** (SPD, :func:`clutchfem.fe.factorize`), on the reduced operators P' M P, P' A P
of the cyclic map (:mod:`.assembly`).  Why fixed steps: ``docs/durability_theory.md``.

    CN:      (M/dt + A/2) a_{n+1} = (M/dt - A/2) a_n + f + Q
    BE(dt/2): (M/dt + A/2) a_{n+1/2} = (M/dt) a_n + (f + Q)/2

The energy tallies use the scheme's own quadrature in time (CN: trapezoid of the loss
rates; BE: end-point), so the discrete balance stored = input - losses holds to solver
round-off: int grad(1) = 0 makes conduction drop out of 1' (M dT/dt + A T), and the
all-ones field is cyclic, so the sector map keeps the identity.  Loss rate of a boundary
part x: int h (T - T_inf) = hsum_x . T - c_x (column sums of H_x and of its right side).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from ..fe import factorize, one_blas_thread
from .assembly import HeatModel

__all__ = ["Probe", "Run", "Segment", "integrate", "steady_state"]


@dataclass
class Segment:
    """One slip event (``heated``) or pause: ``steps`` equal steps over ``duration`` [s]."""

    duration: float
    steps: int
    heated: bool


@dataclass
class Probe:
    """A time series of the run: the maximum over ``nodes``, or ``weights @ T`` (a mean)."""

    name: str
    nodes: np.ndarray | None = None  # 'max' over these nodes
    weights: np.ndarray | None = None  # 'mean': weights @ T (full vector)


@dataclass
class Run:
    """What :func:`integrate` returns: probe series, the hottest node at every step, each
    node's maximum, the fields at segment ends, the energy tallies [J, model], timings."""

    times: np.ndarray
    probes: dict
    part_max: np.ndarray
    part_argmax: np.ndarray
    nodal_max: np.ndarray
    segment_end: list  # full fields at each segment end
    energy: dict
    final: np.ndarray
    solve_s: float
    factorisations: int
    #: (time [s], full field) at about ``frames`` evenly spaced steps and every segment end
    frames: list = None


def integrate(model: HeatModel, T0: np.ndarray, Q: np.ndarray, segments: list[Segment],
              probes: list[Probe], *, homogeneous: bool = False, frames: int = 0) -> Run:
    """Crank-Nicolson with two backward-Euler half steps at the start of every segment
    (module docstring).  ``homogeneous``: drop the ambient/crankshaft terms (the response to
    Q alone, for the FE side of the heat partition); ``frames``: keep the full field at the
    start, at about that many evenly spaced steps and at every segment end (the time series
    of the output)."""
    with one_blas_thread():
        return _integrate_loop(model, T0, Q, segments, probes, homogeneous, frames)


def _integrate_loop(model, T0, Q, segments, probes, homogeneous, frames=0) -> Run:
    t0 = time.perf_counter()
    P = model.P
    Pt = P.T.tocsr()
    Mr = (Pt @ model.M @ P).tocsc()
    Ar = (Pt @ model.A @ P).tocsc()
    f = np.zeros(model.N) if homogeneous else model.f
    fr, Qr = Pt @ f, Pt @ Q
    # loss-rate row sums: loss_x(T) = hsum_x . T - c_x  (int of h (T - T_inf) over the boundary part)
    loss = {}
    for name, (Hm, rhs) in model.H.items():
        loss[name] = (np.asarray(Hm.sum(axis=0)).ravel(), 0.0 if homogeneous else float(rhs.sum()))
    msum = np.asarray(model.M.sum(axis=0)).ravel()
    cache = {}

    def factor(dt):
        key = round(dt, 15)
        if key not in cache:
            cache[key] = (factorize((Mr / dt + 0.5 * Ar).tocsc()), (Mr / dt - 0.5 * Ar).tocsr(), Mr / dt)
        return cache[key]

    # reduced initial vector: T0 is cyclic (equal on paired nodes), so the mean over each
    # column's nodes is the independent value
    a = (Pt @ T0) / np.asarray(P.sum(axis=0)).ravel()
    T = P @ a
    nsteps = sum(s.steps for s in segments)
    times = np.zeros(nsteps + 1)
    series = {p.name: np.zeros(nsteps + 1) for p in probes}
    pmax = np.zeros(nsteps + 1)
    parg = np.zeros(nsteps + 1, dtype=np.int64)
    nodal_max = T.copy()

    def record(k, T):
        for p in probes:
            series[p.name][k] = T[p.nodes].max() if p.nodes is not None else p.weights @ T
        j = int(np.argmax(T))
        pmax[k], parg[k] = T[j], j

    record(0, T)
    every = max(1, math.ceil(nsteps / frames)) if frames else 0
    kept = [(0.0, T.copy())] if frames else []
    E = {"input_J": 0.0, "face_J": 0.0, "bore_J": 0.0, "edge_J": 0.0}
    stored0 = msum @ T

    def rate(T):
        return {n: hs @ T - c for n, (hs, c) in loss.items()}

    ends = []
    k = 0
    tnow = 0.0
    for seg in segments:
        dt = seg.duration / seg.steps
        F, B, Mdt = factor(dt)
        rhs = fr + (Qr if seg.heated else 0.0)
        qin = float(Q.sum()) if seg.heated else 0.0
        for i in range(seg.steps):
            if i == 0:  # two backward-Euler half steps (Rannacher start)
                for _ in range(2):
                    a = F.solve(Mdt @ a + 0.5 * rhs)
                    T = P @ a
                    r = rate(T)
                    for n in r:
                        E[f"{n}_J"] += 0.5 * dt * r[n]
            else:
                r0 = rate(T)
                a = F.solve(B @ a + rhs)
                T = P @ a
                r = rate(T)
                for n in r:
                    E[f"{n}_J"] += 0.5 * dt * (r0[n] + r[n])
            E["input_J"] += dt * qin
            tnow += dt
            k += 1
            times[k] = tnow
            record(k, T)
            np.maximum(nodal_max, T, out=nodal_max)
            if every and (k % every == 0 or i == seg.steps - 1):
                kept.append((tnow, T.copy()))
        ends.append(T.copy())
    E["stored_J"] = float(msum @ T - stored0)
    return Run(times=times, probes=series, part_max=pmax, part_argmax=parg, nodal_max=nodal_max,
                segment_end=ends, energy=E, final=T, solve_s=time.perf_counter() - t0,
                factorisations=len(cache), frames=kept)


def steady_state(model: HeatModel) -> np.ndarray | None:
    """Steady state without friction: A T = f (None if nothing removes heat)."""
    A = model.A
    if not any(m.nnz and abs(m).sum() > 0 for m, _ in model.H.values()):
        return None
    P = model.P
    Pt = P.T.tocsr()
    F = factorize((Pt @ A @ P).tocsc())
    return P @ F.solve(Pt @ model.f)
