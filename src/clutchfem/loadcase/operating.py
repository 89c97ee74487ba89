"""The operating point of an analysis: one typed parameter set for the CLI, ``analyze`` and
the solver alike.

Drum radius, friction coefficient, sense of rotation, axial thickness, material, spin
softening, formulation (plane stress, plane strain, the thick plane model, 3-D with its
layers), the drum's elasticity (rigid, or a ring wall, held or spinning) and the speeds: one
default, one range and one error message for each (:mod:`clutchfem.core.params`).  ``None``
for the drum radius and the thickness means "the concept's value" (a user mesh has no drum:
its radius must be given).

**Fidelity** (issue 20).  ``best`` (default) answers for the real part: the thick plane
model (:class:`clutchfem.fe.FEModelThick`: the 3-D thickness effect of each design), an
elastic drum (a 2 mm steel wall, ASSUMED: a pressed cup of a 60 cc saw; its sensitivity is
reported apart), the pre-stress softening, the mesh of
:meth:`clutchfem.geometry.MeshSettings.preset` ``("best")`` and, with the error estimate,
the peak stress and torque corrected for geometric non-linearity and the peak for its
discretisation.  Against the 3-D non-linear elastic-drum reference it meets 0.5 % on
engagement and slip, 1 % on torque and 3 % on the peak stress, with bands that hold the
reference (BENCHMARKS.md section 13, 26 designs).  ``fast`` keeps the uncorrected 2-D path
(plane stress, rigid drum, the uniform 1.2 mm mesh), with its larger model-form band (~3 %
on engagement, ~18 % on the peak stress), at about half the cost: for sweeps that want it.
The environment variable ``CLUTCHFEM_FIDELITY`` (``best`` or ``fast``) sets the default of
a session (the test suite runs its machinery tests on ``fast``; the tests of the best path
ask for it).  ``formulation="auto"`` and ``drum_wall=None`` follow the fidelity; an explicit
formulation or drum wall (``"rigid"``) overrides it.

The friction coefficient mu = 0.165 is seed 000's value for the spring clutch's shoe lining
on the drum (steel on steel here is similar; ASSUMED the same).
"""

from __future__ import annotations

import math
from typing import ClassVar, Literal

import numpy as np
from pydantic import field_validator

from ..core import InputError, Material, ParameterError, ParamSet, choice, default_fidelity, get_material, param

#: speeds above this are refused: no clutch survives them (and a mix-up of rad/s and rpm in
#: a list is caught)
MAX_RPM = 1.0e6
#: more speeds than this in one sweep are refused (memory and run time grow with them)
MAX_SPEEDS = 20000
#: the drum wall of the best-estimate path [m] (ASSUMED: a pressed steel cup of a 60 cc saw)
BEST_DRUM_WALL = 2.0e-3
#: what each fidelity means when formulation is "auto" and drum_wall is None
FIDELITY = {"best": {"formulation": "thick", "drum_wall": BEST_DRUM_WALL},
            "fast": {"formulation": "plane-stress", "drum_wall": None}}
#: live answers come from the reduced model of the best path (clutchfem.reduced): its FE
#: model, where one is needed (a fallback, a field), is the best path's
FIDELITY["live"] = FIDELITY["best"]


