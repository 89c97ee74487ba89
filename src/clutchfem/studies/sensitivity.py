"""Design sensitivities: the derivative of every main answer with respect to the concept's
parameters, by central differences on meshes morphed from the design's own mesh.

Method (issue 21).  The design is the morph reference (:mod:`clutchfem.mesh.morph`); for each
parameter x_i the designs x_i +- h_i are evaluated on the study engine with their meshes
*morphed* from the design's, so both share its mesh connectivity and the difference

    dA/dx_i ~ (A(x + h_i e_i) - A(x - h_i e_i)) / (2 h_i)            (central, O(h^2))

carries no remeshing noise.  Where a rule of the concept refuses one side, the one-sided
difference against the design itself is used (O(h), said in ``method``); where a morph is
refused (the curves change, or the elements would be too distorted) that side was meshed
from scratch and the derivative carries remeshing noise (said in ``method`` and ``notes``).

Step h_i: lengths 0.01 mm (1e-5 m; exact as a ``--set`` text, :mod:`.values`), angles 0.01
deg, dimensionless values 1e-3 of the value (at least 1e-6).  Measured over h = 1e-3 ..
1e-1 mm on concept 4 (``benchmarks/bench_sensitivity.py``, BENCHMARKS.md, "Robust design"):
on morphed meshes the engagement and mass derivatives scatter by 0-0.15 %, the peak stress's
by 0.02-7 % (remeshed: 6-120 %); slip speed (0.1-0.9 %) and torque (1.5-3 %) scatter as much
as on remeshed designs -- their extraction has steps of its own (the slip root's tolerance,
the contact set), which morphing does not remove.

Answers (SI units): engagement speed, engagement with ripple, slip speed [rpm], torque at the
engine's maximum torque [N m], peak von Mises stress at the engine's maximum speed [Pa], its
safety factor against yield [-], fatigue safety factor [-], part mass [kg].  Operating inputs (mu, drum, material) are not
parameters of the morphed mesh: they are not differentiated here.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from ..core import ParameterError
from ..loadcase import Design
from . import values as V
from .batch import EvalSettings, cluster, evaluate_many

#: (row key, unit) of the differentiated answers
ANSWERS: tuple[tuple[str, str], ...] = (
    ("engagement_rpm", "rpm"), ("engagement_rpm_with_ripple", "rpm"), ("slip_rpm", "rpm"),
    ("torque_at_max_engine_torque_Nm", "N m"), ("max_von_mises_Pa", "Pa"), ("safety_factor", "-"),
    ("fatigue_safety_factor", "-"),
    ("mass_kg", "kg"))
#: finite-difference step per parameter unit (module docstring); dimensionless: relative
STEP = {"m": 1e-5, "deg": 0.01}
REL_STEP = 1e-3


@dataclass
class Sensitivities:
    """What :func:`sensitivities` returns: the answers at the design (``base``), and per
    parameter its value, step, unit, derivative of every answer [answer unit / parameter
    unit, SI] and the method used (``central, morphed`` where both sides were morphed)."""

    concept: str
    base: dict
    values: dict
    steps: dict
    units: dict
    derivatives: dict
    methods: dict
    notes: list = field(default_factory=list)

    def elasticity(self, name: str, answer: str) -> float | None:
        """(x / A) dA/dx: the % change of ``answer`` per % change of parameter ``name``."""
        d = self.derivatives.get(name, {}).get(answer)
        a = self.base.get(answer)
        if d is None or not a:
            return None
        return d * self.values[name] / a

    def table(self) -> str:
        """A text table: derivatives per parameter (per mm, per deg or per unit of the value)."""
        head = "parameter".ljust(22) + "".join(k.replace("_with_ripple", "+ripple")[:18].rjust(20) for k, _ in ANSWERS)
        lines = [head, "".ljust(22) + "".join(f"[{u}/unit]".rjust(20) for _, u in ANSWERS)]
        for n, der in self.derivatives.items():
            scale, unit = {"m": (1e-3, "mm"), "deg": (1.0, "deg")}.get(self.units[n], (1.0, "-"))
            cells = "".join(("-" if der.get(k) is None else f"{der[k] * scale:.5g}").rjust(20) for k, _ in ANSWERS)
            lines.append(f"{n} /{unit}".ljust(22) + cells + f"   ({self.methods[n]})")
        return "\n".join(lines)

    def as_json(self) -> dict:
        return dataclasses.asdict(self)


def step_for(P, name: str, value: float) -> float:
    """The finite-difference step of parameter ``name`` at ``value`` (module docstring)."""
    unit = P.unit(name)
    if unit in STEP:
        return STEP[unit]
    return max(abs(value) * REL_STEP, 1e-6)


def sensitivities(design, names: list[str] | None = None, *, engine=None, requirements=None,
                  workers: int | None = None, morph: bool = True, steps: dict | None = None) -> Sensitivities:
    """Derivatives of the main answers of ``design`` with respect to its concept parameters.

    Parameters
    ----------
    design : Design or EvalSettings
        A concept's design (``Design.from_concept``) or the study settings of one: the point
        of the derivatives and the morph reference.
    names : list of str, optional
        Parameters to differentiate (default: every real-valued parameter of the concept but
        the drum radius, the axial thickness and the table profile's clearances).
    engine, requirements : optional
        The engine curve and requirement factors of the answers (defaults as ``analyze``).
    workers : int, optional
        Study engine workers (None: one per core; 0: this process).
    morph : bool
        Morph the meshes (default).  False meshes every design from scratch: for measuring
        what morphing buys (the derivatives then carry remeshing noise).
    steps : dict, optional
        name -> finite-difference step in SI units (default: :func:`step_for`).

    Returns
    -------
    Sensitivities
        ``derivatives[name][answer]`` in SI units, ``elasticity(name, answer)``, ``table()``.

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> s = cf.sensitivities(d, ["flexure_thickness"], workers=0)
    >>> s.methods["flexure_thickness"]
    'central, morphed'
    >>> s.derivatives["flexure_thickness"]["engagement_rpm"] > 0    # rpm per m: stiffer beam
    True
    """
    if isinstance(design, EvalSettings):
        es, p0, label = design, design.params(), design.concept
    elif isinstance(design, Design) and design.params is not None:
        es = EvalSettings.from_design(design, engine=engine, requirements=requirements)
        p0, label = design.params, design.name
    else:
        raise ParameterError("design", type(design).__name__, "a concept's Design (Design.from_concept): a user "
                             "mesh has no parameters to differentiate")
    P = type(p0)
    floats = [n for n, f in P.model_fields.items() if f.annotation is float and not n.startswith("table_c")
              and n not in ("drum_radius", "thickness")]
    names = list(floats if names is None else names)
    for n in names:
        if n not in floats:
            raise ParameterError(n, None, "a real-valued parameter of the concept: " + ", ".join(floats), label)
    if morph:
        es = dataclasses.replace(es, morph=tuple(sorted(es.values().items())))
    points: list[dict] = [{}]
    plan = []
    for n in names:
        x = float(getattr(p0, n))
        h = float((steps or {}).get(n) or step_for(P, n, x))
        if not h > 0:
            raise ParameterError(f"steps[{n}]", h, "a positive step in SI units", label)
        lo, hi = V.round12(x - h), V.round12(x + h)
        plan.append((n, x, h, len(points), len(points) + 1))
        points += [{n: V.exact_text(P, n, lo)}, {n: V.exact_text(P, n, hi)}]
    with cluster(workers):
        rows = evaluate_many(points, es)
    base = rows[0]
    if base["status"] != "ok":
        raise ParameterError("design", label, f"a design the analysis can evaluate ({base['message']})")
    out = Sensitivities(concept=es.concept, base={k: base.get(k) for k, _ in ANSWERS}, values={}, steps={},
                        units={}, derivatives={}, methods={})
    for n, x, h, im, ip in plan:
        rm, rp = rows[im], rows[ip]
        ok_m, ok_p = rm["status"] == "ok", rp["status"] == "ok"
        pairs = ((rm, rp, 2 * h, "central") if ok_m and ok_p else (base, rp, h, "one-sided (+)") if ok_p
                 else (rm, base, h, "one-sided (-)") if ok_m else None)
        out.values[n], out.steps[n], out.units[n] = x, h, P.unit(n)
        if pairs is None:
            out.derivatives[n] = {k: None for k, _ in ANSWERS}
            out.methods[n] = "not evaluated: " + (rm.get("message") or rp.get("message") or "")
            continue
        a, b, dx, how = pairs
        used = [r for r in (a, b) if r is not base]
        morphed = all(r.get("mesh_morphed") == 1 for r in used) if morph else False
        out.methods[n] = f"{how}, " + ("morphed" if morphed else "meshed from scratch")
        if morph and not morphed:
            out.notes.append(f"{n}: " + "; ".join(r.get("morph_note") or "" for r in used))
        out.derivatives[n] = {k: _diff(a.get(k), b.get(k), dx) for k, _ in ANSWERS}
    return out


def _diff(a, b, dx: float) -> float | None:
    if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)):
        return None
    return (b - a) / dx
