"""Hand checks of the Chalmers thesis (seed ``003``, 2020, with Husqvarna).

* Eqs 9-10, "bending beats tension": a rod L = 0.1 m, r = 0.01 m, E = 210 GPa, clamped at
  one end, 100 N at the free end.  Axial: ``delta_D = P L / (E A)``, A = pi r^2
  (Dahlberg A2) -> 1.52e-7 m.  Transverse: cantilever tip deflection
  ``delta_B = P L^3 / (3 E I)``, I = pi (2r)^4 / 64 (solid circle, diameter 2r;
  Dahlberg A8, A12) -> 2.02e-5 m.  Both printed values follow from exactly these formulas.
* Appendix 1 (MATLAB script, values confidential): the script evaluates the *minus*-shoe
  formula (eq 7) on an rpm grid, with the apply force ``F = m rtp (x 2 pi/60)^2 - ff`` not
  clipped (so M < 0 below engagement), and the reader takes engagement where M > 0 and the
  slip speed where M meets the engine curve.  :func:`matlab_appendix` re-implements the
  script literally on top of :mod:`clutchfem.clutch.shoe`'s integrals.  The thesis gives no
  numbers, so the example uses an **ILLUSTRATIVE, ASSUMED** concept-1-like shoe
  (:data:`ILLUSTRATIVE_SHOE`); its rows are 'computed' (no paper value) and serve as
  consistency checks: grid engagement vs eq 1, grid slip vs the engine-curve bisection.

Tolerance rule (R1, as in :mod:`clutchfem.validation.wiesik`:
:func:`~.records.printed_value`): half a unit in the last printed digit, relative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..clutch import (
    BaselineClutch,
    CentrifugalShoe,
    EngineCurve,
    RippleModel,
    ShoeGeometry,
    effective_engagement_rpm,
    lining_integrals,
    simplified_torque,
    slip_rpm,
    torque_factor,
)
from ..core import ParameterError, rad_s_to_rpm, rpm_to_rad_s
from .paper_figures import finish, paper_figure
from .records import ValidationRecord, printed_value

MODULE = "thesis"
#: report heading and position (clutchfem.validation.runner: ascending ORDER, then name)
SOURCE = "seed 003: Chalmers thesis, one-piece compliant clutch"
ORDER = 20

__all__ = [
    "ROD",
    "RodExample",
    "rod_tension_deflection",
    "rod_bending_deflection",
    "ILLUSTRATIVE_SHOE",
    "MatlabResult",
    "matlab_appendix",
    "records",
    "figures",
]


@dataclass(frozen=True)
class RodExample:
    """Thesis fig. 7 rod: length L [m], radius r [m], modulus E [Pa], end load P [N]."""

    L: float = 0.1
    r: float = 0.01
    E: float = 210e9
    P: float = 100.0

    def __post_init__(self) -> None:
        for name in ("L", "r", "E", "P"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0.0):
                raise ParameterError(name, v, "finite and > 0 (SI units)")


ROD = RodExample()


def rod_tension_deflection(rod: RodExample = ROD) -> float:
    """Axial elongation ``P L / (E pi r^2)`` [m] (thesis eq 9)."""
    return rod.P * rod.L / (rod.E * math.pi * rod.r**2)


def rod_bending_deflection(rod: RodExample = ROD) -> float:
    """Cantilever tip deflection ``P L^3 / (3 E I)``, ``I = pi (2r)^4 / 64`` [m] (thesis eq 10)."""
    inertia = math.pi * (2.0 * rod.r) ** 4 / 64.0
    return rod.P * rod.L**3 / (3.0 * rod.E * inertia)


#: ILLUSTRATIVE, ASSUMED concept-1-like minus shoe for the 60 cc saw (the thesis's values
#: are confidential).  Drum R = 34.4 mm (seed 000), mu = 0.165 (seed 000, "as Husqvarna"),
#: 3 shoes; lining from 15 to 105 deg past the flexure pivot at A = 30 mm; shoe centre of
#: mass at R_Tp = 27 mm, 60 deg past the pivot ray, so the radial centrifugal force has the
#: lever L = A sin(60 deg) = 26.0 mm about the pivot; m = 25 g per shoe; flexure force at
#: contact F_f = 120 N (engagement ~4030 rpm, ~1.5 x idle).
ILLUSTRATIVE_SHOE = CentrifugalShoe(
    geometry=ShoeGeometry(
        phi1=math.radians(15.0),
        phi2=math.radians(105.0),
        A=0.030,
        R=0.0344,
        L=0.030 * math.sin(math.radians(60.0)),
    ),
    m=0.025,
    R_Tp=0.027,
    F_f=120.0,
    mu=0.165,
    n=3,
    kind="minus",
)


@dataclass(frozen=True)
class MatlabResult:
    """Output of :func:`matlab_appendix`: rpm grid, unclipped eq 7/8 torque [N m],
    engagement rpm (first grid point with M > 0) and slip rpm (first crossing of the engine
    curve, linear between grid points; None if none)."""

    rpm: np.ndarray
    torque: np.ndarray
    apply_force: np.ndarray
    engagement_rpm: float | None
    slip_rpm: float | None


def matlab_appendix(
    shoe: CentrifugalShoe = ILLUSTRATIVE_SHOE,
    engine: EngineCurve | None = None,
    rpm: np.ndarray | None = None,
) -> MatlabResult:
    """The thesis's appendix-1 script, line by line (eq 7 for a minus shoe, eq 8).

    ``F=@(x) ((m*rtp*(x*2*pi/60).^2)-ff)``; ``p0bR2=F*L/((A/R)*Iss+my*(Is-(A/R)*Isc))``;
    ``M=n*my*p0bR2*Is``.  Only the minus-shoe form exists in the script; a plus-shoe
    ``shoe`` is refused.
    """
    if shoe.kind != "minus":
        raise ParameterError("shoe.kind", shoe.kind, "'minus' (the appendix script is eq 7 only)")
    engine = EngineCurve.default() if engine is None else engine
    x = np.linspace(*engine.rpm_range, 1001) if rpm is None else np.asarray(rpm, dtype=float)
    g = shoe.geometry
    Is, Iss, Isc = lining_integrals(g.phi1, g.phi2)
    F = shoe.m * shoe.R_Tp * (x * 2 * np.pi / 60) ** 2 - shoe.F_f
    p0bR2 = F * g.L / ((g.A / g.R) * Iss + shoe.mu * (Is - (g.A / g.R) * Isc))
    M = shoe.n * shoe.mu * p0bR2 * Is
    pos = np.nonzero(M > 0.0)[0]
    eng = float(x[pos[0]]) if pos.size else None
    exc = M - engine.torque_at(x)
    hit = np.nonzero(exc >= 0.0)[0]
    slip = None
    if hit.size:
        i = int(hit[0])
        if i == 0:
            slip = float(x[0])
        else:  # linear interpolation of the crossing, as read off the plot
            e0, e1 = exc[i - 1], exc[i]
            slip = float(x[i - 1] + (x[i] - x[i - 1]) * (-e0) / (e1 - e0))
    return MatlabResult(x, M, F, eng, slip)


def _rec(id_, quantity, paper, computed, unit, tol, note) -> ValidationRecord:
    return ValidationRecord(id=f"{MODULE}.{id_}", module=MODULE, quantity=quantity, paper=paper,
                            computed=float(computed), unit=unit, tol=tol, note=note)


def records() -> list[ValidationRecord]:
    """Thesis numbers (eqs 9-10) and the appendix-script example (computed rows)."""
    out: list[ValidationRecord] = []
    dt, db = rod_tension_deflection(), rod_bending_deflection()
    v, t = printed_value("1.52e-7")
    out.append(_rec("rod_tension", "rod elongation under 100 N (eq 9)", v, dt, "m", t,
                    "P L / (E pi r^2)"))
    v, t = printed_value("2.02e-5")
    out.append(_rec("rod_bending", "cantilever tip deflection under 100 N (eq 10)", v, db, "m", t,
                    "P L^3 / (3 E I), I = pi (2r)^4/64"))
    out.append(_rec("rod_ratio", "bending / tension deflection", None, db / dt, "-", 0.0,
                    "= (4/3) (L/r)^2: slender flexures must bend, not stretch"))

    shoe = ILLUSTRATIVE_SHOE
    eng = EngineCurve.default()
    res = matlab_appendix(shoe, eng)
    w0_rpm = rad_s_to_rpm(shoe.engagement_speed)
    step = float(res.rpm[1] - res.rpm[0])
    out.append(_rec("example_engagement_rpm_eq1", "engagement, eq 1 (illustrative shoe)", None, w0_rpm,
                    "rpm", 0.0, "ASSUMED illustrative concept-1-like shoe"))
    out.append(_rec("example_engagement_rpm_script", "engagement, script (first M > 0)", None,
                    res.engagement_rpm, "rpm", 0.0,
                    f"grid step {step:.1f} rpm; eq 1 gives {w0_rpm:.1f} rpm"))
    s_bis = slip_rpm(eng, shoe.torque_at_rpm)
    out.append(_rec("example_slip_rpm_script", "slip rpm, script (M meets engine curve)", None,
                    res.slip_rpm, "rpm", 0.0,
                    f"bisection on the PCHIP engine curve gives {s_bis:.1f} rpm; engine curve ASSUMED"))
    out.append(_rec("example_slip_ratio", "slip rpm / rpm of max engine torque", None,
                    res.slip_rpm / eng.rpm_max_torque, "-", 0.0, "requirement: < b (confidential)"))
    w8000 = rpm_to_rad_s(8000.0)
    m7 = float(shoe.torque(w8000).total)
    m11 = float(simplified_torque(w8000, shoe.m, shoe.R_Tp, shoe.F_f, shoe.mu, shoe.geometry.R, shoe.n))
    out.append(_rec("example_eq11_over_eq7", "eq 11 / eq 7 torque at 8000 rpm", None, m11 / m7, "-", 0.0,
                    "point-load simplification vs distributed pressure"))
    fp = torque_factor(shoe.geometry, shoe.mu, "plus")
    fm = torque_factor(shoe.geometry, shoe.mu, "minus")
    out.append(_rec("example_plus_over_minus", "plus / minus shoe torque, same geometry", None,
                    fp.k / fm.k, "-", 0.0, "flexure on the other side of the lining (concept 4 risk)"))
    rip = RippleModel()
    out.append(_rec("example_engagement_ripple_mean", "engagement with 2-stroke ripple, typical cycle", None,
                    effective_engagement_rpm(w0_rpm, rip, 0.0), "rpm", 0.0,
                    "clutch touches at the ripple peak; delta ~ rpm (ASSUMED)"))
    out.append(_rec("example_engagement_ripple_3s", "engagement with ripple, 3-sigma cycle", None,
                    effective_engagement_rpm(w0_rpm, rip, 3.0), "rpm", 0.0,
                    "lowest speed at which the chain may move"))
    return out


def figures(out_dir: Path) -> list[Path]:
    """Torque-vs-rpm chart of the appendix script (thesis fig. 24 style) and plus/minus vs mu
    (thesis fig. 5 style) as PNGs in ``out_dir``."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    paths: list[Path] = []
    shoe = ILLUSTRATIVE_SHOE
    eng = EngineCurve.default()
    res = matlab_appendix(shoe, eng)

    fig, ax = paper_figure()
    ax.plot(res.rpm, eng.torque_at(res.rpm), "b-", label="engine (ASSUMED shape)")
    ax.plot(res.rpm, np.maximum(res.torque, 0.0), "k-", label="illustrative minus-shoe clutch, eq 7-8")
    plus = CentrifugalShoe(shoe.geometry, shoe.m, shoe.R_Tp, shoe.F_f, shoe.mu, shoe.n, "plus")
    ax.plot(res.rpm, plus.torque_at_rpm(res.rpm), "r--", label="same shoe as plus shoe, eq 2")
    ax.plot(res.rpm, BaselineClutch.new().torque_at_rpm(res.rpm), "g:", label="today's clutch (seed 000, new)")
    if res.engagement_rpm is not None:
        ax.axvline(res.engagement_rpm, color="k", ls=":", lw=0.8)
        ax.annotate("engagement", (res.engagement_rpm, 0.3), fontsize=8)
    if res.slip_rpm is not None:
        ax.plot([res.slip_rpm], [eng.torque_at(res.slip_rpm)], "ko")
        ax.annotate(f"slip {res.slip_rpm:.0f} rpm", (res.slip_rpm, eng.torque_at(res.slip_rpm) + 0.3), fontsize=8)
    eff = effective_engagement_rpm(rad_s_to_rpm(shoe.engagement_speed), RippleModel(), 3.0)
    ax.axvline(eff, color="m", ls=":", lw=0.8)
    ax.annotate("3-sigma ripple engagement", (eff - 250.0, 5.0), fontsize=7, color="m", rotation=90)
    finish(fig, ax, out_dir / "thesis_appendix_torque_rpm.png", paths, legend=dict(fontsize=8),
           xlabel="crank speed [rpm]", ylabel="torque [N m]", ylim=(0, 12),
           title="Thesis appendix 1 script, ILLUSTRATIVE shoe data")

    fig, ax = paper_figure()
    mus = np.linspace(0.0, 0.6, 301)
    F = 300.0
    for kind, style in (("minus", "b-"), ("plus", "r-")):
        tq = np.array([torque_factor(shoe.geometry, mu, kind).k * F for mu in mus])
        ax.plot(mus, np.where(np.isfinite(tq), tq, np.nan), style, label=f"{kind} shoe")
    ax.axvline(0.165, color="0.5", ls=":", lw=0.8)
    finish(fig, ax, out_dir / "thesis_plus_minus_mu.png", paths, legend=dict(fontsize=8),
           xlabel="friction coefficient mu", ylabel="torque per shoe [N m] (F = 300 N)", ylim=(0, 10),
           title="Plus vs minus shoe sensitivity to mu (thesis fig. 5 style)")
    return paths