class OperatingPoint(ParamSet):
    """Operating point and model choices of one analysis (see module docstring).

    Parameters
    ----------
    drum_radius : float or str, optional
        Drum inner radius (default: the concept's; required for a user mesh).
    mu : float
        Shoe-drum friction coefficient (seed 000: 0.165).
    rotation : {"ccw", "cw"}
        The hub's sense of rotation (drum held).
    thickness : float or str, optional
        Axial thickness (default: the concept's; user mesh 11 mm, ASSUMED).
    material : Material or str
        ``"51CrV4"`` (default), ``"titanium"``, ``"aluminium"`` or a :class:`Material`.
    softening : {"prestress", "ritz", "exact", "off", "prestress-exact"}
        Spin softening and pre-stress stiffening (default prestress; prestress-exact: its
        per-speed reference, which ``analyze`` falls back to where prestress misses
        equilibrium).
    fidelity : {"best", "fast", "live"}
        ``best`` (default; ``CLUTCHFEM_FIDELITY`` sets another): the best estimate of the real
        part; ``fast``: the uncorrected 2-D path (module docstring); ``live``: the best path's
        answers from its reduced model (:mod:`clutchfem.reduced`): no mesh, milliseconds, its
        own measured error in every band.
    formulation : {"auto", "plane-stress", "plane-strain", "thick", "3d"}
        The elastic model (auto: the fidelity's); ``layers``: 3-D element layers through half
        the thickness; ``thick_order``: the thick model's through-thickness order.
    drum_wall : float or str, optional
        Elastic drum of this wall thickness, or ``"rigid"`` (default: the fidelity's, 2 mm
        for best, rigid for fast); ``drum_state``: held or spinning.
    contact_smoothing : float or str
        Gap scale of the smoothed contact law (:func:`clutchfem.contact.smooth_lcp`); 0
        (default): exact contact.  For studies of how smooth the answers are in the design
        (``benchmarks/bench_derivative_smoothness.py``).
    rpm : str, optional
        Speeds to tabulate (``"0:14000:250"``).

    Examples
    --------
    >>> import clutchfem as cf
    >>> op = cf.OperatingPoint(mu=0.2, drum_wall="2mm", rotation="cw")
    >>> op.mu, op.drum_wall, op.material.name
    (0.2, 0.002, '51CrV4 (SS 2230) spring steel, hardened ~45 HRC')
    >>> cf.OperatingPoint(fidelity="fast").model_formulation, cf.OperatingPoint(fidelity="best").drum_wall_m
    ('plane-stress', 0.002)
    """

    context: ClassVar[str] = "operating point"

    drum_radius: float | None = param(None, "m", 1e-3, 2.0,
                                      "drum inner radius (default: the concept's; required for a user mesh)")
    mu: float = param(0.165, "-", 0.0, 1.0, "shoe-drum friction coefficient (seed 000: 0.165)")
    rotation: Literal["ccw", "cw"] = choice("ccw", "hub's sense of rotation (drum held)")
    thickness: float | None = param(None, "m", 0.5e-3, 0.2,
                                    "axial thickness of the part (default: the concept's; user mesh 11 mm)")
    material: Material = get_material("51CrV4")
    softening: Literal["ritz", "modal", "exact", "off", "prestress", "prestress-exact"] = choice(
        "prestress", "spin softening and stiffening: prestress (default: mode acceleration on Ritz pairs with "
        "the spin softening and the centrifugal pre-stress stiffness of the flexures, 0.1 % from the "
        "geometrically non-linear reference), ritz (spin softening only, alias modal: 1.3-3 % model-form "
        "error), exact (per-speed reference of ritz), prestress-exact (per-speed reference of prestress; analyze "
        "falls back to it where prestress misses equilibrium), off")
    fidelity: Literal["best", "fast", "live"] = choice(
        "best", "best: the best estimate of the real part (thick plane model, elastic 2 mm drum ASSUMED, pre-stress, "
        "mesh refined at flexures, fillets and contact); fast: the uncorrected 2-D path (plane stress, rigid drum, "
        "uniform 1.2 mm mesh) with its larger model-form band; live: the best path's answers from its reduced "
        "model of the design's region (milliseconds, no mesh; its own measured error added to the band)")
    formulation: Literal["auto", "plane-stress", "plane-strain", "thick", "3d"] = choice(
        "auto", "formulation: auto (the fidelity's: thick for best, plane-stress for fast), plane-stress (thin "
        "part), plane-strain (long part), thick (the 2-D mesh with polynomial through-thickness modes: the 3-D "
        "answer of the extruded part to ~0.05 %) or 3d (the 2-D mesh extruded through the thickness, P2 tetrahedra)")
    layers: int = param(2, "-", 1, 16, "3d: element layers through half the thickness (mid-plane symmetry)")
    thick_order: int = param(4, "-", 2, 8, "thick: highest even power of z in the in-plane displacement "
                             "(2: Saint-Venant bending; 4: with the end restraint)")
    drum_wall: float | None = param(None, "m", 0.0, 30e-3,
                                    "elastic drum: wall thickness, or rigid (0) (default: the fidelity's: 2 mm "
                                    "ASSUMED for best, rigid for fast); a ring of width 14 mm ASSUMED, the part's "
                                    "material")
    drum_state: Literal["held", "spinning"] = choice(
        "held", "elastic drum: held (idle, chain brake, slip) or spinning with the clutch (its centrifugal "
        "expansion opens the gap)")
    contact_smoothing: float = param(0.0, "m", 0.0, 2e-5,
                                     "gap scale of a smoothed contact law (0, default: exact contact); measured on "
                                     "concept 4: 1 um moves slip and torque by < 1e-4, 10 um torque by 0.5 %")
    rpm: str | None = param(None, "rpm", None, None,
                            "speeds: 8000 | 1000,2000 | start:stop:step (default: 0..engine max for "
                            "analyze, 0:14000:250 for solve)")

    def __init__(self, **values):
        if values.get("fidelity") is None:
            values["fidelity"] = default_fidelity()
        if isinstance(values.get("drum_wall"), str) and values["drum_wall"].strip().lower() == "rigid":
            values["drum_wall"] = 0.0
        super().__init__(**values)

    def check(self) -> None:
        if self.drum_wall is not None and 0.0 < self.drum_wall < 0.2e-3:
            self.fail("drum_wall", "rigid (0) or a wall of 0.2 mm to 30 mm")

    @property
    def model_formulation(self) -> str:
        """The formulation used: the given one, or the fidelity's for ``"auto"``."""
        return FIDELITY[self.fidelity]["formulation"] if self.formulation == "auto" else self.formulation

    @property
    def drum_wall_m(self) -> float | None:
        """The elastic drum's wall [m] used, None for a rigid drum (``drum_wall`` None: the
        fidelity's; 0: rigid)."""
        w = FIDELITY[self.fidelity]["drum_wall"] if self.drum_wall is None else self.drum_wall
        return None if not w else float(w)

    @field_validator("material", mode="before")
    @classmethod
    def _material(cls, v):
        if isinstance(v, str):
            return get_material(v)
        return v

    @field_validator("rpm", mode="before")
    @classmethod
    def _rpm(cls, v):
        if v is None or isinstance(v, str):
            if v is not None:
                parse_rpm(v)  # refuse a bad spec now, naming it
            return v
        parse_rpm(v)
        return ",".join(f"{x:.12g}" for x in np.atleast_1d(np.asarray(v, dtype=float)))

    def speeds(self, default: str = "0:14000:250") -> np.ndarray:
        """The speeds [rpm] (``default`` when none were given)."""
        return parse_rpm(self.rpm if self.rpm is not None else default)

    @classmethod
    def help(cls, name: str) -> str:
        """CLI help text of a field: meaning, unit, allowed values and default."""
        f = cls.model_fields[name]
        d = f.default
        if isinstance(d, Material):
            d = "51CrV4"
        unit = cls.unit(name)
        allowed = cls.allowed(name) if name != "material" else "51CrV4, titanium, aluminium"
        dflt = "the concept's" if d is None and name in ("drum_radius", "thickness") else d
        return f"{f.description} ({unit}; {allowed}; default {dflt})".replace("(-; ", "(")


