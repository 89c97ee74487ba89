"""Elastic drum: a ring of given wall thickness, width and material, held or spinning,
condensed to the contact nodes' angles for the contact LCP.

What the contact problem needs
------------------------------
The rigid drum gives the LCP  w = q + G lam  (w the gaps, q = g0 - B u_free(w)).  An elastic
drum's inner wall moves out by  u_d(w) + C_d lam  at the contact nodes (its own centrifugal
expansion when it spins, and its compliance under the shoe forces), which opens the gaps:

    w = (q + u_d(w)) + (G + C_d) lam,    C_d = C_rr + s mu C_rt,

C_rr[i, j] the radial displacement of the drum at node i's angle per unit outward force at
node j's, C_rt[i, j] per unit tangential force along +e_theta (the friction force on the drum
is +s mu lam_j t_j: the hub turns in sense s, the held drum is dragged along).  For a
one-sector model of n identical shoes the loads repeat every 2 pi / n, and C_d is the cyclic
sum over the n copies.  C_d is symmetric positive semi-definite (C_rr), so G + C_d keeps
the P-matrix property the LCP solver relies on for moderate mu.

Ring model (curved Timoshenko beam, the default)
------------------------------------------------
Centroid radius R = R_d + t/2 (R_d the inner radius, t the wall thickness), width b, A = b t,
I = b t^3 / 12, shear area kappa A (Cowper: kappa = 10 (1 + nu) / (12 + 11 nu)).  Radial
displacement w (outward), tangential v, section rotation psi; per harmonic k >= 2 with
w = W cos k phi, v = V sin k phi, psi = Psi sin k phi the strains are

    e = (k V + W) / R,   kappa_b = k Psi / R,   gamma = Psi - (k W + V) / R,

and the energy (pi R / 2)(EA e^2 + EI kappa_b^2 + G kappa A gamma^2) against the work
pi R (Q W + T V + m Psi) of line loads Q cos k phi (radial), T sin k phi (tangential) and the
line moment m sin k phi gives a 3 x 3 system per k.  A tangential force on the inner surface
acts t/2 inside the centroid: it carries the moment m = -(t/2) T.  k = 0: uniform expansion,
taken from the exact thick cylinder under internal pressure (Lame, plane stress:
u(R_d) = p R_d / E ((R_d^2 + R_o^2) / (R_o^2 - R_d^2) + nu), p = Q R / (R_d b); the ring's
W = Q R^2 / EA is its thin limit, 1.8 % low at t / R_d = 0.06); the tangential k = 0 part is
the torque, reacted by the drum's bottom: no radial displacement.  k = 1 is a rigid translation of a free ring: the drum sits on its
bearing through its bottom disc, which holds its centre, so the k = 1 part is taken as
rigid (W_1 = 0).  Without shear (``shear=False``) the system is Euler-Bernoulli's, whose
inextensible limit is the textbook W = Q R^4 / (EI (k^2 - 1)^2).

A point force P at angle theta_j is the line load (P / (2 pi R)) (1 + 2 sum_k cos k phi)
(per unit centroid length), so the radial displacement at theta_i is

    C_rr(phi) = (n / (2 pi R)) (a_0 + 2 sum_{k in n N} s_k a_k cos k phi),   phi = theta_i - theta_j,
    C_rt(phi) = -(n / (2 pi R)) 2 sum_{k in n N} s_k b_k sin k phi,

with a_k = W/Q, b_k = W/T the harmonic compliances and s_k = sinc(k w_j / 2) the factor
that spreads node j's force over its tributary arc w_j (a ring under a true point load is
finite, but the smearing matches the FE nodes' meaning and makes the elasticity check
converge).  The series is summed to k_max = 400 n: its bending terms fall like k^-4, the
shear terms like k^-2 times the smearing factor's ~2 / (k w_j), so the truncation error is
~2e-6 of the diagonal for 0.6 deg arcs (measured in tests/test_drum.py).

Evaluated fast (:meth:`RingDrum.compliance`): the smearing is the mean over node j's arc,
so with the antiderivatives F_r(phi) = a_0 phi + 2 sum s a_k sin(k phi) / k and
F_t(phi) = 2 sum b_k cos(k phi) / k of the point-load kernels,

    C_rr(phi) = (n / (2 pi R)) (F_r(phi + w_j / 2) - F_r(phi - w_j / 2)) / w_j    (C_rt alike),

the same truncated series; the periodic parts are tabulated once on 2^15 points per period
2 pi / n by an inverse FFT and interpolated linearly (within 3e-6 of the largest entry of
the series, tests/test_drum.py), so an m x m operator costs O(m^2) instead of
O(m^2 k_max) cosines (the default design: ~5 ms instead of ~0.3 s).

Verified (tests/test_drum.py) harmonic by harmonic against a condensed scikit-fem annulus
(plane stress, P2, the same wall), :func:`~clutchfem.contact.annulus.annulus_harmonic_compliance`: the two agree to
<1 % for the default drum (t / R_d = 0.06) up to k ~ 15 and to ~1e-3 for a thin ring; the
ring misses the local through-thickness squeeze under the load (2-D elasticity's
logarithmic point-load term), which grows with k and is measured there.

Free expansion of a spinning drum: the free rotating annulus (plane stress Lame,
R_d <= r <= R_d + t), inner radius:
u_d = rho w^2 a / (8 E) ((1 - nu)(3 + nu)(a^2 + b^2) + (1 + nu)(3 + nu) b^2 - (1 - nu^2) a^2)
with a = R_d, b = R_d + t.

Assumptions: the drum is a ring of uniform section (the cup bottom's stiffening of the
rim near it is ignored: conservative, the real rim is stiffer), width ``width`` carries
the shoe loads (the contact is over the clutch's thickness), plane sections, coaxial with
the clutch (no run-out).
"""

