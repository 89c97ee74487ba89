"""Stress algebra of a load cycle: amplitude and mean tensors from the two extreme states,
and their equivalent (von Mises) values.

Per point the tensors sigma_a = (B - A)/2 and sigma_m = (A + B)/2 (exact for the straight
stress path between the extremes of a linear model).  Equivalent values (Shigley,
*Mechanical Engineering Design*, 10th ed., sec. 6-14, "combinations of loading modes"):

    s_a = vonMises(sigma_a),      s_m = sign(tr sigma_m) vonMises(sigma_m)

(plane stress: vM^2 = sxx^2 - sxx syy + syy^2 + 3 sxy^2).  Why von Mises and the sign of
the trace: fatigue cracks in a flexure start at its free edges (fillets, slot ends), where
plane stress is *uniaxial* along the edge; there s_a and s_m are exactly the amplitude
and mean of the edge stress with its sign, and every critical-plane or principal-stress
criterion gives the same numbers.  Inside the part (biaxial) von Mises is the usual
ductile-steel equivalent; the signed mean only decides whether the mean is tensile.
Compressive means get no credit (Shigley: for s_m < 0 failure when s_a = S_e).

Stress arrays are (3, npts): rows (sxx, syy, sxy) [Pa] (plane stress), or (6, npts): 3-D Voigt
rows (sxx, syy, szz, syz, sxz, sxy) (the thick plane and 3-D models), one column per point;
the trace is sxx + syy (+ szz).
"""

from __future__ import annotations

import numpy as np

from ...core import InputError

__all__ = ["amplitude_mean", "equivalent_stresses", "stress_array", "trace"]


def trace(s: np.ndarray) -> np.ndarray:
    """sxx + syy (+ szz for 3-D Voigt rows) of stresses stacked on the first axis."""
    return s[0] + s[1] + (s[2] if s.shape[0] == 6 else 0.0)


def stress_array(name: str, s) -> np.ndarray:
    """``s`` as a float array (3 or 6, npts) of finite stresses [Pa]; InputError naming ``name`` otherwise."""
    try:
        a = np.asarray(s, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name}: not a numeric array of stresses") from None
    if a.ndim != 2 or a.shape[0] not in (3, 6) or a.shape[1] == 0:
        raise InputError(f"{name}: stresses must have shape (3, npts) = (sxx, syy, sxy) x points or (6, npts) = "
                         f"3-D Voigt (sxx, syy, szz, syz, sxz, sxy) x points (got shape {a.shape})")
    if not np.all(np.isfinite(a)):
        k = int(np.nonzero(~np.isfinite(a).all(axis=0))[0][0])
        raise InputError(f"{name}: non-finite stress at point {k}")
    if np.abs(a).max() > 1e11:
        raise InputError(f"{name}: stresses up to {np.abs(a).max():.3g} Pa: expected Pa (|s| <= 1e11)")
    return a


def amplitude_mean(state_a, state_b) -> tuple[np.ndarray, np.ndarray]:
    """(amplitude tensor (B - A)/2, mean tensor (A + B)/2), each (3 or 6, npts) [Pa]."""
    A = stress_array("state_a", state_a)
    B = stress_array("state_b", state_b)
    if A.shape != B.shape:
        raise InputError(f"state_a and state_b must have the same shape (got {A.shape} and {B.shape})")
    return 0.5 * (B - A), 0.5 * (A + B)


def equivalent_stresses(amplitude, mean) -> tuple[np.ndarray, np.ndarray]:
    """(s_a, s_m): von Mises of the amplitude tensor, von Mises of the mean tensor signed by
    its trace (+ for a zero trace) [Pa] (module docstring)."""
    from ...fe import von_mises  # (the FE stage's formula: loaded with the stresses it is given)

    amp = np.asarray(amplitude, dtype=float)
    mean = np.asarray(mean, dtype=float)
    sign = np.where(trace(mean) < 0.0, -1.0, 1.0)
    return von_mises(amp), sign * von_mises(mean)
