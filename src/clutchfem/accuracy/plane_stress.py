"""Model-form error estimates: how far the fast 2-D answers are from the 3-D / non-linear
references, as measured in ``benchmarks/bench_modelform.py`` (issue 13).

Plane stress vs 3-D
-------------------
A flexure bent in its plane behaves as plane stress (modulus E) in its Saint-Venant interior
(the anticlastic curvature across its axial width h is free) but as plane strain
(E / (1 - nu^2)) within about one width h of its clamped ends, where the thick hub and shoe
hold the transverse strain.  So the 3-D answer lies a fraction chi of the way from plane
stress to plane strain, and chi grows with h / L_f (axial thickness over flexure length),
not with h / t_f: measured on a clamped flexure (L = 19 mm, t = 1.75 mm, P2, 3-D converged
in layers) the tip compliance gives

    h / L_f : 0.053  0.105  0.21   0.42   0.58   0.84   1.26
    chi     : 0.036  0.065  0.142  0.310  0.419  0.551  0.682

(``FLEXURE_CHI``; beyond 1.26 continued as 1 - (1 - 0.682) exp(-0.9 (x - 1.26))).  The
engagement speed goes as sqrt(stiffness) and the stiffness ratio plane strain / plane stress
of a bent beam is 1 / (1 - nu^2), so

    w_3D / w_PS - 1 ~ chi (1 / sqrt(1 - nu^2) - 1)     (4.83 % x chi for nu = 0.3).

Checked against the concepts (default 11 mm): concept 4 (h / L_f = 0.58) measured chi =
0.47 (estimate 0.42), concept 1 (0.69) measured 0.34 (estimate 0.47): the estimate carries
+-0.13 in chi, i.e. +-0.6 % in engagement speed, and is a check, not a replacement for
``--formulation 3d``.  Above engagement the normal force error follows from the shifted
engagement speed: dN / N ~ -2 (dw0 / w0) w0^2 / (w^2 - w0^2).

Geometric non-linearity
-----------------------
The centrifugal pre-stress stiffens the flexures: the non-linear reference engages 0.6 %
(concept 1) and 1.5 % (concept 4) above the linear spin-softened fast path and carries 2-3 %
less normal force at 8000 rpm; the ``prestress`` softening strategy recovers it to 0.1 % at
the cost of plain spin softening, so it needs no estimate: use it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core import ParameterError

__all__ = ["FLEXURE_CHI", "PlaneStressEstimate", "plane_stress_estimate"]

#: (h / L_f, chi) measured on a clamped flexure, see module docstring
FLEXURE_CHI = np.array([[0.0, 0.0], [0.0526, 0.0359], [0.1053, 0.0649], [0.2105, 0.1415],
                        [0.4211, 0.3097], [0.5789, 0.4192], [0.8421, 0.5512], [1.263, 0.6815]])
#: uncertainty of chi from the flexure table when applied to whole concepts (measured)
CHI_UNCERTAINTY = 0.13


@dataclass(frozen=True)
class PlaneStressEstimate:
    """Estimated model-form error of a plane-stress answer (see module docstring)."""

    h_over_L: float
    chi: float
    engagement_error: float  # w_PS / w_3D - 1 (negative: plane stress engages too early)
    engagement_band: float  # +- on engagement_error from CHI_UNCERTAINTY
    plane_strain_error: float  # w_PE / w_3D - 1

    @property
    def note(self) -> str:
        return (f"plane stress engages {-self.engagement_error:.1%} (+-{self.engagement_band:.1%}) below a 3-D model, "
                f"plane strain {self.plane_strain_error:.1%} above (h/L_f = {self.h_over_L:.2f}, chi = {self.chi:.2f}); "
                "use --formulation 3d where this matters")


def plane_stress_estimate(thickness: float, flexure_length: float, nu: float = 0.3) -> PlaneStressEstimate:
    """Model-form error of plane stress / plane strain engagement speeds against 3-D for a part
    of axial ``thickness`` [m] whose compliance sits in flexures of length ``flexure_length``
    [m]; ``nu`` Poisson's ratio."""
    for name, v in (("thickness", thickness), ("flexure_length", flexure_length)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ParameterError(name, v, "a length > 0 m")
    if not (0.0 <= nu < 0.5):
        raise ParameterError("nu", nu, "a Poisson's ratio in [0, 0.5)")
    x = thickness / flexure_length
    xs, cs = FLEXURE_CHI[:, 0], FLEXURE_CHI[:, 1]
    if x <= xs[-1]:
        chi = float(np.interp(x, xs, cs))
    else:
        chi = float(1.0 - (1.0 - cs[-1]) * math.exp(-0.9 * (x - xs[-1])))
    span = 1.0 / math.sqrt(1.0 - nu * nu) - 1.0  # w_PE / w_PS - 1
    w3 = 1.0 + chi * span  # w_3D / w_PS
    return PlaneStressEstimate(h_over_L=x, chi=chi, engagement_error=1.0 / w3 - 1.0,
                               engagement_band=CHI_UNCERTAINTY * span / w3,
                               plane_strain_error=(1.0 + span) / w3 - 1.0)