from __future__ import annotations

import math
from typing import ClassVar, Literal

import numpy as np
from pydantic import field_validator

from ..core import Material, ParameterError, ParamSet, choice, get_material, param

__all__ = ["DrumWall", "RingDrum", "lame_free_ring_expansion"]


class DrumWall(ParamSet):
    """The drum's wall (inner radius comes from the design's drum radius)."""

    context: ClassVar[str] = "elastic drum"
    wall_thickness: float = param(2.0e-3, "m", 0.2e-3, 30e-3,
                                  "radial wall thickness of the drum (ASSUMED 2 mm: a pressed steel cup)", "t_d")
    width: float = param(14e-3, "m", 1e-3, 0.3,
                         "axial width of the drum wall (ASSUMED 14 mm: the cup depth of a 60 cc saw)", "b_d")
    material: Material = get_material("51CrV4")
    state: Literal["held", "spinning"] = choice(
        "held", "held: drum at rest (idle, chain brake, slip); spinning: turning with the clutch "
        "(its own centrifugal expansion opens the gap)")
    shear: bool = True

    @field_validator("material", mode="before")
    @classmethod
    def _material(cls, v):
        return get_material(v) if isinstance(v, str) else v


def lame_free_ring_expansion(material: Material, r_in: float, r_out: float, omega: float) -> float:
    """Radial displacement [m] of the inner surface of a free rotating annulus (plane stress)."""
    E, nu, rho = material.E, material.nu, material.rho
    a, b = r_in, r_out
    return rho * omega ** 2 * a / (8 * E) * ((1 - nu) * (3 + nu) * (a * a + b * b)
                                              + (1 + nu) * (3 + nu) * b * b - (1 - nu * nu) * a * a)


