"""The geometric non-linearity of the peak stress, corrected per design (best-estimate path).

With an elastic drum the linear pre-stressed model misses +1.3 to +5.6 % of the peak von
Mises at 14 000 rpm (concepts 1 and 4 and their space-filling designs, BENCHMARKS.md section
13): the drum's contact arc follows the deformed shoe and concentrates towards its tip,
which the small-displacement gap does not see.  A fixed band of that size (the old
:data:`~clutchfem.accuracy.answer_error.GNL_ELASTIC_DRUM` 5.7 %) is larger than the issue's
3 % limit, and its sign is known: it is corrected per design.

Method, at one speed w (the engine's maximum, where the peak is reported):

* s_lin: the peak von Mises (raw P2 vertex values) of the *plane-stress twin* of the design
  (the same mesh, material, drum, friction and softening model, plane stress; where the
  pre-stress Ritz space misses equilibrium, the per-speed ``prestress-exact``, as
  :func:`~clutchfem.analyze` does);
* s_TL: the total-Lagrangian model (:class:`~clutchfem.accuracy.NonlinearModel`: load on the
  deformed position, exact drum circle, the same ring drum's compliance) at w, Newton's method
  started from the twin's linear state with the linearised contact problem solved exactly at
  every step (3-4 iterations; the primal-dual active-set update had needed 16-22 on an
  elastic drum, one contact node leaving per iteration);
* d_NL = s_TL / s_lin - 1, and the design's peak is multiplied by (1 + d_NL).

This is the composition the reference uses (``benchmarks/bench_accuracy.py``: the 3-D answer
times the 2-D ratio), so what stays in the band is what the correction does not know:
:data:`~clutchfem.accuracy.answer_error.CORRECTION_RESIDUAL`, the change of d_NL from the design's mesh to one twice as fine
(its discretisation), measured.  Cost: one plane-stress assembly and factorisation plus 3-4
non-linear iterations, ~0.4-0.8 s on the best mesh (BENCHMARKS.md section 13).
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass

import numpy as np

from ..core import EquilibriumError, SolverError, rpm_to_rad_s
from ..fe import von_mises
from ..loadcase import Design
from .nonlinear import NonlinearModel

__all__ = ["PeakNonlinearity", "peak_nonlinearity"]


@dataclass(frozen=True)
class PeakNonlinearity:
    """The geometric non-linearity of the peak von Mises at one speed (module docstring)."""

    rpm: float
    """the speed [rpm]"""
    linear_Pa: float
    """peak von Mises of the linear pre-stressed plane-stress twin [Pa]"""
    nonlinear_Pa: float
    """peak von Mises of the total-Lagrangian model [Pa]"""
    iterations: int
    """Newton iterations of the total-Lagrangian solve"""
    time_s: float

    @property
    def delta(self) -> float:
        """d_NL = nonlinear / linear - 1."""
        return self.nonlinear_Pa / self.linear_Pa - 1.0

    def as_dict(self) -> dict:
        return {**asdict(self), "delta": self.delta}


def peak_nonlinearity(design: Design, rpm: float) -> PeakNonlinearity:
    """The peak von Mises of ``design``'s plane-stress twin at ``rpm``, linear pre-stressed
    and total-Lagrangian (module docstring).  Raises :class:`~clutchfem.core.SolverError`
    when the non-linear state does not converge (the caller keeps the band instead)."""
    t0 = time.perf_counter()
    op = design.op.replace(formulation="plane-stress")
    twin = Design(design.cm, op, params=design.params, name=design.name)
    try:
        r = twin.sweep([float(rpm)])
    except EquilibriumError:  # the pre-stress Ritz space misses it: per-speed, as analyze does
        twin = twin.with_softening("prestress-exact")
        r = twin.sweep([float(rpm)])
    case = twin.case()
    u = r.fields.displacement(0)
    s_lin = float(np.max(von_mises(twin.model.stress(u))))
    w = rpm_to_rad_s(float(rpm))
    lam, _ = case.solve(w, None)
    nl = NonlinearModel(twin.model, drum_radius=twin.drum_radius, mu=op.mu, rotation=op.rotation,
                        drum_compliance=None if case.contact is None else case.contact.drum_compliance)
    try:
        st = nl.solve(w, u0=u, lam0=lam if case.contact is not None else None)
    except SolverError:
        raise
    except Exception as exc:  # _NoConvergence: the non-linear state was not reached
        raise SolverError(f"geometric non-linearity correction: {exc}") from None
    s_nl = float(np.max(nl.vertex_von_mises(st.u)))
    if not (math.isfinite(s_nl) and s_lin > 0):
        raise SolverError(f"geometric non-linearity correction: peak {s_nl:.4g} / {s_lin:.4g} Pa not usable")
    return PeakNonlinearity(float(rpm), s_lin, s_nl, int(st.iterations), time.perf_counter() - t0)
