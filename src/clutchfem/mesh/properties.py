"""Mass and area properties of a meshed part, by quadrature over its curved P2 triangles.

One set of integrals serves both users: per element e of the mesh,

    A_e = int_e dA,   S_x,e = int_e x dA,   S_y,e = int_e y dA                  (first moments)
    I_xx,e = int_e y^2 dA,   I_yy,e = int_e x^2 dA,   I_xy,e = int_e x y dA      (second, about the origin)

(:func:`element_moments`), summed over the part or over a named zone.  On a P2 triangle the
map x(xi) is quadratic and its Jacobian determinant quadratic too, so x |det J| is a degree-4
and x^2 |det J| a degree-6 polynomial: quadrature of order 4 is exact for the area and first
moments, of order 6 for the second moments, on the mesh's geometry (the only error is the P2
arcs against the true circles).

* :func:`mesh_mass_properties`: area, mass = area x rho x thickness and centre of mass of
  the part (and of each ``shoe_<i>`` zone), for the analysis's ``part`` record; it reuses an
  FE model's basis (its quadrature, order 4) when given one, so it costs no new basis.
* :func:`mesh_area_properties`: area, centroid and second moments of the *whole* part per
  unit density and thickness (the keys of the geometry module's OCC-exact
  ``ClutchMesh.mass["solid"]``), for the crankshaft whirl's rotor
  (:mod:`clutchfem.clutch.crankshaft`).

A one-sector model stands for ``ClutchMesh.sector_copies`` copies of itself: its mass is
scaled by that number (its centre of mass then says nothing about the part and is left
out), and its second moments are completed by cyclic symmetry (:func:`mesh_area_properties`).
"""

from __future__ import annotations

import math

import numpy as np
from skfem import Basis, ElementTriP0

from ..core import MeshError

__all__ = ["element_moments", "mesh_area_properties", "mesh_mass_properties"]


def element_moments(mesh, basis=None, intorder: int = 6, second: bool = False) -> dict[str, np.ndarray]:
    """Per element of ``mesh`` (module docstring): ``area``, ``sx``, ``sy`` and, with
    ``second``, ``ixx``, ``iyy``, ``ixy`` [m^2, m^3, m^4], each (nelem,).  ``basis``: a
    scikit-fem basis on ``mesh`` whose quadrature to use (an FE model's: no new basis; its
    order must integrate the moments asked for exactly); default a P0 basis of order
    ``intorder``."""
    if basis is None:
        basis = Basis(mesh, ElementTriP0(), intorder=intorder)
    dx = basis.dx  # (nelem, nqp) quadrature weights x |det J|
    x, y = basis.mapping.F(basis.X)  # (nelem, nqp) each
    out = {"area": dx.sum(axis=1), "sx": (x * dx).sum(axis=1), "sy": (y * dx).sum(axis=1)}
    if second:
        out.update(ixx=(y * y * dx).sum(axis=1), iyy=(x * x * dx).sum(axis=1), ixy=(x * y * dx).sum(axis=1))
    return out


def mesh_mass_properties(cm, rho: float, thickness: float, basis=None) -> dict:
    """Area, mass and centre of mass of the meshed part (and of each ``shoe_<i>`` zone the mesh
    names), by quadrature over the (possibly curved) P2 triangles: mass = area x rho x thickness.
    ``basis``: a scikit-fem basis on ``cm.mesh`` whose quadrature to use (default: P0,
    order 4).

    A one-sector model is scaled to the whole part (``cm.sector_copies``); its centre of mass
    is then not meaningful and left out.  For a full part, ``unbalance_kg_m`` = mass x
    distance of the centre of mass from the rotation axis.
    """
    e = element_moments(cm.mesh, basis, intorder=4)

    def props(elements=None) -> tuple[float, float, float]:
        sel = slice(None) if elements is None else np.asarray(elements)
        a = float(e["area"][sel].sum())
        return a, float(e["sx"][sel].sum()) / a, float(e["sy"][sel].sum()) / a

    area, cx, cy = props()
    sector = cm.sector_angle is not None
    scale = cm.sector_copies
    out = {"thickness_m": thickness, "rho_kg_m3": float(rho), "area_m2": area * scale,
           "mass_kg": area * scale * rho * thickness,
           "source": "quadrature over the mesh: area x rho x thickness"
                     + (f" (one-sector model x {scale:g})" if sector else "")}
    if not sector:
        out.update({"centroid_m": [cx, cy], "unbalance_kg_m": out["mass_kg"] * math.hypot(cx, cy)})
    shoes = []
    sub = cm.mesh.subdomains or {}
    i = 0
    while f"shoe_{i}" in sub and len(sub[f"shoe_{i}"]):
        a, sx, sy = props(np.asarray(sub[f"shoe_{i}"]))
        shoes.append({"shoe": i, "mass_kg": a * rho * thickness, "centroid_m": [sx, sy],
                      "R_Tp_m": math.hypot(sx, sy)})
        i += 1
    if shoes:
        out["shoes"] = shoes
    return out


