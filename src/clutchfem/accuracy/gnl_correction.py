"""The geometric non-linearity of the peak stress and the torque, corrected per design
(best-estimate path).

With an elastic drum the linear pre-stressed model misses +1.3 to +5.6 % of the peak von
Mises at 14 000 rpm and -0.1 to +0.5 % of the torque at 8000 rpm (concepts 1 and 4 and their
space-filling designs, BENCHMARKS.md section 13): the drum's contact arc follows the deformed
shoe and concentrates towards its tip, which the small-displacement gap does not see.  A
fixed band of that size (:data:`~clutchfem.accuracy.answer_error.GNL_ELASTIC_DRUM`: 5.7 % and
0.41 %) is larger than the issue's limits for the peak (3 %), and its sign is known: the
answer is corrected per design instead.

Method, at the answer's speed w (the engine's maximum for the peak, the rpm of its maximum
torque for the torque):

* a_lin: the answer of the *plane-stress twin* of the design (the same mesh, material,
  drum, friction and softening model, plane stress; where the pre-stress Ritz space misses
  equilibrium, the per-speed ``prestress-exact``, as :func:`~clutchfem.analyze` does): the
  friction torque; the raw P2 vertex peak von Mises *in the measure the design reads its
  own peak with*: a thick model's sweep reads the finite-rotation (Cauchy of the
  St. Venant-Kirchhoff law) measure of its linear displacement
  (:class:`~clutchfem.fe.ThickStress`), which already holds part of the non-linearity
  (+2.2 % of the small-strain peak on concept 4), so a_lin is that measure of the twin's
  linear displacement, and only the rest is corrected;
* a_TL: the total-Lagrangian model's (:class:`~clutchfem.accuracy.NonlinearModel`: load on
  the deformed position, exact drum circle, the same ring drum's compliance) at w, Newton's
  method started from the twin's linear state with the linearised contact problem solved
  exactly at every step (3-4 iterations; the primal-dual active-set update had needed 16-22
  on an elastic drum, one contact node leaving per iteration);
* d_NL = a_TL / a_lin - 1, and the design's answer is multiplied by (1 + d_NL).

This is the composition the reference uses (``benchmarks/bench_accuracy.py``: the 3-D answer
times the 2-D ratio), so what stays in the band is what the correction does not know:
:data:`~clutchfem.accuracy.answer_error.CORRECTION_RESIDUAL`, d_NL's change from the design's
mesh to the error step's finer one (its discretisation), measured.  Cost: one plane-stress
assembly and the twin's linear states, plus 3-4 non-linear iterations a speed (BENCHMARKS.md
section 13).
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass

import numpy as np

from ..core import EquilibriumError, SolverError, rpm_to_rad_s
from ..fe import von_mises
from ..loadcase import Design
from .nonlinear import NonlinearModel, NonlinearSettings

__all__ = ["AnswerNonlinearity", "answer_nonlinearity"]

#: Newton's tolerances for the correction: 1e-6 of the displacement and 1e-5 of the load
#: (the reference's are 1e-10 / 1e-7): d_NL is then within ~1e-7 of the reference's
#: (tests/test_peak_correction.py), two to three iterations instead of four
SETTINGS = NonlinearSettings(tol=1e-6, res_tol=1e-5)
#: the twin's pre-stress Ritz residual from which its linear states are solved per speed
#: (as analysis.strength.PEAK_RESIDUAL_EXACT)
TWIN_RESIDUAL_EXACT = 5e-4


@dataclass(frozen=True)
class AnswerNonlinearity:
    """The geometric non-linearity of one answer at one speed (module docstring)."""

    quantity: str
    """the answer's key in ``Analysis.errors``"""
    rpm: float
    """the speed [rpm]"""
    linear: float
    """the linear pre-stressed plane-stress twin's value (the answer's unit)"""
    nonlinear: float
    """the total-Lagrangian model's value"""
    unit: str
    iterations: int
    """Newton iterations of the total-Lagrangian solve"""
    time_s: float

    @property
    def delta(self) -> float:
        """d_NL = nonlinear / linear - 1."""
        return self.nonlinear / self.linear - 1.0

    def to_json(self) -> dict:
        return {**asdict(self), "delta": self.delta}


