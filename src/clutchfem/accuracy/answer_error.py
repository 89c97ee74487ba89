"""The error of every answer: discretisation from two mesh levels, model form from the
measured comparisons (issues 13 and 20), and the sensitivity to the assumed inputs apart.

**Discretisation.**  The answers are computed again on a mesh twice as fine (global size and
the flexure and fillet factors halved, the same parameters and operating point), and the
error of the design mesh's answer is estimated as |a_h - a_h/2| 2^p / (2^p - 1) with p = 1
(Richardson's estimate at the lowest order observed: engagement speed converges at p ~ 1.6,
the peak stress at p ~ 1.5-2, the torque at 8000 rpm at p ~ 0.5-1.6; BENCHMARKS.md), i.e.
twice the change.  The finer level, not a coarser one: a mesh twice as coarse is outside
the asymptotic range for the peak stress at the fillets (concept 4 at 14 000 rpm: 2864 /
2132 / 2177 / 2193 MPa at sizes 2, 1, 1/2, 1/4 of the default), so a coarse level would
report 732 MPa where the error is ~60 MPa.  A user mesh has a single level: not estimated.

**Discretisation of the 3-D model** (``formulation="3d"``, issue 20), two measured terms
summed: *through the thickness*, the same model with one more layer (n + 1; n - 1 at the
largest layer count or past the memory limit), Richardson with p = 1 in the layer thickness
H / n, e_n = |a_n - a_m| n^-p / |m^-p - n^-p| (n + 1 times the change for m = n + 1); *in
plane*, the relative error the thick plane model (the 3-D answer at 2-D cost, on the same
in-plane mesh) shows from a mesh twice as fine, times the 3-D answer: refining the 3-D
model in plane costs ~4x its unknowns (minutes and GB), while the in-plane error is the
2-D mesh's (``benchmarks/bench_3d_error.py`` measures both against 3-D models at two
in-plane sizes and 1-3 layers: BENCHMARKS.md section 13, "3-D path").  Cost: one 3-D model
with n + 1 layers and two thick plane models.

**Model form, best-estimate path** (``fidelity="best"``: the thick plane model, an elastic
ring drum, the pre-stress softening; ``benchmarks/results_accuracy.md``): what remains is
the thick model's own distance from 3-D elasticity (its through-thickness order and the
representation of the free faces, :data:`THICK_RESIDUAL`: the largest deviation from the
3-D reference over the validation set of BENCHMARKS.md, per answer) and the geometric
non-linearity the pre-stress softening leaves (:data:`GNL`).  The drum wall and the friction
coefficient are inputs, not model errors: their sensitivities are reported apart
(``sensitivities``, not in the band).

**Model form, fast path** (plane stress or plane strain; issue 13; each term relative, with
its sign where the measurements give one):

* axial thickness (plane stress vs 3-D): :func:`clutchfem.accuracy.plane_stress_estimate`
  from h / L_f gives the engagement shift dw0/w0 (and its band); the slip speed moves by
  (w0/ws)^2 dw0/w0 (a torque curve ~ (w^2 - w0^2) shifted at engagement: measured 0.5-0.6 %
  for 2.2 % in engagement), the torque at a speed w by -2 (dw0/w0) w0^2 / (w^2 - w0^2), the
  peak stress by +-3 % (3-D vs plane stress measured +2.8 % / -1.8 % on concepts 1 / 4);
  zero for ``--formulation 3d``, the opposite sign for plane strain;
* geometric non-linearity: the ``prestress`` softening is within 0.1 % of the total-Lagrangian
  reference (engagement, normal force) on a rigid drum; with an elastic drum
  (:data:`GNL_ELASTIC_DRUM`) 0.15 / 0.18 / 0.41 / 5.7 % (engagement / slip / torque / peak);
  spin softening alone ('ritz', 'exact') engages 0.6-1.5 %
  early and carries 2-3 % more normal force; no softening ('off') +1.2-1.6 % engagement;
* rigid drum: an elastic 2 mm steel drum wall (ASSUMED typical) lowers the normal force and
  torque by 3.4-3.7 %, raises the slip speed by 1.3-1.4 % and the peak stress by 7-9 %, and
  does not move the engagement speed: a one-sided band unless ``--drum-wall`` models it.

The total band of an answer is the sum of the magnitudes (a bound, not a standard error).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..core import ParameterError
from ..fe import peak_disc
from ..geometry import MeshSettings, get_concept
from ..loadcase import Design, OperatingPoint
from ..mesh import mesh_concept
from .plane_stress import plane_stress_estimate

NOT_ESTIMATED = {False: "discretisation not estimated: a user mesh has one mesh level",
                  True: "in-plane discretisation not estimated: a user mesh has one mesh level (the layers term is)"}
ANSWERS = {"engagement_rpm": "rpm", "slip_rpm": "rpm", "torque_at_max_engine_torque_Nm": "N m",
           "max_von_mises_Pa": "Pa"}
#: Richardson order used for the discretisation estimate (see module docstring)
P_ORDER = 1.0
#: the largest layer count of an operating point
LAYERS_MAX = int(next(m.le for m in OperatingPoint.model_fields["layers"].metadata if hasattr(m, "le")))


@dataclass(frozen=True)
class AnswerError:
    """Error estimate of one answer (absolute, in the answer's unit; model-form terms relative)."""

    quantity: str
    value: float | None
    unit: str
    discretisation: float | None  # absolute, None if not estimated
    model_form: dict = field(default_factory=dict)  # term -> signed relative estimate (band if unsigned)
    notes: tuple = ()
    #: assumed input -> the answer at its low and high value (absolute; not in the band)
    sensitivities: dict = field(default_factory=dict)

    @property
    def model_form_abs(self) -> float:
        if self.value is None:
            return math.nan
        return abs(self.value) * sum(abs(v) for v in self.model_form.values())

    @property
    def total(self) -> float | None:
        if self.value is None:
            return None
        d = self.discretisation or 0.0
        return d + self.model_form_abs

    def to_json(self) -> dict:
        return {"value": self.value, "unit": self.unit, "discretisation": self.discretisation,
                "model_form_relative": dict(self.model_form), "model_form": self.model_form_abs,
                "total": self.total, "notes": list(self.notes), "sensitivities": dict(self.sensitivities)}


def refined_design(design, peak_at: tuple[float, float] | None = None):
    """The same design on a mesh twice as fine (None for a user mesh and for 3-D: its in-plane
    term comes from :func:`thick_twin`'s).  ``peak_at`` [m]: also refine the disc of
    :func:`~clutchfem.fe.peak_disc` around the peak stress there to half its element size
    (the first level of :func:`~clutchfem.fe.peak_stress_converged`: halving the fillet factor
    alone leaves the stress gradient's region unrefined)."""
    if design.params is None or design.op.model_formulation == "3d":
        return None  # a user mesh has one level; a refined 3-D model costs minutes
    ms = MeshSettings(**design.cm.mesh_settings)
    fine = ms.replace(size=max(0.5 * ms.size, 0.05e-3), flexure_factor=max(0.5 * ms.flexure_factor, 0.05),
                      fillet_factor=max(0.5 * ms.fillet_factor, 0.05))
    if peak_at is not None:
        radius, h0 = peak_disc(design.cm, tuple(peak_at), design.params.drum_radius)
        fine = fine.replace(refine_x=float(peak_at[0]), refine_y=float(peak_at[1]), refine_radius=radius,
                            refine_size=max(0.5 * h0, 1e-6))
    cm = mesh_concept(get_concept(design.name), design.params, fine)
    return Design(cm, design.op, params=design.params, name=design.name)


def thick_twin(design):
    """The thick plane model of a 3-D design on the same in-plane mesh (the in-plane term of
    the 3-D discretisation: module docstring)."""
    return Design(design.cm, design.op.replace(formulation="thick"), params=design.params, name=design.name)


def layers_design(design):
    """(the 3-D design with one layer more, or one fewer at the largest count or past the memory
    limit; None for 1 layer that cannot grow)."""
    n = int(design.op.layers)
    for m in (n + 1, n - 1):
        if 1 <= m <= LAYERS_MAX:
            try:
                return Design(design.cm, design.op.replace(layers=m), params=design.params, name=design.name)
            except ParameterError:  # past the memory limit
                continue
    return None


def layers_error(value: float | None, n: int, value_m: float | None, m: int) -> float | None:
    """Error of the answer ``value`` of n layers from that of m layers (Richardson, p =
    :data:`P_ORDER` in the layer thickness): |a_n - a_m| n^-p / |m^-p - n^-p|."""
    if value is None or value_m is None or not math.isfinite(value_m):
        return None
    p = P_ORDER
    return abs(value - value_m) * n ** -p / abs(m ** -p - n ** -p)


def discretisation_3d(design, answers) -> dict:
    """The discretisation of a 3-D design's answers (module docstring): ``answers(design) ->
    {name: value}`` computes them on a design.  Returns {name: (total, layers term, in-plane
    term or None, note)}, absolute."""
    values = answers(design)
    ld = layers_design(design)
    n = int(design.op.layers)
    al = answers(ld) if ld is not None else {}
    tw = thick_twin(design)
    fine = refined_design(tw)
    at, af = (answers(tw), answers(fine)) if fine is not None else ({}, {})
    out = {}
    for q, v in values.items():
        dl = layers_error(v, n, al.get(q), int(ld.op.layers)) if ld is not None else None
        di = None
        if fine is not None and v is not None and at.get(q) and af.get(q) is not None:
            di = abs(v) * discretisation(at[q], af[q]) / abs(at[q])
        parts = [f"layers {n} vs {ld.op.layers}: {dl:.4g}" if dl is not None else "layers not estimated",
                 f"in plane (thick plane model, mesh twice as fine): {di:.4g}" if di is not None else
                 "in plane not estimated (a user mesh has one level)"]
        tot = None if dl is None and di is None else (dl or 0.0) + (di or 0.0)
        out[q] = (tot, dl, di, "3-D discretisation = " + " + ".join(parts))
    return out


#: the thick plane model's relative deviation from 3-D elasticity on the same in-plane mesh
#: (P2 tetrahedra, 3 layers through half the thickness), through-thickness order 4; order 2
#: is 0.3-0.5 % stiffer in engagement.  Measured on concepts 1 and 4 at their defaults
#: (benchmarks/bench_accuracy.py, BENCHMARKS.md section 13: best estimate against the
#: reference within 0.12 % / 0.12 % / 0.43 % in engagement / slip / torque, mesh included)
#: and concepts 2 and 3 in tests/test_thick.py (< 0.1 %).  NOT covered: concept 5, whose
#: beams are stretched, not bent (0.76 % stiff in engagement at 14 mm, a strict xfail in
#: tests/test_thick.py); the space-filling validation set is partly run (section 13).
#: The peak stress: the largest |best estimate - reference| over the designs the band is
#: built from (concepts 1 and 4 at their defaults and their space-filling designs
#: lhs01-lhs04; the reference's peak converged by local refinement at order 6) is 1.45 %
#: (concept 4, the estimate low: order 4 reads 0.7-1.4 % below order 6 at the converged
#: fillet peak, benchmarks/bench_refpeak_orders.py); the other designs are held out to test
#: it (BENCHMARKS.md section 13).
THICK_RESIDUAL = {4: {"engagement_rpm": 0.001, "slip_rpm": 0.001, "torque_at_max_engine_torque_Nm": 0.002,
                      "max_von_mises_Pa": 0.015},
                  2: {"engagement_rpm": 0.006, "slip_rpm": 0.003, "torque_at_max_engine_torque_Nm": 0.006,
                      "max_von_mises_Pa": 0.02}}
#: geometric non-linearity left by each softening model (relative; total-Lagrangian reference,
#: benchmarks/results_modelform.md and results_accuracy.md)
GNL = {"prestress": {"engagement_rpm": 0.001, "slip_rpm": 0.001, "torque_at_max_engine_torque_Nm": 0.001,
                     "max_von_mises_Pa": 0.014},
       "ritz": {"engagement_rpm": -0.015, "slip_rpm": -0.011, "torque_at_max_engine_torque_Nm": 0.033,
                "max_von_mises_Pa": 0.014},
       "exact": {"engagement_rpm": -0.015, "slip_rpm": -0.011, "torque_at_max_engine_torque_Nm": 0.033,
                 "max_von_mises_Pa": 0.014},
       "off": {"engagement_rpm": 0.016, "slip_rpm": 0.01, "torque_at_max_engine_torque_Nm": 0.04,
               "max_von_mises_Pa": 0.02}}
#: geometric non-linearity the ``prestress`` softening leaves *with an elastic drum* (the
#: band's term where the drum is elastic, e.g. the best path): the largest |total-Lagrangian /
#: linear pre-stressed - 1| (2-D plane stress, the same 2 mm ring drum) over the validation
#: designs it was built from -- concepts 1 and 4 at their defaults and their space-filling
#: designs lhs01-lhs04 (9 designs, ``d_nl`` in benchmarks/results_accuracy.jsonl); the
#: designs lhs05-lhs10 were held out to test it (BENCHMARKS.md section 13).  The rigid drum's
#: 0.1 % (GNL) missed the elastic drum's +0.25..+0.46 % in torque and +1.3..+5.6 % in peak
#: stress on concept 4: the drum's contact arc moves with the deformed shoe.
GNL_ELASTIC_DRUM = {"engagement_rpm": 0.0015, "slip_rpm": 0.0018, "torque_at_max_engine_torque_Nm": 0.0041,
                    "max_von_mises_Pa": 0.057}
#: what the per-design correction of the geometric non-linearity
#: (:mod:`~clutchfem.accuracy.gnl_correction`, the best-estimate path) leaves, relative: its
#: discretisation, twice the largest |d_NL(design mesh) - d_NL(the error step's finer mesh)|
#: measured (concepts 1 and 4 at their defaults, concept1-lhs02/05, concept4-lhs02/07 of
#: BENCHMARKS.md section 13): peak stress 0.00040 (d_NL 0.013-0.056), torque 0.00051
#: (d_NL -0.003..+0.005), rounded up.  Not in it: the transfer of the 2-D ratio to the thick
#: model's answer, which the reference makes the same way (benchmarks/bench_accuracy.py)
CORRECTION_RESIDUAL = {"max_von_mises_Pa": 0.001, "torque_at_max_engine_torque_Nm": 0.0012}
#: a rigid drum instead of the elastic 2 mm one (relative; issue 13)
RIGID_DRUM = {"engagement_rpm": 0.0, "slip_rpm": 0.014, "torque_at_max_engine_torque_Nm": -0.037,
              "max_von_mises_Pa": 0.09}


def model_form(design, answer: str, value: float | None, *, w0: float | None = None,
               w: float | None = None, corrected: bool = False) -> tuple[dict, tuple]:
    """Signed relative model-form terms of one answer (see module docstring); ``corrected``:
    the answer's geometric non-linearity was corrected per design
    (:mod:`~clutchfem.accuracy.gnl_correction`), so its term is the correction's residual."""
    terms: dict = {}
    notes = []
    if value is None:
        return terms, ()
    op = design.op
    form = op.model_formulation
    if form == "thick":
        order = 4 if op.thick_order >= 4 else 2
        terms["thickness_3d_residual"] = THICK_RESIDUAL[order][answer]
    elif form in ("plane-stress", "plane-strain"):
        # axial thickness: plane stress / plane strain vs 3-D
        L = getattr(design.params, "flexure_length", None) if design.params is not None else None
        if L:
            est = plane_stress_estimate(design.thickness, float(L), design.model.material.nu)
            d_eng = est.engagement_error if form == "plane-stress" else est.plane_strain_error
            band = est.engagement_band
            if answer == "engagement_rpm":
                terms["thickness_3d"] = d_eng
                terms["thickness_3d_band"] = band
            elif answer == "slip_rpm" and w0 and w:
                terms["thickness_3d"] = (w0 / w) ** 2 * d_eng
            elif answer == "torque_at_max_engine_torque_Nm" and w0 and w and w > w0:
                terms["thickness_3d"] = -2.0 * d_eng * w0 ** 2 / (w ** 2 - w0 ** 2)
            elif answer == "max_von_mises_Pa":
                terms["thickness_3d_band"] = 0.03
        else:
            notes.append("thickness effect not estimated (no flexure length): use the thick plane model "
                         "(--formulation thick, or --fidelity best)")
    # geometric non-linearity
    # (the per-speed references carry their Ritz strategy's model form)
    soft = {"modal": "ritz", "prestress-exact": "prestress"}.get(op.softening, op.softening)
    if corrected:
        terms["geometric_nonlinearity_correction"] = CORRECTION_RESIDUAL[answer]
    else:
        terms["geometric_nonlinearity"] = (GNL_ELASTIC_DRUM[answer] if soft == "prestress" and op.drum_wall_m
                                           else GNL[soft][answer])
    # rigid drum
    if op.drum_wall_m is None and RIGID_DRUM[answer]:
        terms["rigid_drum"] = RIGID_DRUM[answer]
    return terms, tuple(notes)


def extrapolated_peak(a0: float, a1: float) -> tuple[float, float]:
    """(value, error) of a peak stress from its design-mesh value ``a0`` and ``a1`` on the
    refined mesh with the disc at the peak (:func:`refined_design` ``peak_at``): Richardson's
    extrapolation at P2's order 2 of the vertex stress, a1 + (a1 - a0) / 3, and its error
    |a1 - a0| / 3 (the size of the step, i.e. a1's estimated error).  Measured against the
    peak converged over four levels (BENCHMARKS.md section 13, "Converged peaks"): concept 4
    2376.3 against 2371.4 +- 2.6 MPa, concept 1 1039.8 against 1040.9 +- 3.5 MPa: within the
    error (10.3 and 4.9 MPa)."""
    return a1 + (a1 - a0) / 3.0, abs(a1 - a0) / 3.0


def discretisation(value: float | None, value_fine: float | None) -> float | None:
    """|a_h - a_h/2| 2^p / (2^p - 1) (p = :data:`P_ORDER`): the error of ``value`` (mesh h)."""
    if value is None or value_fine is None or not math.isfinite(value_fine):
        return None
    return abs(value - value_fine) * 2 ** P_ORDER / (2 ** P_ORDER - 1)


def format_error(e: AnswerError, scale: float = 1.0, unit: str | None = None, fmt: str = ".0f") -> str:
    """'+- 12 rpm (discretisation 3, model form 9)' for the summary tables."""
    if e is None or e.value is None or e.total is None:
        return ""
    u = unit or e.unit
    d = "n/a" if e.discretisation is None else f"{e.discretisation * scale:{fmt}}"
    return f"+- {e.total * scale:{fmt}} {u} (discretisation {d}, model form {e.model_form_abs * scale:{fmt}})"


def sweep_errors(design, res) -> dict:
    """Errors of a sweep's engagement speed and, at its highest speed, torque and peak stress
    (``clutchfem solve``): the refined mesh solved at that one speed.

    Parameters
    ----------
    design : Design
        The design that was swept.
    res : SweepResult
        Its sweep (``design.sweep(...)``).

    Returns
    -------
    dict
        ``engagement_rpm``, ``torque_Nm`` and ``max_von_mises_Pa`` (those the sweep answers),
        each an error record as in :attr:`Analysis.errors <clutchfem.Analysis>` (``value``,
        ``unit``, ``discretisation``, ``model_form``, ``total``: the band, in the answer's
        unit), and ``at_rpm``: the speed of the torque and stress [rpm].

    Examples
    --------
    >>> import clutchfem as cf
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> e = cf.sweep_errors(d, d.sweep("0:14000:7000"))
    >>> e["at_rpm"], e["engagement_rpm"]["unit"], e["engagement_rpm"]["total"] > 0
    (14000.0, 'rpm', True)
    """
    rpm_top = float(res.rpm.max())
    values = {"engagement_rpm": res.engagement_rpm,
              "torque_Nm": float(res.curve["torque_Nm"].iloc[res.index(rpm_top)]),
              "max_von_mises_Pa": float(res.curve["max_von_mises_Pa"].iloc[res.index(rpm_top)])}
    units = {"engagement_rpm": "rpm", "torque_Nm": "N m", "max_von_mises_Pa": "Pa"}
    keys = {"engagement_rpm": "engagement_rpm", "torque_Nm": "torque_at_max_engine_torque_Nm",
            "max_von_mises_Pa": "max_von_mises_Pa"}
    stresses = not math.isnan(values["max_von_mises_Pa"])

    def answers(d):
        if d is design:
            return values
        fr = d.sweep([rpm_top], stresses=stresses)
        return {"engagement_rpm": fr.engagement_rpm, "torque_Nm": float(fr.curve["torque_Nm"].iloc[0]),
                "max_von_mises_Pa": float(fr.curve["max_von_mises_Pa"].iloc[0])}

    three_d = design.op.model_formulation == "3d"
    fine = refined_design(design)
    fv = answers(fine) if fine is not None else {}
    disc3 = discretisation_3d(design, answers) if three_d else {}
    w0 = res.engagement_rpm
    out = {}
    for q, v in values.items():
        if v is not None and isinstance(v, float) and math.isnan(v):
            continue
        terms, notes = model_form(design, keys[q], v, w0=w0, w=rpm_top)
        d = discretisation(v, fv.get(q)) if fine is not None else None
        if q in disc3:
            d = disc3[q][0]
            notes = notes + (disc3[q][3],)
        elif fine is None:
            notes = notes + (NOT_ESTIMATED[three_d],)
        out[q] = AnswerError(q, v, units[q], d, terms, notes).to_json()
        if q in disc3:
            out[q]["discretisation_layers"], out[q]["discretisation_in_plane"] = disc3[q][1:3]
    out["at_rpm"] = rpm_top
    return out