def parse_rpm(spec) -> np.ndarray:
    """rpm values from a number, a list/array, or a string '8000', '1000,2000', '0:14000:250'
    (start:stop:step, stop included).  Refuses (InputError naming the spec): an empty list,
    non-finite or negative speeds, speeds above MAX_RPM, more than MAX_SPEEDS speeds.

    Parameters
    ----------
    spec : float, sequence of float or str
        Speeds [rpm]: ``8000``, ``[1000, 2000]``, ``"1000,2000"`` or ``"start:stop:step"``.

    Returns
    -------
    numpy.ndarray
        The speeds [rpm] in the order given.

    Examples
    --------
    >>> import clutchfem as cf
    >>> cf.parse_rpm("0:14000:3500").tolist(), cf.parse_rpm("8000, 9000").tolist(), cf.parse_rpm(2700).tolist()
    ([0.0, 3500.0, 7000.0, 10500.0, 14000.0], [8000.0, 9000.0], [2700.0])
    >>> cf.parse_rpm("-100")
    Traceback (most recent call last):
    ...
    clutchfem.core.errors.InputError: rpm spec '-100': speeds must be finite and >= 0 rpm
    """
    if isinstance(spec, bool):
        raise InputError(f"rpm spec {spec!r} is not understood: use 8000, 1000,2000,3000 or 0:14000:250 (rpm)")
    if isinstance(spec, str):
        s = spec.strip()
        try:
            if ":" in s:
                parts = [float(x) for x in s.split(":")]
                if len(parts) != 3:
                    raise ValueError
                a, b, step = parts
                if not all(math.isfinite(x) for x in parts):
                    raise InputError(f"rpm spec '{spec}': start, stop and step must be finite numbers (rpm)")
                if step <= 0 or b < a:
                    raise InputError(f"rpm spec '{spec}': need start <= stop and step > 0 "
                                     "(form start:stop:step, e.g. 0:14000:250)")
                n = int(math.floor((b - a) / step + 1e-9)) + 1
                if n > MAX_SPEEDS:
                    raise InputError(f"rpm spec '{spec}' gives {n} speeds; at most {MAX_SPEEDS} are allowed "
                                     "(use a larger step: answers such as the slip speed do not depend on it)")
                vals = a + step * np.arange(n)
            else:
                vals = np.array([float(x) for x in s.split(",") if x.strip()])
        except InputError:
            raise
        except ValueError:
            raise InputError(f"rpm spec '{spec}' is not understood: use 8000, 1000,2000,3000 or "
                             "0:14000:250 (rpm)") from None
    else:
        try:
            vals = np.atleast_1d(np.asarray(spec, dtype=float)).ravel()
        except (TypeError, ValueError):
            raise InputError(f"rpm spec {spec!r} is not understood: give numbers in rpm") from None
    if vals.size == 0:
        raise InputError(f"rpm spec '{spec}' gives no speed")
    if vals.size > MAX_SPEEDS:
        raise InputError(f"rpm spec gives {vals.size} speeds; at most {MAX_SPEEDS} are allowed")
    if not np.all(np.isfinite(vals)) or np.any(vals < 0):
        raise InputError(f"rpm spec '{spec}': speeds must be finite and >= 0 rpm")
    if vals.max() > MAX_RPM:
        raise InputError(f"rpm spec '{spec}': speeds above {MAX_RPM:g} rpm are not physical here "
                         "(is it in rad/s or rpm?)")
    return vals


def check_rpm_range(rpm: np.ndarray, lo: float, hi: float, why: str) -> None:
    """Refuse speeds outside [lo, hi] rpm, naming ``why`` the range is what it is."""
    if rpm.min() < lo or rpm.max() > hi:
        raise ParameterError("rpm", f"{rpm.min():g}..{rpm.max():g}", f"speeds within {lo:g}..{hi:g} rpm ({why})")
