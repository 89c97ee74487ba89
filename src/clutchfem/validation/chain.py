"""Impact tension of a round-link chain on a pocket wheel (seed ``002``, Rynik & Dolipski).

Validation module: reproduces eqs (1)-(18) of J. Rynik, M. Dolipski, *Napiecia udarowe
lancucha ogniwowego wspolpracujacego z kolem gniazdowym* (Polish, OCR'd) and its worked
example (figs 3-4).  Interface shared by all validation modules: :func:`records` and
:func:`figures`.

Geometry (nominal meshing: the working joint centres of the chain lie on the pitch circle)::

    R      = 1/2 sqrt( (t / sin(pi/2z))^2 + (d / cos(pi/2z))^2 )            (3)
    delta1 = 2 asin((t + d) / 2R)   horizontal (pocket) link, chord t + d    (7)
    delta2 = 2 asin((t - d) / 2R)   vertical link, chord t - d               (8)
    delta1 + delta2 = 2 pi / z                                               (9)
    R_C = R_G = sqrt(R^2 + d^2/4 - R d sin((delta2 + psi)/2))                (4)
    gamma  = asin( d/(2 R_G) cos((delta2 + psi)/2) )
    alpha1 = delta1/2 + gamma,   alpha2 = delta2/2 - gamma                   (5, 6)
    v_u1 = w [ R cos((psi - delta2)/2) - R_C cos(psi/2 + alpha2) ]           (1)
    v_u2 = w [ R_G cos(pi/z + psi/2 - alpha1) - R cos(pi/z + psi/2 + delta1/2) ]   (2)
    E_u  = k m_0 v_u^2 / 2,  m_0 = q t / g,  k = 2                           (10, 11)
    T    = N^2 L / (2 E_0)                                                   (14)
    N_u  = v_u sqrt(k q t E_0 / (g L))                                       (16)-(18)

OCR reconstruction (how the printed formulas were read):

* The OCR writes the tooth apex angle as ``nu`` in (1)-(4) and ``pi`` in the symbol list;
  (5), (6), (12), (13) spell it ``psi``.  ``kappa_1, kappa_2`` in (12), (13), (17), (18) are
  ``alpha_1, alpha_2`` and ``R_0``/``R_c`` are ``R_G``/``R_C``.
* (13) prints ``pi/2`` and ``- delta1/2`` where (2) and (18) print ``pi/z`` and
  ``+ delta1/2``.  The ``-`` reading is physically impossible: ``G`` lies on the flank normal
  through the joint centre (``|JG| = d/2`` along the normal), so the normal projections of
  the wheel's rigid-body velocity at ``G`` and at the joint centre are equal and ``v_u2``
  would vanish identically.  We use ``+ delta1/2`` (two of three printings agree).
* (17), (18) print ``R_c`` for both terms; (1), (2) print ``R`` for the joint-centre term.
  We follow (1), (2) (the joint centre lies on the pitch circle, radius ``R``).
* With these readings the wheel terms collapse (law of sines in triangle O-J-C) and the
  speeds have closed forms that the tests check:
  ``v_u1 = w (t - d) sin(psi/2)`` (independent of ``z``) and
  ``v_u2 = w (t + d) sin(psi/2 + pi/z)``.

Unit weight of the chain: the paper does not print ``q``.  ``m_0 = q t / g`` is the link
mass, so only the mass per length ``q/g`` [kg/m] enters (16); we use
:data:`MASS_PER_LENGTH_ASSUMED` = 6.6 kg/m, the tabulated mass of an 18x64 round-link
mining chain (DIN 22252, grade-independent; a wire-length estimate, centre-line length
2(t - b) + pi (b + d) with inner width b = 21 mm, gives 6.5 kg/m).  ``N_u`` scales with the
square root of it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.optimize import brentq

from ..core import ParameterError, figure
from .records import ValidationRecord

MODULE = "chain"
#: report heading and position (clutchfem.validation.runner: ascending ORDER, then name)
SOURCE = "seed 002: Rynik & Dolipski, impact tension of a round-link chain on a pocket wheel"
ORDER = 30

#: Mass share factor of Rjabow [1]: the equivalent impacting mass is twice the link mass.
K_MASS_SHARE = 2.0
#: Assumed mass per metre of chain 18x64 [kg/m] (q/g of the paper); see module docstring.
MASS_PER_LENGTH_ASSUMED = 6.6


@dataclass(frozen=True)
class ChainExample:
    """The paper's worked example (section 3).  SI units."""

    pitch_m: float = 0.064  # t, chain 18x64
    wire_diameter_m: float = 0.018  # d
    stiffness_N: float = 2.26e7  # E_0, chain stiffness (force per unit strain) [3]
    branch_length_m: float = 2.0  # L, active branch length
    omega_rad_s: float = 20.0  # w, pocket-wheel angular speed
    teeth: tuple[int, ...] = (6, 8, 10)
    apex_angle_deg_range: tuple[float, float] = (20.0, 60.0)
    mass_per_length_kg_m: float = MASS_PER_LENGTH_ASSUMED  # assumed, not in the paper
    k: float = K_MASS_SHARE


