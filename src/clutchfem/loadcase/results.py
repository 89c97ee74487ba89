"""Results of a speed sweep: one frozen, self-contained object, and every table built from it.

A :class:`SweepResult` keeps what was solved (speeds, nodal contact forces, the displacement
of every state as a small reduced basis and coefficients) and the read-only parts needed to
post-process it (contact node geometry, the stress recovery operator, the FE basis for
``.vtu`` output).  It never points back at a solver: ``.vtu`` files and pressure tables are
written from its stored states, not by solving again.

Conventions of the tables (one meaning everywhere):

* forces, torque: the whole clutch (a one-sector model is scaled by n_shoes_total / 1);
* ``contact_arc_deg``: per shoe, the arc from the first to the last end of its contact, the
  ends found between the nodes from the gap and the pressure interpolated along the P2
  boundary (:mod:`clutchfem.contact.arc`), ``contact_arc_error_deg`` its error (0.4 node
  spacings per end, 0 where the contact reaches the end of the contact surface); the curve
  gives the mean over the modelled shoes;
* ``gaps``: every contact node's gap [m] at every state, g = g0 + u_drum - B u (+ C_d lam
  for an elastic drum);
* ``max_von_mises_Pa``: raw (unaveraged) vertex stresses, the peak over the part;
* angles: polar angles of the drum frame [deg];
* ``residual``: relative equilibrium residual of the state, ``torque_balance_error``: bore
  reaction moment against the applied moment (:mod:`clutchfem.loadcase.checks`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..contact import arc_error_deg, contact_ends
from ..core import InputError, clean, wrap_angle

#: speeds per block when stresses and displacements of many speeds are post-processed
#: (bounds the memory of a sweep over many speeds)
CHUNK = 64


@dataclass(frozen=True, eq=False)
class Fields:
    """Displacements of the solved states: ``basis @ coef`` (reduced) or explicit ``U``, and
    the read-only operators to post-process them."""

    basis: np.ndarray | None  # (ndofs, nb)
    coef: np.ndarray | None  # (nb, ns)
    U: np.ndarray | None  # (ndofs, ns) explicit (exact softening)
    stress: object  # clutchfem.fe.VertexStress
    fe_basis: object  # skfem Basis of the P2 vector field (dof layout, node positions)

    @property
    def n(self) -> int:
        return self.U.shape[1] if self.U is not None else self.coef.shape[1]

    def displacement(self, k: int) -> np.ndarray:
        """Full displacement vector [m] (all dofs) of state k."""
        return self.U[:, k] if self.U is not None else self.basis @ self.coef[:, k]

    def block(self, sl: slice) -> np.ndarray:
        return self.U[:, sl] if self.U is not None else self.basis @ self.coef[:, sl]

    def stresses(self, sl: slice) -> np.ndarray:
        """Vertex stresses (3, npts, len(sl)) of states ``sl``."""
        n = len(range(*sl.indices(self.n)))
        if self.U is not None or ("_bs" not in self.__dict__ and n < self.basis.shape[1]):
            # (fewer states than basis vectors: their own stresses cost less than the basis')
            s = self.stress(self.block(sl))
            return s.reshape(s.shape[0], -1, n)
        return self._basis_stress @ self.coef[:, sl]

    @property
    def _basis_stress(self) -> np.ndarray:
        if "_bs" not in self.__dict__:  # (components: 3 in 2-D, 6 in 3-D)
            s = self.stress(self.basis)
            object.__setattr__(self, "_bs", s.reshape(s.shape[0], -1, self.basis.shape[1]))
        return self.__dict__["_bs"]


@dataclass(frozen=True, eq=False)
class SweepResult:
    """What a speed sweep returns: frozen, self-contained (module docstring for the tables).

    Attributes
    ----------
    rpm, omega : ndarray
        The speeds [rpm], [rad/s].
    lam : ndarray
        Contact forces per speed and contact node [N] (model: one sector of a cyclic part).
    gaps : ndarray
        Gaps per speed and contact node [m].
    contact_modulus : float
        E* [Pa] of the part's surface (:func:`clutchfem.contact.contact_modulus`).
    engagement_rpm : float or None
        Engagement speed (None: never engages below the divergence speed).
    curve : pandas.DataFrame
        One row per speed: normal force [N], torque [N m], contact arc and its error [deg],
        peak von Mises [Pa], safety factor, displacement [m], checks (whole clutch).
    shoes : pandas.DataFrame
        Per shoe and speed.
    warnings : tuple of str

    Examples
    --------
    >>> import clutchfem as cf
    >>> r = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm")).sweep("8000")
    >>> sorted(c for c in r.curve.columns if c.startswith(("torque", "contact_arc")))
    ['contact_arc_deg', 'contact_arc_error_deg', 'torque_Nm', 'torque_balance_error']
    """

    rpm: np.ndarray
    omega: np.ndarray  # rad/s
    lam: np.ndarray  # (ns, m) nodal contact forces [N] of the model (sector or full)
    engagement_rpm: float | None
    first_touch: str | None
    first_touch_angle_deg: float | None
    divergence_rpm: float | None
    contact: object | None  # clutchfem.contact.DrumContact
    scale: float
    thickness: float
    softening: str
    curve: pd.DataFrame
    shoes: pd.DataFrame
    fields: Fields
    #: (ns, m) gap of every contact node at every state [m]
    gaps: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    #: E* of the part's surface [Pa] (the contact arc's ends: clutchfem.contact.arc)
    contact_modulus: float = float("nan")
    #: 1-norm condition estimate of the reduced stiffness (clutchfem.loadcase.checks)
    condition: float = float("nan")
    #: numerical warnings of the solve (model-applicability warnings: clutchfem.loadcase.model_warnings)
    warnings: list = field(default_factory=list)
    timings: dict = field(default_factory=dict)

    @property
    def mu(self) -> float:
        return 0.0 if self.contact is None else self.contact.mu

    def find(self, rpm: float) -> int | None:
        """Index of the sweep speed equal to ``rpm`` (within 1e-9 relative), None if that
        speed was not solved."""
        k = int(np.argmin(np.abs(self.rpm - rpm)))
        return None if abs(self.rpm[k] - rpm) > 1e-9 * max(1.0, abs(rpm)) else k

    def index(self, rpm: float) -> int:
        """Index of the sweep speed equal to ``rpm`` (within 1e-9 relative); refuses a speed
        that was not solved (no silent nearest-speed answer)."""
        k = self.find(rpm)
        if k is None:
            raise InputError(f"{rpm:g} rpm is not a speed of this sweep (solved: {_speeds(self.rpm)}); "
                             "sweep it first")
        return k

    def pressure(self, rpm: float) -> pd.DataFrame:
        """Contact pressure along the contact surface at sweep speed ``rpm``."""
        return pressure_table(self, self.index(rpm))

    def displacement(self, k: int) -> np.ndarray:
        return self.fields.displacement(k)

    @property
    def displacements(self) -> np.ndarray:
        """(ndofs, nspeeds) displacements of every state [m] (built on demand)."""
        return self.fields.block(slice(None))

    def contact_extent(self, shoe: int = 0) -> np.ndarray:
        """(nspeeds, 4) start and end polar angle [rad] of shoe ``shoe``'s contact and their
        errors [rad] (NaN where it does not touch): :func:`clutchfem.contact.contact_ends`."""
        return contact_extent(self.contact, self.lam, self.gaps, self.thickness, self.contact_modulus, shoe)

    def to_json(self) -> dict:
        cols = ["rpm", "normal_force_N", "torque_Nm", "contact_arc_deg", "contact_arc_error_deg",
                "max_von_mises_Pa", "max_displacement_m"]
        return {"engagement_rpm": self.engagement_rpm, "first_touch": self.first_touch,
                "divergence_rpm": self.divergence_rpm, "mu": self.mu, "softening": self.softening,
                "condition_estimate": self.condition,
                "max_residual": float(self.curve["residual"].max()) if "residual" in self.curve else None,
                "warnings": list(self.warnings), "curve": records(self.curve), "required_columns": cols}


def _speeds(rpm: np.ndarray) -> str:
    if len(rpm) <= 6:
        return ", ".join(f"{r:g}" for r in rpm) + " rpm"
    return f"{len(rpm)} speeds {rpm.min():g}..{rpm.max():g} rpm"


def records(df: pd.DataFrame) -> list[dict]:
    """DataFrame rows as JSON-safe dicts (NaN and +-inf become null: strict JSON)."""
    return clean(df.to_dict("records"))


# ---------------------------------------------------------------------------------------
# tables
# ---------------------------------------------------------------------------------------
def contact_extent(contact, lam: np.ndarray, gaps: np.ndarray, thickness: float, modulus: float,
                   shoe: int = 0) -> np.ndarray:
    """(nstates, 4) start and end polar angle [rad] of shoe ``shoe``'s contact and their errors
    [rad], NaN where it does not touch (:func:`clutchfem.contact.contact_ends`); ``lam`` and
    ``gaps`` (nstates, m): nodal forces [N] and gaps [m]."""
    lam = np.atleast_2d(lam)
    if contact is None:
        return np.full((lam.shape[0], 4), np.nan)
    return contact_ends(contact.nodes, lam, gaps, thickness, modulus, shoe)


def contact_arcs_deg(contact, lam: np.ndarray, gaps: np.ndarray, thickness: float,
                     modulus: float) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """Per shoe, (contact arc [deg], its error [deg]) at every state (0 where it does not touch)."""
    if contact is None:
        return {}
    out = {}
    for s_ in contact.nodes.shoes:
        ext = contact_extent(contact, lam, gaps, thickness, modulus, s_)
        out[s_] = (np.degrees(np.nan_to_num(ext[:, 1] - ext[:, 0])), arc_error_deg(ext))
    return out


def state_gaps(contact, omega: np.ndarray, lam: np.ndarray, U: np.ndarray) -> np.ndarray:
    """(nstates, m) gaps [m] of the contact nodes for displacements ``U`` (ndofs, nstates):
    g = g0 + u_drum(w) - B u (+ C_d lam: an elastic drum's wall pushed out by the forces)."""
    nd = contact.nodes
    g = nd.gap0[:, None] - nd.normal_displacement(U).reshape(nd.m, -1)
    g = g + np.array([contact.drum_gap(float(w)) for w in np.atleast_1d(omega)])[None, :]
    Cd = contact.drum_compliance
    if Cd is not None:
        g = g + Cd @ np.atleast_2d(lam).T
    return g.T


def curve_table(rpm, omega, lam, contact, scale: float, fields: Fields, stresses: bool,
                yield_strength: float, thickness: float, modulus: float) -> tuple[pd.DataFrame, np.ndarray]:
    """(the sweep curve: one row per speed, see module docstring for the conventions; the
    contact nodes' gaps (ns, m) [m])."""
    ns = len(rpm)
    R = 0.0 if contact is None else contact.drum_radius
    mu = 0.0 if contact is None else contact.mu
    nsum = lam.sum(axis=1) * scale if lam.size else np.zeros(ns)
    gaps = np.zeros((ns, 0 if contact is None else contact.nodes.m))
    b = fields.fe_basis
    # every node's x and y dof (2-D P2: vertices and facets; 3-D P2 tetrahedra: vertices and edges)
    xd, yd = (np.concatenate([d[c] for d in (b.nodal_dofs, b.facet_dofs, b.edge_dofs) if d.shape[0] > c])
              for c in (0, 1))
    umax = np.zeros(ns)
    vm_max = np.full(ns, np.nan)
    kmax = np.zeros(ns, dtype=np.int64)
    for a in range(0, ns, CHUNK):
        sl = slice(a, min(a + CHUNK, ns))
        U = fields.block(sl)
        umax[sl] = np.sqrt(U[xd] ** 2 + U[yd] ** 2).max(axis=0) if U.size else 0.0
        if contact is not None:
            gaps[sl] = state_gaps(contact, np.asarray(omega)[sl], lam[sl], U)
        if stresses:
            # the thick plane model reads its peaks with the finite-rotation (Cauchy, Green-
            # Lagrange) measure of the same displacement (clutchfem.fe.ThickStress)
            vm = fields.stress.von_mises(fields.stresses(sl))
            if getattr(fields.stress, "FINITE", False):
                vm_max[sl], kmax[sl] = fields.stress.finite_peak(U, vm)
            else:
                vm_max[sl] = vm.max(axis=0)
                kmax[sl] = vm.argmax(axis=0)
    arcs = contact_arcs_deg(contact, lam, gaps, thickness, modulus)
    arc = np.mean(np.vstack([a for a, _ in arcs.values()]), axis=0) if arcs else np.zeros(ns)
    arc_err = np.mean(np.vstack([e for _, e in arcs.values()]), axis=0) if arcs else np.zeros(ns)
    df = pd.DataFrame({"rpm": np.asarray(rpm, dtype=float), "omega_rad_s": np.asarray(omega, dtype=float),
                       "normal_force_N": nsum, "torque_Nm": mu * R * nsum, "contact_arc_deg": arc,
                       "contact_arc_error_deg": arc_err,
                       "contact_nodes": (lam > 0).sum(axis=1) if lam.size else np.zeros(ns, dtype=int),
                       "max_displacement_m": umax})
    if stresses and ns:
        pts = fields.stress.points
        df["max_von_mises_Pa"] = vm_max
        df["max_vm_x_m"] = pts[0, kmax]
        df["max_vm_y_m"] = pts[1, kmax]
        with np.errstate(divide="ignore", over="ignore"):
            df["safety_factor"] = np.where(vm_max > 0, yield_strength / np.maximum(vm_max, 1e-300), np.inf)
    else:
        df["max_von_mises_Pa"] = np.nan
        df["safety_factor"] = np.nan
    return df, gaps


def shoe_table(rpm, lam, contact, nominal_arcs, gaps, thickness: float, modulus: float) -> pd.DataFrame:
    """One row per (speed, modelled shoe): normal force, torque, contact extent and arc with
    its error, share of the nominal shoe arc."""
    if contact is None:
        return pd.DataFrame()
    nd = contact.nodes
    R, mu = contact.drum_radius, contact.mu
    frames = []
    for s_ in nd.shoes:
        sel = nd.shoe == s_
        N = lam[:, sel].sum(axis=1)
        ext = contact_extent(contact, lam, gaps, thickness, modulus, s_)
        span = np.degrees(np.nan_to_num(ext[:, 1] - ext[:, 0]))
        nominal = abs(math.degrees(nominal_arcs[s_][1] - nominal_arcs[s_][0])) if 0 <= s_ < len(nominal_arcs) \
            else math.nan
        frames.append(pd.DataFrame({"rpm": np.asarray(rpm, dtype=float), "shoe": int(s_), "normal_force_N": N,
                                    "torque_Nm": mu * R * N, "arc_start_deg": np.degrees(ext[:, 0]),
                                    "arc_end_deg": np.degrees(ext[:, 1]), "contact_arc_deg": span,
                                    "contact_arc_error_deg": arc_error_deg(ext),
                                    "arc_fraction": span / nominal if nominal else math.nan}))
    df = pd.concat(frames, ignore_index=True)
    return df.sort_values(["rpm", "shoe"], kind="stable").reset_index(drop=True)


def pressure_table(res: SweepResult, k: int) -> pd.DataFrame:
    """Contact pressure along the contact surface at state k, ordered by shoe and angle."""
    if res.contact is None:
        return pd.DataFrame()
    nd = res.contact.nodes
    lam = res.lam[k]
    p = res.contact.pressure(lam, res.thickness)
    order = nd.by_arc
    return pd.DataFrame({"shoe": nd.shoe[order], "angle_deg": np.degrees(nd.angle[order]),
                         "x_m": nd.xy[0, order], "y_m": nd.xy[1, order],
                         "force_N": lam[order], "pressure_Pa": p[order], "gap0_m": nd.gap0[order],
                         "gap_m": res.gaps[k, order]})


def first_touch(contact, node: int | None, nominal_arcs) -> tuple[str | None, float | None]:
    """('root' | 'middle' | 'tip' | 'unknown', polar angle [deg]) of the first contact node."""
    if node is None or contact is None:
        return None, None
    nd = contact.nodes
    ang = float(nd.angle[node])
    s_ = int(nd.shoe[node])
    if s_ < 0 or s_ >= len(nominal_arcs):
        return "unknown", math.degrees(ang)
    root, tip = nominal_arcs[s_]
    a = wrap_angle(ang, root)
    frac = (a - root) / (tip - root)
    where = "tip" if frac > 2 / 3 else ("root" if frac < 1 / 3 else "middle")
    return where, math.degrees(ang)
