"""Numerical stress test: drive the solver to its edges; every case must end in a correct
answer or a clear refusal, never a silent wrong number (issue 12).

Each case function returns :class:`Outcome` records: the inputs, ``answer`` or ``refused``
(with the message), the engagement speed, the largest equilibrium residual and torque-balance
error of the sweep, the condition estimate, and a check against a reference where one exists
(closed form, finer mesh, cold-started solve).  ``tests/test_numerical_edges.py`` asserts the
invariants on them; ``benchmarks/bench_stress.py`` prints the table kept in BENCHMARKS.md.

Cases: a flexure at its slenderness limit (L/t = 100), badly shaped (sliver) elements,
mesh sizes from the coarsest allowed to very fine (and past the size limit), speeds up to
and beyond the divergence speed, clearances from 1 um to 2 mm against the closed-form
rotating annulus, friction 0..1 on plus and minus shoes, contact that opens and closes
along the arc as the speed rises, shoes that never engage.
"""

from __future__ import annotations

import math
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from clutchfem.core import ClutchfemError, rad_s_to_rpm

#: every case's sweep speeds [rpm] unless it says otherwise
SPEEDS = "0:14000:500"


@dataclass
class Outcome:
    case: str
    inputs: str
    outcome: str = "answer"  # or "refused"
    message: str = ""
    engagement_rpm: float | None = None
    max_residual: float = math.nan
    max_torque_balance: float = math.nan
    condition: float = math.nan
    reference: str = ""  # what the answer was checked against, and the error
    error: float = math.nan
    seconds: float = 0.0
    extra: dict = field(default_factory=dict)

    def row(self) -> tuple:
        eng = "-" if self.engagement_rpm is None else f"{self.engagement_rpm:.1f}"
        return (self.case, self.inputs, self.outcome, eng, f"{self.max_residual:.1e}",
                f"{self.max_torque_balance:.1e}", f"{self.condition:.1e}",
                (f"{self.reference}: {self.error:.1e}" if self.reference else "") or "-",
                (self.message[:90] + "...") if len(self.message) > 90 else self.message)


HEADERS = ("case", "inputs", "outcome", "engagement rpm", "max residual", "max torque bal.", "cond. est.",
           "check", "message")


def _run(case: str, inputs: str, fn) -> Outcome:
    t0 = time.perf_counter()
    o = Outcome(case, inputs)
    try:
        res = fn(o)
        if res is not None:
            o.engagement_rpm = res.engagement_rpm
            o.max_residual = float(res.curve["residual"].max())
            o.max_torque_balance = float(res.curve["torque_balance_error"].max())
            o.condition = float(res.condition)
            o.extra["result"] = res
    except ClutchfemError as exc:
        o.outcome, o.message = "refused", str(exc).replace("\n", " ")
    o.seconds = time.perf_counter() - t0
    return o


def _concept_design(name: str, size: float | None = None, mu: float | None = None, **params):
    from clutchfem.geometry import MeshSettings, get_concept
    from clutchfem.loadcase import Design, OperatingPoint
    from clutchfem.mesh import mesh_concept

    c = get_concept(name)
    p = c.params(**params)
    ms = MeshSettings() if size is None else MeshSettings(size=size)
    # spin softening only ('ritz') so that 'exact' is its per-speed reference
    op = OperatingPoint(softening="ritz") if mu is None else OperatingPoint(mu=mu, softening="ritz")
    return Design(mesh_concept(c, p, ms), op, params=p, name=name)


def slender_flexure() -> list[Outcome]:
    """Concept 1, two shoes, 30 mm x 0.3 mm flexure: slenderness 100."""
    def fn(o):
        d = _concept_design("concept1", n_shoes=2, shoe_arc=60.0, flexure_length=0.030, flexure_thickness=0.3e-3)
        lim = rad_s_to_rpm(d.case().omega_limit)
        o.extra["divergence_rpm"] = lim
        return d.sweep(np.arange(0.0, 0.95 * lim, 0.95 * lim / 20))
    return [_run("slender flexure", "concept1, n=2, L/t = 30/0.3 mm = 100, up to 0.95 x divergence", fn)]