EXAMPLE = ChainExample()


@dataclass(frozen=True)
class WheelGeometry:
    """Pocket-wheel quantities of eqs (3)-(9); angles in rad, lengths in m."""

    pitch_radius_m: float  # R, eq (3)
    delta1_rad: float  # eq (7)
    delta2_rad: float  # eq (8)
    impact_radius_m: np.ndarray | float  # R_C = R_G, eq (4)
    alpha1_rad: np.ndarray | float  # eq (5)
    alpha2_rad: np.ndarray | float  # eq (6)


def _check_chain(t: float, d: float) -> None:
    if not (math.isfinite(t) and t > 0):
        raise ParameterError("t", t, "chain pitch > 0 m, finite")
    if not (math.isfinite(d) and 0 < d < t):
        raise ParameterError("d", d, f"0 < wire diameter < pitch t = {t} m")


def _check_z(z: int) -> None:
    if isinstance(z, bool) or not float(z).is_integer() or z < 3:
        raise ParameterError("z", z, "integer number of teeth >= 3")


def _check_psi(psi) -> np.ndarray:
    p = np.asarray(psi, dtype=float)
    if not np.all(np.isfinite(p)) or np.any(p <= 0) or np.any(p >= math.pi):
        raise ParameterError("psi", psi, "tooth apex angle in (0, pi) rad")
    return p


def _positive(name: str, value: float, unit: str) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0):
        raise ParameterError(name, value, f"> 0 {unit}, finite")
    return v


def pitch_radius(t: float, d: float, z: int) -> float:
    """Pitch-circle radius R [m] of a pocket wheel, eq (3).

    The chain polygon alternates chords ``t + d`` (horizontal link, central angle delta1)
    and ``t - d`` (vertical link, delta2) with ``delta1 + delta2 = 2 pi / z``; solving the
    two chord relations gives (3).
    """
    _check_chain(t, d)
    _check_z(z)
    h = math.pi / (2 * z)
    return 0.5 * math.hypot(t / math.sin(h), d / math.cos(h))


def central_angles(t: float, d: float, z: int) -> tuple[float, float]:
    """Central angles (delta1, delta2) [rad] between working joint centres, eqs (7), (8)."""
    R = pitch_radius(t, d, z)
    return 2 * math.asin((t + d) / (2 * R)), 2 * math.asin((t - d) / (2 * R))


def wheel_geometry(t: float, d: float, z: int, psi) -> WheelGeometry:
    """R, delta1, delta2, impact-point radius R_C = R_G and alpha1, alpha2, eqs (3)-(9).

    ``psi`` is the tooth apex angle [rad] (scalar or array).  R_C follows from the law of
    cosines in triangle (wheel centre O, joint centre J, impact point C): ``|JC| = d/2``
    along the flank normal, which makes the angle ``pi/2 - (delta2 + psi)/2`` with OJ; the
    arcsine in (5), (6) is the angle JOC from the law of sines.
    """
    p = _check_psi(psi)
    R = pitch_radius(t, d, z)
    d1, d2 = central_angles(t, d, z)
    half = (d2 + p) / 2
    rc = np.sqrt(R**2 + d**2 / 4 - R * d * np.sin(half))
    gamma = np.arcsin(d / (2 * rc) * np.cos(half))
    a1 = d1 / 2 + gamma
    a2 = d2 / 2 - gamma
    if np.ndim(psi) == 0:
        rc, a1, a2 = float(rc), float(a1), float(a2)
    return WheelGeometry(R, d1, d2, rc, a1, a2)


def impact_speeds(t: float, d: float, z: int, psi, omega: float):
    """Impact speeds (v_u1, v_u2) [m/s] on the non-working / working tooth side, eqs (1), (2).

    Each is the difference of the projections on the common normal (tooth flank / link) of
    the wheel's velocity at the impact point and of the chain's working joint centre.
    ``psi`` in rad (scalar or array), ``omega`` in rad/s.  Read with ``+ delta1/2`` in (2),
    see the module docstring.
    """
    omega = _positive("omega", omega, "rad/s")
    g = wheel_geometry(t, d, z, psi)
    p = np.asarray(psi, dtype=float)
    R, rc = g.pitch_radius_m, g.impact_radius_m
    v1 = omega * (R * np.cos((p - g.delta2_rad) / 2) - rc * np.cos(p / 2 + g.alpha2_rad))
    v2 = omega * (
        rc * np.cos(math.pi / z + p / 2 - g.alpha1_rad)
        - R * np.cos(math.pi / z + p / 2 + g.delta1_rad / 2)
    )
    if np.ndim(psi) == 0:
        return float(v1), float(v2)
    return v1, v2