def answer_nonlinearity(design: Design, peak_rpm: float,
                        torque_rpm: float | None = None) -> dict[str, AnswerNonlinearity]:
    """The geometric non-linearity of ``design``'s peak von Mises at ``peak_rpm`` and, if
    given, of its friction torque at ``torque_rpm`` [rpm] (module docstring), keyed by the
    answers' names (``max_von_mises_Pa``, ``torque_at_max_engine_torque_Nm``).  Raises
    :class:`~clutchfem.core.SolverError` when a non-linear state does not converge or an
    answer is not usable (no contact at ``torque_rpm``): the caller keeps the band instead."""
    finite = bool(getattr(design.model.stress, "FINITE", False))
    op = design.op.replace(formulation="plane-stress")
    twin = Design(design.cm, op, params=design.params, name=design.name)
    speeds = sorted({float(peak_rpm)} | ({float(torque_rpm)} if torque_rpm is not None else set()))
    try:  # (no stress table: the peak is read below, in the measure the design uses)
        res = twin.sweep(speeds, stresses=False)
        # a pre-stress Ritz residual spoils a_lin's peak (its error is local: up to ~15x the
        # residual, analysis.strength.peak_sweep), which d_NL would take for non-linearity
        exact = op.softening == "prestress" and float(res.curve["residual"].max()) >= TWIN_RESIDUAL_EXACT
    except EquilibriumError:  # the pre-stress Ritz space misses it: per-speed, as analyze does
        exact = True
    if exact:
        twin = twin.with_softening("prestress-exact")
        res = twin.sweep(speeds, stresses=False)
    case = twin.case()
    if case.contact is None:
        raise SolverError("geometric non-linearity correction: the design has no contact nodes")
    nl = NonlinearModel(twin.model, drum_radius=twin.drum_radius, mu=op.mu, rotation=op.rotation,
                        drum_compliance=case.contact.drum_compliance, settings=SETTINGS)
    out = {}
    for rpm in speeds:
        t1 = time.perf_counter()
        u = res.fields.displacement(res.index(rpm))
        w = rpm_to_rad_s(rpm)
        lam, _ = case.solve(w, None)
        try:
            st = nl.solve(w, u0=u, lam0=lam)
        except SolverError as exc:  # the non-linear state was not reached
            raise SolverError(f"geometric non-linearity correction at {rpm:.0f} rpm: {exc}") from None
        if rpm == float(peak_rpm):
            # the linear peak in the measure the design reads its own peak with: a thick
            # model's sweep reads the finite-rotation measure of its linear displacement
            # (ThickStress.FINITE), which holds part of the non-linearity already
            lin = float(np.max(nl.vertex_von_mises(u) if finite else von_mises(twin.model.stress(u))))
            val = float(np.max(nl.vertex_von_mises(st.u)))
            out["max_von_mises_Pa"] = AnswerNonlinearity("max_von_mises_Pa", rpm, lin, val, "Pa", int(st.iterations),
                                                         time.perf_counter() - t1)
        if torque_rpm is not None and rpm == float(torque_rpm):
            lin, val = float(case.friction_torque(lam)), nl.torque(st)
            if lin > 0 and val > 0:  # else the twin is not in contact there: no torque to correct
                out["torque_at_max_engine_torque_Nm"] = AnswerNonlinearity(
                    "torque_at_max_engine_torque_Nm", rpm, lin, val, "N m", int(st.iterations),
                    time.perf_counter() - t1)
    a = out["max_von_mises_Pa"]
    if not (math.isfinite(a.nonlinear) and a.linear > 0):
        raise SolverError(f"geometric non-linearity correction: peak von Mises {a.nonlinear:.4g} Pa against "
                          f"{a.linear:.4g} Pa (linear) at {a.rpm:.0f} rpm is not usable")
    return out