class RingDrum:
    """The ring model of a drum of inner radius ``radius`` (module docstring)."""

    KMAX_PER_N = 400

    def __init__(self, radius: float, wall: DrumWall | None = None):
        if not (isinstance(radius, (int, float)) and math.isfinite(radius) and radius > 0):
            raise ParameterError("drum_radius", radius, "a radius > 0 m")
        self.wall = wall or DrumWall()
        self.radius = float(radius)
        if self.wall.wall_thickness > 0.5 * self.radius:
            raise ParameterError("wall_thickness", self.wall.wall_thickness,
                                 f"<= half the drum radius ({0.5 * self.radius * 1e3:.3g} mm) for a ring model",
                                 "elastic drum")
        t, b = self.wall.wall_thickness, self.wall.width
        m = self.wall.material
        self.Rc = self.radius + t / 2
        self.EA = m.E * b * t
        self.EI = m.E * b * t ** 3 / 12
        nu = m.nu
        kappa = 10 * (1 + nu) / (12 + 11 * nu)
        self.GkA = (m.E / (2 * (1 + nu))) * kappa * b * t if self.wall.shear else math.inf
        # k = 0: exact thick cylinder (Lame, plane stress) under the internal pressure
        # p = Q_in / b, Q_in = Q R / R_d; thin limit R^2 / EA
        ai, ao = self.radius, self.radius + t
        self._a0 = (self.Rc / ai) / b * ai / m.E * ((ai * ai + ao * ao) / (ao * ao - ai * ai) + nu)

    # -- harmonics ----------------------------------------------------------------------
    def harmonics(self, k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(a_k, b_k): radial displacement of the ring per unit radial line load Q cos k phi
        and per unit tangential line load T sin k phi applied at the inner surface (with its
        moment -(t/2) T), loads per unit centroid length.  k = 0: (Lame, 0); k = 1: (0, 0)."""
        k = np.atleast_1d(np.asarray(k, dtype=float))
        R, EA, EI, GkA = self.Rc, self.EA, self.EI, self.GkA
        t = self.wall.wall_thickness
        a = np.zeros(len(k))
        bk = np.zeros(len(k))
        a[k == 0] = self._a0
        sel = k >= 2  # k = 1: rigid (bearing), 0 handled above
        kk = k[sel]
        if not len(kk):
            return a, bk
        z = np.zeros_like(kk)
        if math.isinf(GkA):  # Euler-Bernoulli: Psi = (k W + V) / R eliminated
            e = np.stack([np.full_like(kk, 1 / R), kk / R])  # (2, K)
            kb = np.stack([kk * kk / R ** 2, kk / R ** 2])
            Km = EA * np.einsum("iK,jK->Kij", e, e) + EI * np.einsum("iK,jK->Kij", kb, kb)
            # the moment m = -(t/2) T works on Psi = (k W + V)/R: load (-(t/2) k/R, 1 - (t/2)/R)
            rhs = np.stack([np.stack([np.ones_like(kk), z], -1),
                            np.stack([-(t / 2) * kk / R, np.full_like(kk, 1.0 - (t / 2) / R)], -1)], -1)
        else:
            e = np.stack([np.full_like(kk, 1 / R), kk / R, z])
            kb = np.stack([z, z, kk / R])
            g = np.stack([-kk / R, np.full_like(kk, -1 / R), np.ones_like(kk)])
            Km = (EA * np.einsum("iK,jK->Kij", e, e) + EI * np.einsum("iK,jK->Kij", kb, kb)
                  + GkA * np.einsum("iK,jK->Kij", g, g))
            rhs = np.stack([np.stack([np.ones_like(kk), z, z], -1),
                            np.stack([z, np.ones_like(kk), np.full_like(kk, -t / 2)], -1)], -1)
        sol = np.linalg.solve(Km, rhs)  # (K, dof, 2 load cases)
        a[sel], bk[sel] = sol[:, 0, 0], sol[:, 0, 1]
        return a, bk

    # -- condensed compliance -------------------------------------------------------------
    def compliance(self, angles: np.ndarray, n: int = 1, arc: np.ndarray | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
        """(C_rr, C_rt) [m/N], m x m, at the polar ``angles`` [rad] for the n-fold cyclic load
        pattern (n = number of identical sectors; 1: the loads of all shoes are listed);
        ``arc`` [rad]: each node's tributary arc (None: point loads).  See module docstring."""
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ParameterError("n", n, "an integer number of identical sectors >= 1")
        th = np.asarray(angles, dtype=float)
        w = np.zeros(len(th)) if arc is None else np.asarray(arc, dtype=float)
        if len(th) and np.all(w > 0):
            return self._compliance_tabulated(th, n, w)
        k = np.arange(n, self.KMAX_PER_N * n + 1, n, dtype=float)
        a, b = self.harmonics(k)
        a0 = self.harmonics([0.0])[0][0]
        phi = th[:, None] - th[None, :]
        s = np.sinc(np.outer(w, k) / (2 * math.pi))  # numpy sinc(x) = sin(pi x)/(pi x): (m, K)
        pref = n / (2 * math.pi * self.Rc)
        Crr = np.empty((len(th), len(th)))
        Crt = np.empty((len(th), len(th)))
        for j in range(len(th)):  # column j: force at node j (smeared over its arc)
            kp = np.outer(phi[:, j], k)
            Crr[:, j] = pref * (a0 + 2 * np.cos(kp) @ (s[j] * a))
            Crt[:, j] = -pref * 2 * (np.sin(kp) @ (s[j] * b))
        return Crr, Crt

    #: grid points per period 2 pi / n of the tabulated antiderivatives
    TABLE_POINTS = 1 << 15

    def _antiderivative_tables(self, n: int):
        """Periodic parts of F_r and F_t (module docstring) on TABLE_POINTS points of one
        period 2 pi / n (cached per n): (grid step [rad], P_r, P_t), without the a_0 phi
        term of F_r."""
        cache = self.__dict__.setdefault("_tables", {})
        if n not in cache:
            J = self.KMAX_PER_N
            k = np.arange(n, J * n + 1, n, dtype=float)
            a, b = self.harmonics(k)
            N = self.TABLE_POINTS
            # irfft(X)[m] = (1/N) (X_0 + 2 sum_j Re(X_j e^(2 pi i j m / N))): X_j = -i N c_j for
            # sum_j c_j sin(j psi), X_j = N c_j for cos (psi = n phi)
            Xr = np.zeros(N // 2 + 1, dtype=complex)
            Xt = np.zeros(N // 2 + 1, dtype=complex)
            Xr[1:J + 1] = -1j * N * (a / k)  # 2 sum a_k sin(k phi) / k (the factor 2 from irfft)
            Xt[1:J + 1] = N * (b / k)  # 2 sum b_k cos(k phi) / k
            cache[n] = (2 * math.pi / n / N, np.fft.irfft(Xr, N), np.fft.irfft(Xt, N))
        return cache[n]

    def _compliance_tabulated(self, th: np.ndarray, n: int, w: np.ndarray):
        """(C_rr, C_rt) from the tabulated antiderivatives (module docstring)."""
        step, Pr, Pt = self._antiderivative_tables(n)
        a0 = self.harmonics([0.0])[0][0]
        period = 2 * math.pi / n
        N = len(Pr)

        def table(P, x):
            u = np.mod(x, period) / step
            i = np.floor(u).astype(np.int64)
            f = u - i
            return P[i % N] * (1 - f) + P[(i + 1) % N] * f

        phi = th[:, None] - th[None, :]
        lo, hi = phi - 0.5 * w[None, :], phi + 0.5 * w[None, :]
        pref = n / (2 * math.pi * self.Rc)
        Crr = pref * (a0 * w[None, :] + table(Pr, hi) - table(Pr, lo)) / w[None, :]
        Crt = pref * (table(Pt, hi) - table(Pt, lo)) / w[None, :]  # -(2 sum b_k sin) smeared = +dF_t / w
        return Crr, Crt

    def free_expansion(self, omega: float) -> float:
        """Radial displacement [m] of the inner wall of the drum spinning at ``omega`` alone
        (0 when the drum is held)."""
        if self.wall.state == "held":
            return 0.0
        return lame_free_ring_expansion(self.wall.material, self.radius,
                                        self.radius + self.wall.wall_thickness, omega)

    def operator(self, nodes, friction: float, n: int) -> np.ndarray:
        """C_d = C_rr + (s mu) C_rt at the contact nodes (a ContactNodes) for an n-fold cyclic
        model; the tributary arc of node i is weight_i / |x_i| (its length over its radius)."""
        arc = np.asarray(nodes.weight) / np.hypot(*nodes.xy[:2])
        ang, inv = np.unique(np.round(nodes.angle, 12), return_inverse=True)
        # nodes at the same angle (3-D: several levels) share the ring's displacement; their
        # arcs are the same: spread over one arc
        arc_u = np.zeros(len(ang))
        np.maximum.at(arc_u, inv, arc)
        Crr, Crt = self.compliance(ang, n, arc_u)
        C = Crr if friction == 0.0 else Crr + friction * Crt
        return C[np.ix_(inv, inv)]