def link_mass(mass_per_length_kg_m: float, t: float) -> float:
    """Link mass m_0 = q t / g [kg], eq (11), with q/g the chain's mass per length [kg/m]."""
    return _positive("mass_per_length_kg_m", mass_per_length_kg_m, "kg/m") * _positive(
        "t", t, "m"
    )


def impact_energy(v_u, mass_per_length_kg_m: float, t: float, k: float = K_MASS_SHARE):
    """Impact energy E_u = k m_0 v_u^2 / 2 [J], eqs (10)-(13)."""
    k = _positive("k", k, "(mass share factor)")
    return k * link_mass(mass_per_length_kg_m, t) * np.asarray(v_u) ** 2 / 2


def elastic_energy(N, branch_length_m: float, stiffness_N: float):
    """Elastic energy of the chain branch T = N^2 L / (2 E_0) [J], eq (14)."""
    L = _positive("L", branch_length_m, "m")
    E0 = _positive("E_0", stiffness_N, "N")
    return np.asarray(N) ** 2 * L / (2 * E0)


def impact_tension(
    v_u,
    mass_per_length_kg_m: float,
    t: float,
    stiffness_N: float,
    branch_length_m: float,
    k: float = K_MASS_SHARE,
):
    """Impact tension N_u = v_u sqrt(k q t E_0 / (g L)) [N], eqs (15)-(18).

    From E_u (10) = T (14).  ``q/g`` is the mass per length [kg/m].
    """
    k = _positive("k", k, "(mass share factor)")
    E0 = _positive("E_0", stiffness_N, "N")
    L = _positive("L", branch_length_m, "m")
    m0 = link_mass(mass_per_length_kg_m, t)
    n = np.asarray(v_u, dtype=float) * math.sqrt(k * m0 * E0 / L)
    return float(n) if np.ndim(v_u) == 0 else n


def impact_tensions(z: int, psi, ex: ChainExample = EXAMPLE):
    """(N_u1, N_u2) [N] of the example chain for ``z`` teeth and apex angle ``psi`` [rad]."""
    v1, v2 = impact_speeds(ex.pitch_m, ex.wire_diameter_m, z, psi, ex.omega_rad_s)
    args = (ex.mass_per_length_kg_m, ex.pitch_m, ex.stiffness_N, ex.branch_length_m, ex.k)
    return impact_tension(v1, *args), impact_tension(v2, *args)


# --------------------------------------------------------------------------------------
# Validation records and figures
# --------------------------------------------------------------------------------------


def _psi_grid(ex: ChainExample, n: int = 81) -> np.ndarray:
    lo, hi = ex.apex_angle_deg_range
    return np.radians(np.linspace(lo, hi, n))


