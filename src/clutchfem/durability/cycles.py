"""Load cycles of a clutch in service, built from solved FE states (issue 14): no new
factorisation, only linear combinations of contact states the design's load cases solve.

Three kinds of stress cycle act on a compliant one-piece clutch (points = the raw element
vertex stresses of the elastic model, :class:`clutchfem.fe.VertexStress`):

1. **Start-stop** (one per start of the saw): from rest (zero stress) to the farthest state
   the part reaches in that start and back.  Candidates: the state at the engine's maximum
   speed while the clutch holds the engine's torque there (free revving / cutting at top
   speed), and every running state (below) of a ripple class that occurs at least once per
   start.  Per point the one farthest from zero (von Mises) is taken: the largest rainflow
   cycle of each start spans rest to the extreme of that start's history.
   Count: ``FatigueLoads.start_stops`` (ASSUMED 5e4; issue 14: 1e4-1e5).

2. **Running revolutions** (one per crank revolution at the operating speed: a one-cylinder
   two-stroke fires once per revolution).  Over one revolution (crank angle theta, seed 000
   eqs 6, 10-12)

       w(theta) = w_o (1 + delta sin theta)                                   (speed ripple)
       M(theta) = J delta w_o^2 cos theta + M_o (1 - cos theta)   (inertia + cutting torque)

   the speed and the torque the clutch must carry vary together, a quarter turn apart;
   M < 0 when the drum and chain (inertia J) overrun the decelerating crank.  They are *one*
   cycle per revolution, not two: counted separately and summed by Miner, the combined
   excursion would be missed (the amplitude of the pair is larger than either alone).
   delta scatters from revolution to revolution (Normal law, seed 000: 0.032 +- 0.013 at
   8000 rpm; :class:`~clutchfem.clutch.ripple.RippleModel`): the revolutions are split into
   five classes by z = (delta - mean) / std: z <= 0, 0-1, 1-2, 2-3, > 3, each represented by
   its upper edge (z = 0, 1, 2, 3 and 4 for the open tail: conservative) and counted
   ``revolutions`` x its probability.  Count: ``FatigueLoads.revolutions`` (issue 14: ~1e7
   revolutions = 21 h at 8000 rpm; a professional saw's cutting life is longer: with the
   elementary Miner rule every class above the 1e6-cycle knee acts at its endurance limit,
   whatever its count, so the count matters for the rare classes only).

3. The torque fluctuation is inside 2.

**Holding state at load torque M** (the clutch holds: static friction carries M).  From the
frictionless state S_0(w) (mu = 0: the same speed, no tangential force) and the full-slip
state S_f(w) with its torque M_f(w) (the clutch's capacity),

       S(w, M) = S_0(w) + (M / M_f(w)) (S_f(w) - S_0(w)),      -M_r(w) <= M <= M_f(w),

the straight line through the two solved states.  Why: with the contact nodes fixed (the
active set of the slip state) the part is linear, so the normal force is N(T) = N_0 + c T
for a tangential force T; the slip state is the point T = mu N on that line.  The line is
exact for one contact node and for tangential forces distributed like the slip state's
(mu lam_i), which static friction need not do (it can shift the traction within the patch);
at the default designs the patch is 4-5 nodes (~1 mm) at the shoe tip, so the resultant
decides the flexure stress.  The same line gives the reverse slip torque (M < 0, the drum
driving the hub: friction reversed, a plus shoe becomes a minus shoe and vice versa):
T = -mu N, i.e.

       M_r = M_0 / (2 - M_0 / M_f),      M_0 = mu R_d N_0 n   (frictionless normal force),

checked against solved reversed-friction states (tests; measured at 8000 and 9072 rpm,
default meshes): the reverse capacity within 0.03-1.1 % (concepts 4, 1, 2); the stress
field on the line vs the solved one within 0.05-1.2 % of the peak von Mises farther than 2
mm from the contact surface (1.5-4.5 % beyond 1 mm, concept 2's in-shoe flexure being the
closest), up to ~12 % at the contact patch itself, where the contact node moves by one
node with the friction direction (a local contact stress, not a flexure stress).  Beyond
the capacity the clutch slips for that part of the revolution and carries M_f (or -M_r):
M is clipped (seed 000 eq 13).  Speeds between the solved ones
(w_o (1 -+ delta_max), w_o) are interpolated piecewise linearly in w^2 (exact for a field
linear in w^2, e.g. before engagement); capacities likewise.

**Amplitude and mean of a non-proportional cycle.**  The revolution's stress path is a
closed curve in (sxx, syy, sxy); per point the cycle is taken between the two samples of
the path (``samples`` per revolution, crank angles k 360/n, n a multiple of 4 so that the
speed extremes and theta = 0, 180 deg are among them) that are farthest apart in the von
Mises norm: the *longest chord* (amplitude = half its von Mises length, mean = its
midpoint).  For a proportional (straight) path it is the usual amplitude and mean; for the
ellipse of an unclipped revolution it is the major axis.  The path's states are linear
combinations sum_a c_a(theta) B_a of a few solved fields B_a, so the von Mises length of
every chord at every point is one small matrix product with the per-point Gram matrix
q(B_a, B_b) (no stress tensor per sample is formed).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from statistics import NormalDist
from typing import ClassVar

import numpy as np

from ..clutch import SEED_DRIVE_INERTIA
from ..core import ParameterError, ParamSet, param
from .fatigue import LoadCycle

__all__ = ["FatigueLoads", "DELTA_CLASSES", "SEED_DRIVE_INERTIA", "ripple_classes", "revolution_torque",
           "reverse_capacity", "vm_gram", "longest_chord", "farthest_state", "ServiceStates",
           "service_cycles", "CycleSet"]


#: ripple classes: (z_lo, z_hi, z represented); z = (delta - mean) / std
DELTA_CLASSES = ((-math.inf, 0.0, 0.0), (0.0, 1.0, 1.0), (1.0, 2.0, 2.0), (2.0, 3.0, 3.0), (3.0, math.inf, 4.0))


class FatigueLoads(ParamSet):
    """The service loads of the fatigue check (module docstring); ASSUMED values, sources
    in the descriptions.  ``None``: taken from the engine curve.

    Parameters
    ----------
    start_stops, revolutions : float
        Start-stop cycles (default 5e4) and loaded crank revolutions (default 1e7) in the
        clutch's life.
    operating_rpm, max_rpm : float or str, optional
        Cutting speed and the speed each start reaches [rpm] (default: the engine's rpm of
        maximum torque and its top speed).
    cutting_torque : float or str, optional
        Mean cutting torque [N m] (default: the engine's torque at the operating speed).
    drive_inertia : float or str
        Drum, sprockets and chain on the clutch axis [kg m^2].
    samples : int
        Crank-angle samples per revolution (a multiple of 4).

    Examples
    --------
    >>> import clutchfem as cf
    >>> f = cf.FatigueLoads(start_stops=1e4, operating_rpm="9000rpm")
    >>> f.operating_rpm, f.cutting_torque                   # None: from the engine curve
    (9000.0, None)
    >>> cf.FatigueLoads(samples=30)
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.ParameterError: fatigue loads: parameter 'samples' = 30 is not allowed: a multiple of 4 ...
    """

    context: ClassVar[str] = "fatigue loads"
    start_stops: float = param(5e4, "-", 1.0, 1e9, "start-stop cycles in the clutch's life (ASSUMED; issue 14: "
                               "1e4-1e5)", "n_ss")
    revolutions: float = param(1e7, "-", 1.0, 1e12, "crank revolutions under load in the clutch's life (issue "
                               "14: ~1e7; one running cycle per revolution)", "n_rev")
    operating_rpm: float | None = param(None, "rpm", 100.0, 1e5, "operating (cutting) speed (default: the "
                                        "engine's rpm of maximum torque, 8000 rpm for the built-in curve, where "
                                        "seed 000 measured the ripple)", "n_o")
    cutting_torque: float | None = param(None, "N m", 0.0, 1e3, "mean cutting torque M_o (default: the engine's "
                                         "full-throttle torque at the operating speed; seed 000: 3.20 N m at "
                                         "9072 rpm)", "M_o")
    drive_inertia: float = param(SEED_DRIVE_INERTIA, "kg m^2", 0.0, 1.0, "drum, sprockets and chain reduced to "
                                 "the clutch axis, J_b + m_p r_k^2 (seed 000: 2.078e-4 kg m^2)", "J")
    max_rpm: float | None = param(None, "rpm", 100.0, 1e5, "speed each start reaches (default: the engine "
                                  "curve's top speed: free revving at full throttle)", "n_max")
    samples: int = param(24, "-", 8, 720, "crank-angle samples per revolution (a multiple of 4)", "n_theta")

    def check(self) -> None:
        if self.samples % 4:
            self.fail("samples", "a multiple of 4 (so that the speed extremes and 0, 180 deg are sampled)")


# ---------------------------------------------------------------------------------------
# pure pieces (no FE)
# ---------------------------------------------------------------------------------------
def _cdf(z: float) -> float:
    """Standard normal distribution function (0 and 1 at -+inf)."""
    return 0.0 if z == -math.inf else 1.0 if z == math.inf else NormalDist().cdf(z)


def ripple_classes(ripple_model, rpm: float, revolutions: float) -> list[dict]:
    """The ripple classes at mean speed ``rpm``: per class its z range, the delta it is
    represented by (upper edge, clipped at 0) and its count (``revolutions`` x probability)."""
    mean = float(ripple_model.delta_mean(rpm))
    std = float(ripple_model.delta_std(rpm))
    out = []
    for lo, hi, z in DELTA_CLASSES:
        p = _cdf(hi) - _cdf(lo)
        out.append({"z_range": [lo, hi], "z": z, "delta": max(mean + z * std, 0.0), "probability": p,
                    "count": revolutions * p})
    return out


def class_name(c: dict) -> str:
    lo, hi = c["z_range"]
    if not math.isfinite(lo):
        span = "delta <= mean"
    elif not math.isfinite(hi):
        span = f"delta > mean + {lo:g} sd"
    else:
        span = f"delta mean + {lo:g}..{hi:g} sd"
    return f"running revolutions, {span} (delta {c['delta']:.3f})"


def revolution_torque(theta, delta: float, omega_o: float, cutting_torque: float, inertia: float):
    """Load torque [N m] over a revolution (seed 000 eqs 10-12): J delta w_o^2 cos theta +
    M_o (1 - cos theta)."""
    th = np.asarray(theta, dtype=float)
    return inertia * delta * omega_o ** 2 * np.cos(th) + cutting_torque * (1.0 - np.cos(th))


def reverse_capacity(m0: float, mf: float) -> float:
    """Reverse slip torque M_r [N m] on the line through the frictionless and the forward
    full-slip states (module docstring): M_0 / (2 - M_0 / M_f); M_0 = mu R_d N_0 n."""
    if mf <= 0.0 or m0 <= 0.0:
        return 0.0
    den = 2.0 - m0 / mf
    if den <= 0.0:  # the reverse direction self-locks on this line: no finite capacity
        return math.inf
    return m0 / den


def _q(x, y):
    """von Mises bilinear form: q(s, s) = vM(s)^2, for plane stress s = (sxx, syy, sxy) or 3-D
    Voigt s = (sxx, syy, szz, syz, sxz, sxy)."""
    if x.shape[0] == 6:
        return (x[0] * y[0] + x[1] * y[1] + x[2] * y[2]
                - 0.5 * (x[0] * y[1] + x[1] * y[0] + x[1] * y[2] + x[2] * y[1] + x[0] * y[2] + x[2] * y[0])
                + 3.0 * (x[3] * y[3] + x[4] * y[4] + x[5] * y[5]))
    return x[0] * y[0] - 0.5 * (x[0] * y[1] + x[1] * y[0]) + x[1] * y[1] + 3.0 * x[2] * y[2]


def vm_gram(B: np.ndarray) -> tuple[np.ndarray, list[tuple[int, int]]]:
    """Per-point Gram matrix of the fields B (k, c, npts) (c = 3 or 6 stress rows) in the von Mises form: rows
    q(B_a, B_b) for a <= b (k (k + 1) / 2, npts) and the (a, b) of each row."""
    k = B.shape[0]
    pairs = [(a, b) for a in range(k) for b in range(a, k)]
    return np.stack([_q(B[a], B[b]) for a, b in pairs]), pairs  # (rows, npts)


def _quad_rows(D: np.ndarray, pairs) -> np.ndarray:
    """Rows d_a d_b (x2 off the diagonal) matching :func:`vm_gram`'s rows, for each d in D (n, k)."""
    return np.stack([D[:, a] * D[:, b] * (1.0 if a == b else 2.0) for a, b in pairs], axis=1)


def longest_chord(B: np.ndarray, C: np.ndarray, base: np.ndarray | None = None, gram=None):
    """Per point the two samples of the path sum_a C[s, a] B_a (+ ``base``) farthest apart
    in von Mises: (state_a, state_b) (3, npts) each and the sample indices (i, j) per point.
    B (k, 3, npts) fields, C (n, k) coefficients of the n samples; ``gram``: B's
    :func:`vm_gram` if already computed.  The search runs in single precision (it only
    picks the pair), the states are formed in double."""
    n = C.shape[0]
    G, pairs = gram if gram is not None else vm_gram(B)
    i, j = np.triu_indices(n, 1)
    R = _quad_rows(C[i] - C[j], pairs)
    L = G.T.astype(np.float32) @ R.T.astype(np.float32)  # (npts, npairs): vM^2 of every chord
    best = np.argmax(L, axis=1)
    ia, ib = i[best], j[best]
    Sa = np.einsum("pa,aqp->qp", C[ia], B)
    Sb = np.einsum("pa,aqp->qp", C[ib], B)
    if base is not None:
        Sa = Sa + base
        Sb = Sb + base
    return Sa, Sb, ia, ib


def farthest_state(B: np.ndarray, C: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per point the sample of sum_a C[s, a] B_a with the largest von Mises: (state (3, npts),
    sample index per point)."""
    G, pairs = vm_gram(B)
    V = G.T @ _quad_rows(C, pairs).T
    best = np.argmax(V, axis=1)
    return np.einsum("pa,aqp->qp", C[best], B), best


# ---------------------------------------------------------------------------------------
# from solved states to cycles
# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ServiceStates:
    """Solved stress fields (3, npts) [Pa] and torques [N m] the cycles are built from.

    ``omegas`` (3,): w_o (1 - d), w_o, w_o (1 + d) [rad/s]; ``S0`` (3, 3, npts): frictionless
    states at them; ``Sf_o``: the forward full-slip state at w_o; ``Mf`` (3,), ``M0`` (3,):
    capacity and mu R_d N_0 n at the three speeds; ``S0_max``, ``Sf_max``, ``Mf_max``,
    ``M0_max``: the same at the engine's maximum speed ``omega_max``."""

    omegas: np.ndarray
    S0: np.ndarray
    Sf_o: np.ndarray
    Mf: np.ndarray
    M0: np.ndarray
    omega_max: float
    S0_max: np.ndarray
    Sf_max: np.ndarray
    Mf_max: float
    M0_max: float


    def at(self, points) -> "ServiceStates":
        """The same states at the points ``points`` only (indices into the stress arrays)."""
        idx = np.asarray(points)
        return ServiceStates(omegas=self.omegas, S0=self.S0[..., idx], Sf_o=self.Sf_o[:, idx], Mf=self.Mf,
                             M0=self.M0, omega_max=self.omega_max, S0_max=self.S0_max[:, idx],
                             Sf_max=self.Sf_max[:, idx], Mf_max=self.Mf_max, M0_max=self.M0_max)


@dataclass(frozen=True)
class CycleSet:
    """The load cycles and what they were built from (JSON-ready ``info``).

    ``stress_bound`` (npts,) [Pa]: per point an upper bound of the von Mises stress of every
    state the cycles were sampled from; ``amplitude_bound``, ``mean_bound`` (cycles, npts)
    [Pa]: per cycle type (in the order of ``cycles``) and point, upper bounds of its
    equivalent amplitude and |mean|.  All by the triangle inequality (von Mises is a
    seminorm): a sample sum_a c_a B_a has vM <= sum_a |c_a| vM(B_a), the chord between two
    samples vM <= sum_a range(c_a) vM(B_a); start-stop (rest to its peak P) has amplitude =
    mean = vM(P)/2."""

    cycles: tuple[LoadCycle, ...]
    info: dict = field(default_factory=dict)
    stress_bound: np.ndarray | None = None
    amplitude_bound: np.ndarray | None = None
    mean_bound: np.ndarray | None = None


def _interp_w2(w2, nodes_w2, values):
    """Piecewise linear in w^2 through the three solved speeds (flat beyond them)."""
    return np.interp(w2, nodes_w2, values)


def service_cycles(st: ServiceStates, *, delta_classes: list[dict], cutting_torque: float, inertia: float,
                   max_speed_torque: float, start_stops: float, samples: int = 24, points=None,
                   bound_only: bool = False) -> CycleSet:
    """Start-stop and running-revolution cycles from the solved states (module docstring).

    ``points``: build them at these points only (indices into the stress arrays; each point's
    cycles depend on its own stresses only).  ``bound_only``: skip the cycles (their chord
    searches are most of the cost) and return the ``stress_bound`` of every point, for a
    screen of the points before the cycles are built."""
    if points is not None:
        st = st.at(points)
    w = np.asarray(st.omegas, dtype=float)
    if w.shape != (3,) or not (0 < w[0] < w[1] < w[2]):
        raise ParameterError("omegas", w, "three increasing speeds w_o (1 - d), w_o, w_o (1 + d) > 0 rad/s")
    w2n = w ** 2
    wo = float(w[1])
    S0m, S0o, S0p = st.S0
    # fields: B0 = S0(w_o), B1 = S0(w+) - S0(w_o), B2 = S0(w-) - S0(w_o), B3 = G (per N m)
    mf_o = float(st.Mf[1])
    G = (st.Sf_o - S0o) / mf_o if mf_o > 0 else np.zeros_like(S0o)
    B = np.stack([S0o, S0p - S0o, S0m - S0o, G])
    Mr = np.array([reverse_capacity(m0, mf) for m0, mf in zip(st.M0, st.Mf)])
    n = int(samples)
    theta = 2.0 * math.pi * np.arange(n) / n
    gram = vm_gram(B[1:])
    info_classes = []
    cycles = []
    running_rows = []  # coefficient rows of the running samples of classes seen at least once per start
    sampled = []  # coefficient rows of every running sample (for the stress bound)
    for c in delta_classes:
        d = float(c["delta"])
        w2 = (wo * (1.0 + d * np.sin(theta))) ** 2
        up = np.clip((w2 - w2n[1]) / (w2n[2] - w2n[1]), 0.0, None)
        dn = np.clip((w2n[1] - w2) / (w2n[1] - w2n[0]), 0.0, None)
        cap_f = _interp_w2(w2, w2n, st.Mf)
        cap_r = _interp_w2(w2, w2n, Mr)
        demand = revolution_torque(theta, d, wo, cutting_torque, inertia)
        carried = np.clip(demand, -cap_r, cap_f) if mf_o > 0 else np.zeros(n)
        slipping = (carried != demand) if mf_o > 0 else np.ones(n, dtype=bool)
        C = np.column_stack([np.ones(n), up, dn, carried])
        name = class_name(c)
        sampled.append(C)
        if not bound_only:
            Sa, Sb, ia, ib = longest_chord(B[1:], C[:, 1:], base=B[0], gram=gram)
            cycles.append(LoadCycle(name, Sa, Sb, max(float(c["count"]), 1.0)))
        if c["count"] >= start_stops:
            running_rows.append(C)
        info_classes.append({"name": name, "z_range": c["z_range"], "delta": d, "probability": c["probability"],
                             "count": float(c["count"]), "speed_rpm": [wo * (1 - d) * 30 / math.pi,
                                                                      wo * (1 + d) * 30 / math.pi],
                             "demand_torque_Nm": [float(demand.min()), float(demand.max())],
                             "carried_torque_Nm": [float(carried.min()), float(carried.max())],
                             "slipping_fraction_of_revolution": float(slipping.mean()) if mf_o > 0 else None})
    # start-stop: rest -> farthest state of the start (max-speed state or a running state)
    m_hi = min(max_speed_torque, st.Mf_max) if st.Mf_max > 0 else 0.0
    S_max = st.S0_max + (m_hi / st.Mf_max) * (st.Sf_max - st.S0_max) if st.Mf_max > 0 else st.S0_max
    Bs = np.concatenate([B, S_max[None]])
    rows = [np.r_[np.zeros(4), 1.0][None]]
    for C in running_rows:
        rows.append(np.column_stack([C, np.zeros(len(C))]))
    Cs = np.vstack(rows)
    # bounds by the triangle inequality (von Mises is a seminorm): a sample sum_a c_a B_a has
    # vM <= sum_a |c_a| vM(B_a), and a chord between two samples has vM <= sum_a range(c_a)
    # vM(B_a); no state is formed
    field_vm = np.stack([np.sqrt(np.maximum(_q(F, F), 0.0)) for F in Bs])  # (5, npts)
    amp_b, mean_b = [], []
    for C in sampled:
        Mc = np.abs(C).max(axis=0) @ field_vm[:4]
        amp_b.append(np.minimum(0.5 * ((C[:, 1:].max(axis=0) - C[:, 1:].min(axis=0)) @ field_vm[1:4]), Mc))
        mean_b.append(Mc)
    in_start = [Mc for Mc, c in zip(mean_b, delta_classes) if c["count"] >= start_stops]
    peak_b = np.max([field_vm[4]] + in_start, axis=0)  # start-stop: rest -> the farthest row of Cs
    bound = np.max([field_vm[4]] + mean_b, axis=0)
    amp_b, mean_b = np.vstack([0.5 * peak_b] + amp_b), np.vstack([0.5 * peak_b] + mean_b)
    if bound_only:
        return CycleSet((), {}, bound, amp_b, mean_b)
    peak, which = farthest_state(Bs, Cs)
    cycles.insert(0, LoadCycle("start-stop", np.zeros_like(peak), peak, start_stops))
    info = {
        "operating_rpm": wo * 30 / math.pi, "solved_rpm": list(w * 30 / math.pi),
        "cutting_torque_Nm": cutting_torque, "drive_inertia_kg_m2": inertia,
        "capacity_forward_Nm": list(st.Mf), "capacity_reverse_Nm": list(Mr),
        "frictionless_torque_mu_R_N0_Nm": list(st.M0),
        "max_speed_rpm": st.omega_max * 30 / math.pi, "max_speed_torque_Nm": float(max_speed_torque),
        "max_speed_carried_torque_Nm": float(m_hi), "capacity_at_max_speed_Nm": float(st.Mf_max),
        # (over the points the cycles were built at: analyze builds them at the screened points)
        "start_stop_peak_from_running_state_fraction": float(np.mean(which > 0)) if len(which) else math.nan,
        "points": int(len(which)),
        "start_stops": float(start_stops), "revolutions": float(sum(c["count"] for c in delta_classes)),
        "samples_per_revolution": n, "classes": info_classes,
        "engaged_at_operating_speed": bool(mf_o > 0),
    }
    return CycleSet(tuple(cycles), info, bound, amp_b, mean_b)