def mesh_area_properties(cm) -> dict:
    """Area properties of the *whole* part per unit density and thickness, from its mesh.

    Quadrature of order 6 over the (curved) P2 triangles of ``cm.mesh`` (a
    :class:`~clutchfem.mesh.ClutchMesh`): exact on the mesh's geometry (module docstring).
    Returned keys, as the geometry module's OCC-exact ``cm.mass["solid"]``: ``area`` [m^2],
    ``centroid`` (x, y) [m], ``Ixx_origin`` = int y^2 dA, ``Iyy_origin`` = int x^2 dA,
    ``Ixy_origin`` = int x y dA, ``J_origin`` = Ixx + Iyy, ``J_centroid`` = J_origin - A |c|^2
    [m^4].

    One-sector model (``cm.sector_angle`` set): the part is ``k = cm.sector_copies`` copies of
    the sector rotated by ``i sector_angle``, i = 0..k-1.  A copy rotated by theta has
    ``int y^2 = Ixx c^2 + Iyy s^2 + 2 Ixy s c`` and ``int x^2 = Iyy c^2 + Ixx s^2 - 2 Ixy s c``
    (c, s = cos, sin theta); summed over the copies, ``sum c^2 = sum s^2 = k/2`` and
    ``sum s c = 0`` for k >= 3, so I_xx = I_yy = J/2 exactly (cyclic symmetry) and the
    centroid lies on the axis; k = 2 and k = 1 follow from the same sums.  A full model uses
    its actual moments and centroid.
    """
    e = element_moments(cm.mesh, intorder=6, second=True)
    a, sx, sy = float(e["area"].sum()), float(e["sx"].sum()), float(e["sy"].sum())
    ixx, iyy, ixy = float(e["ixx"].sum()), float(e["iyy"].sum()), float(e["ixy"].sum())
    if cm.sector_angle:
        k = cm.sector_copies
        if k < 1 or cm.n_shoes_total % cm.n_shoes_model or abs(k * cm.sector_angle - 2 * math.pi) > 1e-9:
            raise MeshError(f"mesh from {cm.source}: a sector of {math.degrees(cm.sector_angle):g} deg with "
                            f"{cm.n_shoes_model} of {cm.n_shoes_total} shoes does not close the circle "
                            "(n_shoes_total / n_shoes_model sectors must span 360 deg)")
        th = cm.sector_angle * np.arange(k)
        c, s = np.cos(th), np.sin(th)
        a, sx, sy = k * a, float((c * sx - s * sy).sum()), float((s * sx + c * sy).sum())
        ixx, iyy, ixy = (float((ixx * c * c + iyy * s * s + 2 * ixy * s * c).sum()),
                         float((iyy * c * c + ixx * s * s - 2 * ixy * s * c).sum()),
                         float(((iyy - ixx) * s * c + ixy * (c * c - s * s)).sum()))
    cx, cy = sx / a, sy / a
    return {"area": a, "centroid": (cx, cy), "Ixx_origin": ixx, "Iyy_origin": iyy,
            "Ixy_origin": ixy, "J_origin": ixx + iyy, "J_centroid": ixx + iyy - a * (cx * cx + cy * cy)}