def records() -> list[ValidationRecord]:
    """One record per number the paper prints (plus a few documented computed values)."""
    ex = EXAMPLE
    out: list[ValidationRecord] = []
    q = ex.mass_per_length_kg_m

    # Minimum N_u2 over the paper's grid z in {6, 8, 10}, psi in [20, 60] deg.
    psi = _psi_grid(ex)
    grid = {z: impact_tensions(z, psi, ex)[1] for z in ex.teeth}
    z_min, i_min = min(((z, int(np.argmin(v))) for z, v in grid.items()),
                       key=lambda zi: grid[zi[0]][zi[1]])  # (teeth, index of psi) at min
    n2_min = float(grid[z_min][i_min])
    q_needed = q * (2300.0 / n2_min) ** 2  # N_u ~ sqrt(q)
    out.append(ValidationRecord(
        "chain.Nu2_min", MODULE, "min N_u2 over z in {6,8,10}, psi in [20,60] deg", 2300.0,
        n2_min, "N", tol=50.0 / 2300.0,
        note=(f"q/g = {q} kg/m assumed (DIN 22252, 18x64; not in the paper); N_u ~ sqrt(q): "
              f"2300 N would need q/g = {q_needed:.2f} kg/m, below the 6.6-6.9 kg/m of 18x64 "
              "chains; tol = half a unit of the printed 2300 (nearest 100 N)")))
    out.append(ValidationRecord(
        "chain.Nu2_min_z", MODULE, "teeth z at min N_u2", 10.0, float(z_min), "-", tol=0.0,
        note="N_u2 falls with z (v_u2 = w (t+d) sin(psi/2 + pi/z))"))
    out.append(ValidationRecord(
        "chain.Nu2_min_psi", MODULE, "apex angle psi at min N_u2", 20.0,
        float(np.degrees(psi[i_min])), "deg", tol=1e-9,
        note="N_u2 rises with psi on the whole range (lower end of the grid)"))

    # Ratio N_u2 / N_u1 at psi = 40 deg, z = 8 (q, E_0, L, omega cancel: geometry only).
    n1, n2 = impact_tensions(8, math.radians(40.0), ex)
    t, d = ex.pitch_m, ex.wire_diameter_m
    def ratio_at(p_rad: float) -> float:
        a, b = impact_tensions(8, p_rad, ex)
        return b / a - 2.54

    psi_254 = math.degrees(brentq(ratio_at, math.radians(1.0), math.radians(179.0)))
    s20 = math.sin(math.radians(20.0))
    ratio_t = (t + d) * math.sin(math.radians(20.0) + math.pi / 8) / (t * s20)
    out.append(ValidationRecord(
        "chain.ratio_psi40_z8", MODULE, "N_u2/N_u1 at psi = 40 deg, z = 8", 2.54, n2 / n1, "-",
        tol=0.005 / 2.54,
        note=("geometry-only ratio (t+d) sin(psi/2+pi/z) / ((t-d) sin(psi/2)) from eqs (1)-(9) as "
              "printed; 2.54 is not reachable on psi in [20,60] deg "
              f"(needs psi = {psi_254:.1f} deg); t in place "
              f"of t-d in v_u1 would give {ratio_t:.2f}: the paper's fig 4 likely used other N_u1 "
              "geometry")))

    # Eq (9): delta1 + delta2 = 2 pi / z (a consistency check of eqs 3, 7, 8).
    for z in ex.teeth:
        d1, d2 = central_angles(t, d, z)
        out.append(ValidationRecord(
            f"chain.delta_sum.z{z}", MODULE, f"delta1 + delta2 (eq 9), z = {z}",
            360.0 / z, math.degrees(d1 + d2), "deg", tol=1e-9,
            note="eqs (3), (7), (8) are consistent with (9)"))

    # Documented computed values (no number in the paper; read off figs 3-4 if you have them).
    for z in ex.teeth:
        for deg_ in (20.0, 60.0):
            _, n2z = impact_tensions(z, math.radians(deg_), ex)
            out.append(ValidationRecord(
                f"chain.Nu2.z{z}.psi{deg_:g}", MODULE, f"N_u2, z = {z}, psi = {deg_:g} deg",
                None, float(n2z), "N", note=f"fig 3 curve point, q/g = {q} kg/m assumed"))
    out.append(ValidationRecord(
        "chain.Nu1.z8.psi40", MODULE, "N_u1, z = 8, psi = 40 deg", None, float(n1), "N",
        note=f"fig 4 curve point; v_u1 = w (t-d) sin(psi/2) does not depend on z; q/g = {q} kg/m"))
    out.append(ValidationRecord(
        "chain.Eu2.z10.psi20", MODULE, "impact energy E_u2, z = 10, psi = 20 deg (eq 13)", None,
        float(impact_energy(impact_speeds(t, d, 10, math.radians(20.0), ex.omega_rad_s)[1], q, t)),
        "J", note="E_u = k m_0 v_u^2/2 with m_0 = q t/g"))
    return out


def figures(out_dir: Path) -> list[Path]:
    """Reproduce figs 3 (N_u2 vs psi) and 4 (N_u1 vs psi) for z = 6, 8, 10; returns PNG paths."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    ex = EXAMPLE
    psi = _psi_grid(ex)
    deg_ = np.degrees(psi)
    paths: list[Path] = []
    specs = [
        (1, "fig3_Nu2_vs_psi.png", "Rys. 3: impact tension on the working tooth side $N_{u2}$"),
        (0, "fig4_Nu1_vs_psi.png",
         "Rys. 4: impact tension on the non-working side $N_{u1}$ (same for all z)"),
    ]
    for which, name, title in specs:
        fig, ax = figure(figsize=(6.4, 4.2))
        for z, ls in zip(ex.teeth, ("-", "--", ":")):
            ax.plot(deg_, impact_tensions(z, psi, ex)[which], ls, label=f"z = {z}")
        if which == 1:
            ax.plot([20.0], [2300.0], "ko", label="paper: min 2300 N (z=10)")
        ax.set_xlabel("tooth apex angle psi [deg]")
        ax.set_ylabel("impact tension [N]")
        ax.set_title(title, fontsize=9)
        ax.text(0.98, 0.02, f"chain 18x64, L = 2 m, w = 20 1/s, q/g = {ex.mass_per_length_kg_m}"
                " kg/m (assumed)", transform=ax.transAxes, fontsize=7, ha="right")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        p = out_dir / name
        fig.savefig(p, dpi=110)
        paths.append(p)
    return paths
