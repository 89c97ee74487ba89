"""Crankshaft whirl of a clutch design: the first critical speed of the chainsaw crankshaft
carrying the design's clutch, the drum and the sprocket on its overhang.

A design analysis (like the slip speed or the stress check), not a paper comparison: the
mechanics is the overhung shaft of :mod:`clutchfem.clutch.shaft` (validated against the seed-004
paper in :mod:`clutchfem.validation.shaft`); this module supplies the rotor.

* **Clutch** (:func:`whirl`): mass and inertia of the design's *own* mesh, by quadrature
  over its curved P2 triangles (:func:`clutchfem.mesh.mesh_area_properties`), no extra meshing.  A
  one-sector model of n identical sectors is completed to the whole part by cyclic
  symmetry: the sector's second-moment tensor is rotated by ``k 2 pi / n`` and summed, which
  for n >= 3 gives I_xx = I_yy = J/2 about the axis (and the centroid on the axis); a full
  model's actual moments and centroid are used.  Agreement with the geometry module's
  OCC-exact area properties of the full part (:func:`concept_rotor`, the reference path) is
  ~1e-7 at the default mesh (tests/test_clutch_whirl.py).
* **Drum, sprocket, crankshaft**: ASSUMED (:class:`ChainsawLayout`, a 60 cc saw; the drum
  wall sits on the design's drum radius).  Every part is a :class:`RigidPart`; the
  :class:`Rotor` lumps them at their composite centre of mass, which ends the overhang.
* **Critical speed** (:func:`crankshaft_whirl`): synchronous forward whirl, effective tip
  rotary inertia ``I_d - I_p(spinning parts)``, read three ways (clutch engaged: all parts
  spin; drum held by the chain brake: only the clutch spins; no gyroscopic effect: the
  natural frequency at rest, the most conservative).  Each root of the exact frequency
  determinant is checked against the Hermite beam FE model.

Bearing and crankcase compliance are not modelled (rigid pinned main bearings): they would
lower the critical speeds, so the margin over the maximum engine speed is an upper estimate.
SI units throughout; speeds in rpm where designers expect them.

Usage::

    from clutchfem.loadcase import Design
    from clutchfem.clutch import whirl
    ans = whirl(Design.from_concept("concept4"))
    print(ans.summary())
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Literal

from ..core import ParameterError, SolverError, get_material, rad_s_to_rpm
from ..geometry import MeshSettings, concepts, get_concept
from ..loadcase import Design
from ..mesh import mesh_area_properties, mesh_concept
from .shaft import OverhungShaft, clear_beam_cache, finite_param, first_frequency_coefficient

Spin = Literal["crank", "drum"]
Gyro = Literal["engaged", "drum_held", "none"]


@dataclass(frozen=True)
class RigidPart:
    """One rigid body on the crankshaft overhang (axisymmetric in the whirl model).

    ``polar_inertia_kg_m2`` about the spin axis and ``diametral_inertia_kg_m2`` about a
    diameter, both through the part's own centre of mass; ``axial_position_m`` is that
    centre's distance from the clutch-side main bearing.  ``spins``: ``"crank"`` = always
    turns with the crankshaft (the clutch), ``"drum"`` = turns with it only while the
    clutch is engaged (drum, sprocket: they sit on a needle bearing).  ``source`` says where
    the numbers come from (the design's mesh, the geometry module, or ASSUMED).
    """

    name: str
    mass_kg: float
    polar_inertia_kg_m2: float
    diametral_inertia_kg_m2: float
    axial_position_m: float
    spins: Spin
    source: str

    def __post_init__(self):
        finite_param("mass_kg", self.mass_kg, unit="kg")
        finite_param("polar_inertia_kg_m2", self.polar_inertia_kg_m2, allow_zero=True, unit="kg m^2")
        finite_param("diametral_inertia_kg_m2", self.diametral_inertia_kg_m2, allow_zero=True,
                unit="kg m^2")
        finite_param("axial_position_m", self.axial_position_m, allow_zero=True, unit="m")
        if self.polar_inertia_kg_m2 > 2 * self.diametral_inertia_kg_m2 * (1 + 1e-9):
            raise ParameterError("polar_inertia_kg_m2", self.polar_inertia_kg_m2,
                                 f"<= 2 x diametral inertia = {2 * self.diametral_inertia_kg_m2:g}"
                                 " kg m^2 (a rigid body has I_p <= 2 I_d about its centre)")
        if self.spins not in ("crank", "drum"):
            raise ParameterError("spins", self.spins, "'crank' or 'drum'")

    @classmethod
    def ring(cls, name: str, r_in_m: float, r_out_m: float, length_m: float, rho: float,
             axial_position_m: float, spins: Spin, source: str) -> RigidPart:
        """Solid ring (annulus x axial length): I_p = m (a^2 + b^2)/2,
        I_d = m ((a^2 + b^2)/4 + L^2/12)."""
        a = finite_param("r_in_m", r_in_m, allow_zero=True, unit="m")
        b = finite_param("r_out_m", r_out_m, unit="m")
        length = finite_param("length_m", length_m, unit="m")
        if b <= a:
            raise ParameterError("r_out_m", r_out_m, f"> r_in_m = {a} m")
        m = rho * math.pi * (b * b - a * a) * length
        s = a * a + b * b
        return cls(name, m, m * s / 2, m * (s / 4 + length**2 / 12), axial_position_m, spins,
                   source)


@dataclass(frozen=True)
class ChainsawLayout:
    """ASSUMED crankshaft, drum and sprocket of a 60 cc saw (not in the sources; change freely).

    Crankshaft: d = 13 mm at the clutch side (12-15 mm on 50-90 cc saws), pinned at the two
    main bearings 50 mm apart; the crank throw between them is stiffer and heavier than a
    plain shaft: modelling it as the 13 mm shaft is conservative for stiffness.  Axial stack
    outward from the clutch-side main bearing (Husqvarna order: sprocket inboard, drum open
    side outward, clutch screwed on the shaft end inside the drum):

    * sprocket (rim sprocket + its hub): steel ring r 9.0-21.0 mm (r_k = 21.2 mm pitch
      radius, seed 000), 8 mm wide, centre ``sprocket_z_m`` = 12 mm;
    * drum end wall: steel disc r 8.0-36.0 mm, 1.5 mm thick, from z = 16 mm;
    * drum wall: steel tube from the drum's inner radius (34.4 mm, seed 000, or the
      concept's ``drum_radius``) to + 1.6 mm, as long as ``gap + clutch thickness + lip``;
    * clutch: the design's part (its mesh, or the geometry module's OCC values), ``gap`` =
      1.5 mm from the end wall.

    The overhang of the whirl model ends at the composite centre of mass (all parts lumped
    into one rigid body there); the shaft beyond it carries no part.  Seed 000 gives the
    drum + sprocket (+ nose sprocket) inertia J_b = 85.10e-6 kg m^2 of its 56.5 cc saw: the
    assumed drum + sprocket is checked against it in the records.
    """

    shaft_diameter_m: float = 0.013
    bearing_span_m: float = 0.050
    sprocket_r_in_m: float = 0.009
    sprocket_r_out_m: float = 0.021
    sprocket_width_m: float = 0.008
    sprocket_z_m: float = 0.012
    drum_end_z_m: float = 0.016  # inner (bearing-side) face of the drum end wall
    drum_end_thickness_m: float = 0.0015
    drum_end_r_in_m: float = 0.008
    drum_wall_m: float = 0.0016
    drum_gap_m: float = 0.0015  # end wall to clutch face
    drum_lip_m: float = 0.0015  # drum wall beyond the clutch's outer face
    E: float = 210e9
    rho: float = 7850.0  # drum, sprocket and crankshaft steel
    max_rpm: float = 15000.0  # seed 000: saw engines run up to ~15 000 rpm


CHAINSAW_LAYOUT = ChainsawLayout()
#: Seed 000's drum + sprockets inertia (56.5 cc Husqvarna 357 XP) [kg m^2].
SEED000_J_B_KG_M2 = 85.10e-6


def clutch_part_from_mass_properties(mass: dict, thickness_m: float, rho: float,
                                     axial_position_m: float, source: str) -> RigidPart:
    """Rigid body of a one-piece clutch from the area properties of the whole part.

    ``mass["solid"]`` holds, per unit density and thickness, the area A [m^2], centroid
    (x, y) [m], ``J_centroid`` = int ((x - x_c)^2 + (y - y_c)^2) dA, ``Ixx_origin`` =
    int y^2 dA and ``Iyy_origin`` = int x^2 dA [m^4] of the *whole* part: either the
    geometry module's OCC-exact values of a full model (``ClutchMesh.mass``) or the
    quadrature over any mesh of the part (:func:`clutchfem.mesh.mesh_area_properties`, same keys).  For the
    plate of thickness h: m = rho h A, I_p = rho h J_c (about the centre of mass), I_d about
    the in-plane axes through the centre of mass: rho h (Ixx - A y_c^2) + m h^2/12 (and the
    same with x); the whirl model is axisymmetric, so the mean of the two is used (equal
    for n >= 3 identical shoes).
    """
    s = mass["solid"]
    area = float(s["area"])
    h = finite_param("thickness_m", thickness_m, unit="m")
    rh = finite_param("rho", rho, unit="kg/m^3") * h
    cx, cy = (float(c) for c in s["centroid"])
    m = rh * area
    ip = rh * float(s["J_centroid"])
    ixx = rh * (float(s["Ixx_origin"]) - area * cy * cy) + m * h * h / 12
    iyy = rh * (float(s["Iyy_origin"]) - area * cx * cx) + m * h * h / 12
    return RigidPart("clutch", m, ip, 0.5 * (ixx + iyy), axial_position_m, "crank", source)


@dataclass(frozen=True)
class Rotor:
    """Rigid parts on the overhang, lumped at their composite centre of mass."""

    parts: tuple[RigidPart, ...]

    @property
    def mass_kg(self) -> float:
        return sum(p.mass_kg for p in self.parts)

    @property
    def cg_m(self) -> float:
        """Composite centre of mass: distance from the main bearing [m] (= model overhang)."""
        return sum(p.mass_kg * p.axial_position_m for p in self.parts) / self.mass_kg

    @property
    def diametral_inertia_kg_m2(self) -> float:
        """I_d about a diameter through the composite centre (parallel-axis terms included)."""
        zc = self.cg_m
        return sum(p.diametral_inertia_kg_m2 + p.mass_kg * (p.axial_position_m - zc) ** 2
                   for p in self.parts)

    def polar_inertia_kg_m2(self, spinning: Gyro = "engaged") -> float:
        """Sum of I_p over the parts that spin at crank speed: all (clutch engaged), the
        crank-bound ones only (``drum_held``: chain brake on, clutch slipping) or none."""
        if spinning not in ("engaged", "drum_held", "none"):
            raise ParameterError("gyroscopic", spinning, "'engaged', 'drum_held' or 'none'")
        if spinning == "none":
            return 0.0
        return sum(p.polar_inertia_kg_m2 for p in self.parts
                   if spinning == "engaged" or p.spins == "crank")




def clutch_axial_position(thickness_m: float, layout: ChainsawLayout = CHAINSAW_LAYOUT) -> float:
    """Axial position [m] of the clutch's mid-plane from the clutch-side main bearing: inner
    face of the drum end wall + its thickness + ``drum_gap_m`` + half the clutch thickness."""
    L = layout
    return L.drum_end_z_m + L.drum_end_thickness_m + L.drum_gap_m + thickness_m / 2


def chainsaw_rotor(clutch: RigidPart, drum_radius_m: float, thickness_m: float,
                   layout: ChainsawLayout = CHAINSAW_LAYOUT) -> Rotor:
    """The rotor on the crankshaft overhang: ``clutch`` first, then the ASSUMED drum wall
    (from ``drum_radius_m`` outward by ``drum_wall_m``, as long as gap + clutch thickness +
    lip), drum end wall and sprocket of ``layout`` (steel rings, see
    :class:`ChainsawLayout`)."""
    L = layout
    rd = finite_param("drum_radius", drum_radius_m, unit="m")
    h = finite_param("thickness", thickness_m, unit="m")
    wall_z0 = L.drum_end_z_m + L.drum_end_thickness_m
    wall_len = L.drum_gap_m + h + L.drum_lip_m
    assumed = "ASSUMED (ChainsawLayout)"
    return Rotor((
        clutch,
        RigidPart.ring("drum wall", rd, rd + L.drum_wall_m, wall_len, L.rho,
                       wall_z0 + wall_len / 2, "drum", assumed),
        RigidPart.ring("drum end wall", L.drum_end_r_in_m, rd + L.drum_wall_m,
                       L.drum_end_thickness_m, L.rho, L.drum_end_z_m + L.drum_end_thickness_m / 2,
                       "drum", assumed),
        RigidPart.ring("sprocket", L.sprocket_r_in_m, L.sprocket_r_out_m, L.sprocket_width_m,
                       L.rho, L.sprocket_z_m, "drum", assumed),
    ))


def concept_rotor(concept: str | None = None, params=None, rho: float | None = None,
                  layout: ChainsawLayout = CHAINSAW_LAYOUT) -> tuple[str, Rotor]:
    """(concept name, rotor) for a concept with the clutch from its geometry module's
    OCC-exact area properties of the *full* 360 degree part: the reference path against
    which :func:`whirl` (a design's own mesh, no extra meshing) is tested.

    ``concept`` defaults to the default design (``concept4``, else ``concept1``: the rule of
    :func:`clutchfem.report.default_design_report`); ``params`` to the concept's defaults
    (its ``thickness`` and ``drum_radius`` are used); ``rho`` to the 51CrV4 steel of the
    thesis.  The full model is meshed once and cached on disk by
    :func:`clutchfem.mesh.mesh_concept`.
    """
    if concept is None:
        concept = "concept4" if "concept4" in concepts() else "concept1"
    c = get_concept(concept)
    p = params if params is not None else c.params()
    rho = get_material("51CrV4").rho if rho is None else rho
    cm = mesh_concept(c, p, MeshSettings(model="full"))
    h, rd = float(p.thickness), float(p.drum_radius)
    clutch = clutch_part_from_mass_properties(
        cm.mass, h, rho, clutch_axial_position(h, layout),
        f"{c.name} geometry (OCC exact area properties x rho {rho:g} kg/m^3 x h "
        f"{1e3 * h:g} mm)")
    return c.name, chainsaw_rotor(clutch, rd, h, layout)


@dataclass(frozen=True)
class WhirlResult:
    """First critical (synchronous forward whirl) speed of the crankshaft with its rotor."""

    omega_crit_rad_s: float
    rpm_crit: float
    max_rpm: float
    margin: float  # rpm_crit / max_rpm - 1 (0.25 = 25 % above the maximum engine speed)
    beta1_per_m: float
    overhang_m: float
    rotor_mass_kg: float
    effective_rotary_inertia_kg_m2: float
    gyroscopic: Gyro
    fe_rpm_crit: float  # independent FE value (Richardson), a check on rpm_crit

    def summary(self) -> str:
        g = {"engaged": "gyroscopic: all parts spinning", "drum_held": "gyroscopic: clutch "
             "only, drum held", "none": "no gyroscopic effect"}[self.gyroscopic]
        return (f"first critical speed {self.rpm_crit:,.0f} rpm "
                f"({self.omega_crit_rad_s:,.0f} rad/s, {g}); max engine speed "
                f"{self.max_rpm:,.0f} rpm; margin {100 * self.margin:+.0f} %")


def crankshaft_whirl(rotor: Rotor, layout: ChainsawLayout = CHAINSAW_LAYOUT, *,
                     gyroscopic: Gyro = "engaged") -> WhirlResult:
    """First critical speed of a crankshaft carrying ``rotor`` on its overhang.

    Same model as the saw shaft of seed 004 (:mod:`clutchfem.clutch.shaft`): crankshaft pinned at
    the two main bearings (span ``layout.bearing_span_m``), rotor lumped as one rigid body
    at its composite centre of mass (overhang = :attr:`Rotor.cg_m`).  The critical speed is the lowest speed at which
    a natural whirl frequency equals the spin: unbalance excites *synchronous forward*
    whirl.  For a body spinning at Omega and whirling forward at omega = Omega the
    gyroscopic moment is ``I_p Omega omega theta``, so the tip moment condition carries
    ``(I_d - I_p) omega^2`` instead of ``I_d omega^2``: the effective rotary inertia is
    ``I_d - I_p`` (negative for disc-like bodies: the gyroscopic effect stiffens and raises
    the critical speed).  ``gyroscopic``: ``"engaged"`` (all parts spin), ``"drum_held"``
    (only the clutch spins: chain brake on) or ``"none"`` (non-spinning natural frequency,
    the most conservative).  The exact determinant root is checked against the FE model.
    """
    L = layout
    finite_param("max_rpm", L.max_rpm, unit="rpm")
    j = rotor.diametral_inertia_kg_m2 - rotor.polar_inertia_kg_m2(gyroscopic)
    shaft = OverhungShaft.round_shaft(diameter_m=L.shaft_diameter_m, E=L.E, rho=L.rho,
                                      span_m=L.bearing_span_m, overhang_m=rotor.cg_m,
                                      tip_mass_kg=rotor.mass_kg, tip_rotary_inertia_kg_m2=j)
    beta1, beta_fe = first_frequency_coefficient(shaft)  # FE-bracketed determinant root
    w = float(shaft.omega(beta1))
    w_fe = float(shaft.omega(beta_fe))
    if abs(w_fe - w) > 1e-4 * w:  # a root missed by either model would show up here
        raise SolverError(f"critical speed: determinant {w:.6g} rad/s and FE {w_fe:.6g} rad/s "
                          f"disagree for {shaft}")
    rpm = rad_s_to_rpm(w)
    return WhirlResult(w, rpm, float(L.max_rpm), rpm / float(L.max_rpm) - 1.0, beta1,
                       rotor.cg_m, rotor.mass_kg, j, gyroscopic, rad_s_to_rpm(w_fe))




# --------------------------------------------------------------------------------------
# The design analysis
# --------------------------------------------------------------------------------------

#: the three gyroscopic readings, in the order of :attr:`WhirlAnswer.readings`
READINGS: tuple[Gyro, ...] = ("engaged", "drum_held", "none")


@dataclass(frozen=True)
class WhirlAnswer:
    """Crankshaft whirl of one design (:func:`whirl`): frozen and self-contained.

    Critical speeds [rpm] (synchronous forward whirl, see :func:`crankshaft_whirl`) for the
    three gyroscopic readings: ``rpm_crit_engaged`` (clutch engaged, all parts spinning),
    ``rpm_crit_drum_held`` (chain brake on: only the clutch spins), ``rpm_crit_no_gyro``
    (natural frequency at rest); ``rpm_crit_lowest`` is the smallest, ``lowest_reading`` its
    reading, ``margin`` = rpm_crit_lowest / max_engine_rpm - 1 (0.25 = 25 % above the
    maximum engine speed; an upper estimate, bearings being rigid).  Clutch mass [kg] and
    inertias [kg m^2] about its centre of mass (I_p about the spin axis, I_d about a
    diameter, the mean of the two in-plane axes, incl. m h^2/12); ``clutch_Ixx_kg_m2`` and
    ``clutch_Iyy_kg_m2`` the two in-plane values (equal for n >= 3 identical shoes).
    ``overhang_m``: the rotor's composite centre of mass from the main bearing (the model
    overhang).  ``rotor`` and ``readings`` keep every part and every
    :class:`WhirlResult`; ``mass_source`` and ``assumptions`` say where the numbers come
    from and what is ASSUMED.
    """

    design: str
    rpm_crit_engaged: float
    rpm_crit_drum_held: float
    rpm_crit_no_gyro: float
    rpm_crit_lowest: float
    lowest_reading: Gyro
    max_engine_rpm: float
    margin: float
    clutch_mass_kg: float
    clutch_polar_inertia_kg_m2: float
    clutch_diametral_inertia_kg_m2: float
    clutch_Ixx_kg_m2: float
    clutch_Iyy_kg_m2: float
    drum_sprocket_mass_kg: float
    drum_sprocket_polar_inertia_kg_m2: float
    rotor_mass_kg: float
    overhang_m: float
    mass_source: str
    assumptions: str
    rotor: Rotor
    readings: tuple[WhirlResult, ...]

    def reading(self, gyroscopic: Gyro) -> WhirlResult:
        """The :class:`WhirlResult` of one gyroscopic reading."""
        for r in self.readings:
            if r.gyroscopic == gyroscopic:
                return r
        raise ParameterError("gyroscopic", gyroscopic, "'engaged', 'drum_held' or 'none'")

    def to_json(self) -> dict:
        """Plain JSON-ready numbers and texts (no rotor, no per-reading objects)."""
        skip = ("rotor", "readings")
        return {k: getattr(self, k) for k in self.__dataclass_fields__ if k not in skip}

    def summary(self) -> str:
        return (f"crankshaft whirl: first critical speed {self.rpm_crit_lowest:,.0f} rpm "
                f"({self.lowest_reading}; engaged {self.rpm_crit_engaged:,.0f}, drum held "
                f"{self.rpm_crit_drum_held:,.0f}, no gyroscopic effect "
                f"{self.rpm_crit_no_gyro:,.0f} rpm), {100 * self.margin:+.0f} % over the "
                f"{self.max_engine_rpm:,.0f} rpm maximum engine speed (upper estimate: rigid "
                "bearings)")


def whirl(design, layout: ChainsawLayout = CHAINSAW_LAYOUT, *,
          max_rpm: float | None = None) -> WhirlAnswer:
    """Crankshaft whirl of a :class:`~clutchfem.loadcase.Design`: its clutch (mass and
    inertia of ``design.cm`` by quadrature, :func:`clutchfem.mesh.mesh_area_properties`; one sector is
    completed by cyclic symmetry; density ``design.model.material.rho``, thickness
    ``design.thickness``) with the ASSUMED drum (on ``design.drum_radius``), sprocket and
    crankshaft of ``layout``, at the three gyroscopic readings (:func:`crankshaft_whirl`).

    ``max_rpm``: the maximum engine speed of the margin (default ``layout.max_rpm``, 15 000
    rpm from seed 000; pass the engine curve's maximum to match an analysis).  A design
    without a drum radius (a user mesh without ``--drum-radius``) is refused: the drum wall
    sits on it.
    """
    if not isinstance(design, Design):
        raise ParameterError("design", type(design).__name__, "a clutchfem.design.Design")
    if design.drum_radius is None:
        raise ParameterError("drum_radius", None, "the drum's inner radius in m (the whirl model puts the "
                             "ASSUMED drum wall on it), e.g. 0.0344", context="crankshaft whirl")
    if max_rpm is not None:
        layout = replace(layout, max_rpm=finite_param("max_rpm", max_rpm, unit="rpm"))
    cm, h = design.cm, float(design.thickness)
    rho = float(design.model.material.rho)
    props = mesh_area_properties(cm)
    sector = cm.sector_angle is not None
    src = (f"{design.name}: quadrature over its mesh"
           + (f" (one sector x {cm.n_shoes_total // cm.n_shoes_model}, cyclic symmetry)" if sector else
              " (full model, actual moments)")
           + f" x rho {rho:g} kg/m^3 x h {1e3 * h:g} mm")
    clutch = clutch_part_from_mass_properties({"solid": props}, h, rho, clutch_axial_position(h, layout),
                                              src)
    cx, cy = props["centroid"]
    a, rh = props["area"], rho * h
    ixx = rh * (props["Ixx_origin"] - a * cy * cy) + clutch.mass_kg * h * h / 12
    iyy = rh * (props["Iyy_origin"] - a * cx * cx) + clutch.mass_kg * h * h / 12
    rotor = chainsaw_rotor(clutch, design.drum_radius, h, layout)
    # the three readings differ only in the disc's rotary inertia: they share the beam model's
    # matrices (cached for this design only, so that every design pays its own)
    clear_beam_cache()
    res = tuple(crankshaft_whirl(rotor, layout, gyroscopic=g) for g in READINGS)
    worst = min(res, key=lambda r: r.rpm_crit)
    ds = [p for p in rotor.parts if p.spins == "drum"]
    L = layout
    aniso = abs(ixx - iyy) / (0.5 * (ixx + iyy))
    text = (f"Clutch mass and inertia from the design's mesh ({src}). Drum and sprocket are ASSUMED "
            f"steel rings (ChainsawLayout: drum wall {1e3 * L.drum_wall_m:g} mm on the drum radius "
            f"{1e3 * design.drum_radius:g} mm, end wall {1e3 * L.drum_end_thickness_m:g} mm, sprocket r "
            f"{1e3 * L.sprocket_r_in_m:g}-{1e3 * L.sprocket_r_out_m:g} mm x {1e3 * L.sprocket_width_m:g} mm; "
            f"{sum(p.mass_kg for p in ds):.3f} kg, I_p {sum(p.polar_inertia_kg_m2 for p in ds):.3g} kg m^2 "
            f"against seed 000's J_b = {1e6 * SEED000_J_B_KG_M2:.1f}e-6 kg m^2), so is the crankshaft "
            f"(d {1e3 * L.shaft_diameter_m:g} mm, rigid pinned main bearings {1e3 * L.bearing_span_m:g} mm "
            f"apart). All parts are lumped at their centre of mass, {1e3 * rotor.cg_m:.1f} mm outboard of the "
            "bearing. Critical speed = synchronous forward whirl, J_eff = I_d - I_p of the spinning parts. "
            f"Maximum engine speed {L.max_rpm:,.0f} rpm. Bearing and crankcase compliance is not modelled "
            "and would lower these speeds: the margin is an upper estimate.")
    if aniso > 1e-3:
        text += (f" The clutch's in-plane inertias differ by {100 * aniso:.1f} %: the axisymmetric whirl "
                 "model uses their mean.")
    by = {r.gyroscopic: r for r in res}
    return WhirlAnswer(
        design=design.name, rpm_crit_engaged=by["engaged"].rpm_crit,
        rpm_crit_drum_held=by["drum_held"].rpm_crit, rpm_crit_no_gyro=by["none"].rpm_crit,
        rpm_crit_lowest=worst.rpm_crit, lowest_reading=worst.gyroscopic, max_engine_rpm=float(L.max_rpm),
        margin=worst.margin, clutch_mass_kg=clutch.mass_kg,
        clutch_polar_inertia_kg_m2=clutch.polar_inertia_kg_m2,
        clutch_diametral_inertia_kg_m2=clutch.diametral_inertia_kg_m2, clutch_Ixx_kg_m2=ixx,
        clutch_Iyy_kg_m2=iyy, drum_sprocket_mass_kg=sum(p.mass_kg for p in ds),
        drum_sprocket_polar_inertia_kg_m2=sum(p.polar_inertia_kg_m2 for p in ds),
        rotor_mass_kg=rotor.mass_kg, overhang_m=rotor.cg_m, mass_source=src, assumptions=text,
        rotor=rotor, readings=res)