def sliver_elements(tmp: Path) -> list[Outcome]:
    """Rotating annulus against a drum with one interior node pushed almost onto its
    neighbour (aspect ratios up to ~1e3): checked against the closed-form engagement."""
    from clutchfem.loadcase import Design, OperatingPoint

    from .shapes import load_annulus

    out = []
    a, b, h, c_gap = 6.5e-3, 33.8e-3, 11e-3, 0.2e-3
    meshed = {}  # the annulus, meshed once: each case moves a vertex of a copy of its points
    for squash in (0.0, 0.5, 0.9, 0.99, 0.999):
        def fn(o, squash=squash):
            if "cm" not in meshed:
                meshed["cm"] = load_annulus(tmp / "sliver.msh", a, b, 2e-3, thickness=h)
            cm = meshed["cm"]
            m = cm.mesh
            if True:  # straight-sided P2 for all, so that only the sliver differs
                # move an interior vertex towards its nearest vertex neighbour
                bnd = np.zeros(m.p.shape[1], dtype=bool)
                bnd[m.facets[:, m.boundary_facets()].ravel()] = True
                ok = np.nonzero(~bnd[m.t].any(axis=0))[0]  # elements with 3 interior vertices
                el = int(ok[len(ok) // 2])
                i, j = int(m.t[0, el]), int(m.t[1, el])
                p = m.p.copy()
                p[:, i] = p[:, i] + squash * (p[:, j] - p[:, i])
                from skfem import MeshTri1, MeshTri2
                nv = int(m.t.max()) + 1  # vertices come first in p, then the mid-edge nodes
                mesh2 = MeshTri2.from_mesh(MeshTri1(p[:, :nv], m.t))  # straight-sided P2 elements
                q = _min_angle_deg(p[:, :nv], m.t)
                o.inputs += f" (smallest angle {q:.2g} deg)"
                mesh2 = mesh2.with_boundaries({k: v for k, v in (m.boundaries or {}).items()})
                from clutchfem.mesh import check_orientation
                check_orientation(mesh2, "sliver mesh")
                from dataclasses import replace
                cm = replace(cm, mesh=mesh2)
            d = Design(cm, OperatingPoint(drum_radius=b + c_gap, mu=0.3))
            res = d.sweep([0.0, 3.5e4 * 60 / (2 * math.pi)])
            w0 = _annulus_engagement(a, b, c_gap, d.model.material)
            o.reference, o.error = "closed-form engagement (Lame, no softening)", abs(
                d.sweep([0.0], softening="off").engagement_rpm / rad_s_to_rpm(w0) - 1)
            return res
        out.append(_run("sliver elements", f"annulus, one vertex moved {100 * squash:g} % onto a neighbour", fn))
    return out


def _min_angle_deg(p: np.ndarray, t: np.ndarray) -> float:
    """Smallest interior angle [deg] of the straight triangles (p, t)."""
    worst = 180.0
    for k in range(3):
        a, b, c = p[:, t[k]], p[:, t[(k + 1) % 3]], p[:, t[(k + 2) % 3]]
        u, v = b - a, c - a
        cos = np.sum(u * v, axis=0) / np.maximum(np.linalg.norm(u, axis=0) * np.linalg.norm(v, axis=0), 1e-300)
        worst = min(worst, float(np.degrees(np.arccos(np.clip(cos, -1, 1))).min()))
    return worst


def _annulus_engagement(a, b, c, mat) -> float:
    """Engagement speed [rad/s] of a free rotating annulus (Lame, plane stress, clamped at
    r = a, free at r = b, no softening): u(b; w) = c."""
    E, nu, rho = mat.E, mat.nu, mat.rho
    D = E / (1 - nu * nu)
    C = rho / D  # w = 1
    # u = A r + B / r - C r^3 / 8;  u(a) = 0;  s_r(b) = 0
    f = [lambda r: r, lambda r: 1.0 / r, lambda r: -C * r ** 3 / 8]
    df = [lambda r: 1.0, lambda r: -1.0 / r ** 2, lambda r: -3 * C * r ** 2 / 8]
    sr = lambda i, r: df[i](r) + nu * f[i](r) / r  # noqa: E731
    M = np.array([[f[0](a), f[1](a)], [sr(0, b), sr(1, b)]])
    A, B = np.linalg.solve(M, [-f[2](a), -sr(2, b)])
    u1 = A * b + B / b + f[2](b)
    return math.sqrt(c / u1)


def mesh_sizes() -> list[Outcome]:
    """Concept 4 from the coarsest allowed mesh to a fine one, and past the size limit;
    engagement checked against the finest answer."""
    out, results = [], {}
    for size in (10e-3, 5e-3, 2.4e-3, 1.2e-3, 0.6e-3, 0.05e-3):
        def fn(o, size=size):
            r = _concept_design("concept4", size=size).sweep([0.0, 8000.0, 14000.0], stresses=True)
            results[size] = r.engagement_rpm
            return r
        out.append(_run("mesh size", f"concept4, size {size * 1e3:g} mm", fn))
    ref = results.get(0.6e-3)
    for o, size in zip(out, (10e-3, 5e-3, 2.4e-3, 1.2e-3, 0.6e-3, 0.05e-3)):
        if o.outcome == "answer" and ref and size != 0.6e-3:
            o.reference, o.error = "engagement vs 0.6 mm mesh", abs(o.engagement_rpm / ref - 1)
    return out


def near_divergence() -> list[Outcome]:
    """Concept 4 at 0.5 .. 0.999 of its divergence speed (answers, with their residuals) and
    at / beyond it (refused), for the Ritz and the exact spin softening."""
    d = _concept_design("concept4", size=2.4e-3)
    lim = rad_s_to_rpm(d.case().omega_limit)
    out = []
    for f in (0.5, 0.9, 0.99, 0.999, 1.0, 1.5):
        for soft in ("ritz", "exact"):
            def fn(o, f=f, soft=soft):
                r = d.sweep([f * lim], softening=soft)
                if soft == "ritz":
                    ex = d.sweep([f * lim], softening="exact")
                    n_ex = float(ex.curve["normal_force_N"].iloc[0])
                    o.reference = "normal force vs exact softening"
                    o.error = abs(float(r.curve["normal_force_N"].iloc[0]) / n_ex - 1) if n_ex else 0.0
                return r
            out.append(_run("near divergence", f"concept4, {f:g} x divergence ({lim:.0f} rpm), {soft}", fn))
    return out


def clearances(tmp: Path) -> list[Outcome]:
    """Rotating annulus against a drum, clearance 1 um .. 2 mm: engagement against the Lame
    closed form (no softening)."""
    from clutchfem.loadcase import Design, OperatingPoint

    from .shapes import load_annulus

    a, b, h = 6.5e-3, 33.8e-3, 11e-3
    cm = load_annulus(tmp / "clear.msh", a, b, 2e-3, thickness=h)
    out = []
    for c in (1e-6, 1e-5, 1e-4, 1e-3, 2e-3):
        def fn(o, c=c):
            d = Design(cm, OperatingPoint(drum_radius=b + c, mu=0.3, softening="off"))
            w0 = _annulus_engagement(a, b, c, d.model.material)
            r = d.sweep([0.0, min(1.3 * rad_s_to_rpm(w0), 9.0e5)])
            o.reference = "engagement vs Lame closed form"
            o.error = abs(r.engagement_rpm / rad_s_to_rpm(w0) - 1) if r.engagement_rpm else math.inf
            return r
        out.append(_run("clearance", f"annulus, clearance {c * 1e3:g} mm", fn))
    return out


def friction() -> list[Outcome]:
    """Concept 1, plus and minus arrangements, mu = 0 .. 1 (the range end): torque >= 0,
    the normal force ratio N(mu)/N(0) reported (self-energising plus, de-energising minus)."""
    out = []
    for arr in ("minus", "plus"):
        d = _concept_design("concept1", size=2.4e-3, arrangement=arr)
        n0 = float(d.sweep([8000.0], mu=0.0, stresses=False).curve["normal_force_N"].iloc[0])
        for mu in (0.0, 0.165, 0.4, 0.8, 1.0):
            def fn(o, mu=mu):
                r = d.sweep(SPEEDS, mu=mu, stresses=False)
                n = float(r.curve.set_index("rpm").loc[8000.0, "normal_force_N"])
                o.extra["N_ratio"] = n / n0
                return r
            out.append(_run("friction", f"concept1 {arr}, mu {mu:g}", fn))
    return out


def moving_contact() -> list[Outcome]:
    """Concept 4 with a linear profile (clearance small at the root, large at the tip): the
    contact starts at the root and moves/spreads with speed, nodes closing and opening; the
    warm-started sweep is checked against cold solves at every speed."""
    def fn(o):
        d = _concept_design("concept4", size=2.4e-3, profile="linear", clearance=0.3e-3, clearance_tip=1.2e-3)
        r = d.sweep(SPEEDS, stresses=False)
        case = d.case()
        worst, opened = 0.0, 0
        prev = None
        for k, w in enumerate(r.omega):
            cold, _ = case.__class__(case.model, case.contact, case.softening).solve(float(w))
            ref = max(float(np.abs(cold).max()), 1e-300)
            worst = max(worst, float(np.abs(cold - r.lam[k]).max()) / ref if cold.any() else 0.0)
            on = r.lam[k] > 0
            if prev is not None:
                opened += int(np.count_nonzero(prev & ~on))
            prev = on
        o.reference, o.error = "warm vs cold contact solves", worst
        o.extra["nodes_opening"] = opened
        return r
    return [_run("moving contact", "concept4 linear profile 0.3 -> 1.2 mm, 0..14000 rpm", fn)]


def never_engages() -> list[Outcome]:
    """Concept 1 with a 3 mm clearance and a stiff 3 mm flexure: it engages only above the
    engine's speed range (with spin softening every outward-moving shoe reaches the drum
    before divergence), so the analysis must say 'never engages', with no slip speed."""
    def fn(o):
        from clutchfem.analysis import analyze

        d = _concept_design("concept1", size=2.4e-3, clearance=3e-3, flexure_thickness=3e-3, shoe_arc=70.0)
        an = analyze(d)
        o.extra.update(status=an.slip_status, slip_rpm=an.slip_rpm, torque_8000=an.torque_at_max_engine_torque_Nm)
        o.reference, o.error = "torque in the engine range (must be 0)", float(an.curves["fe_torque_Nm"].abs().max())
        return d.sweep(SPEEDS)
    return [_run("never engages", "concept1, clearance 3 mm, flexure 3 mm (analyze)", fn)]


def all_cases() -> list[Outcome]:
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        return (slender_flexure() + sliver_elements(tmp) + mesh_sizes() + near_divergence() + clearances(tmp)
                + friction() + moving_contact() + never_engages())
