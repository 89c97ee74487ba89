"""Stress recovery of the thick plane model (:class:`~clutchfem.fe.FEModelThick`): the 3-D
stresses at the element vertices of the mid-plane and the free face, small-strain or in the
finite-rotation measure, and the sweep's peak of the latter evaluated only where it can be."""

from __future__ import annotations

from functools import cached_property

import numpy as np

from .stress import p2_vertex_gradients, von_mises

#: share below a state's small-strain peak von Mises within which the finite-rotation peak
#: is searched (ThickStress.finite_peak)
PEAK_CANDIDATE = 0.2
#: reference gradients of the three P1 shape functions (constant)
_R1 = np.array([[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]])


class ThickStress:
    """Raw 3-D stresses of a :class:`FEModelThick` at every element vertex on the mid-plane
    and on the free face z = h/2: ``__call__(U)`` -> (6, npts[, ncols]) Voigt xx, yy, zz, yz,
    xz, xy [Pa]; points ordered (level, element, vertex); ``points`` (3, npts) [m],
    ``element`` (npts,) the 2-D element of each point."""

    LEVELS = (0.0, 1.0)  # zeta of the stress levels
    #: the sweep's peak stress uses the finite-rotation measure (``__call__(U, finite=True)``);
    #: the fatigue cycles combine small-strain fields (linear in the solved states)
    FINITE = True

    def __init__(self, model):  # FEModelThick
        self._m = model
        self.lame = model.lame
        Gx, Gy, ex, ey, Jinv = p2_vertex_gradients(model.basis, model.cm.source)
        self._G = (Gx, Gy, ex, ey)
        g1 = _R1[None, None] @ Jinv  # (ne, 3 vertices, 3 shape functions, 2)
        self._g1 = g1
        t = model.cm.mesh.t[:3].T  # (ne, 3) vertex of each local P1 function
        self._t = t

    def gradients(self, U: np.ndarray, elements: np.ndarray | None = None) -> np.ndarray:
        """The 3-D displacement gradient H[a, b] = d u_a / d x_b at every stress point:
        array (3, 3, npts, ncols) for the displacement column(s) U (points as :attr:`points`;
        with ``elements``, only those elements' points, ordered (level, given element, vertex))."""
        m = self._m
        U = np.asarray(U).reshape(np.shape(U)[0], -1)
        e = slice(None) if elements is None else np.asarray(elements, dtype=np.int64)
        Gx, Gy, ex, ey = (a[e] for a in self._G)
        g1, t = self._g1[e], self._t[e]
        ux, uy = U[ex], U[ey]  # (ne, 6, ncols)
        g0 = {(0, 0): Gx @ ux, (0, 1): Gy @ ux, (1, 0): Gx @ uy, (1, 1): Gy @ uy}  # (ne, 3, ncols)
        fields = []
        for i in range(len(m.fields)):
            F = U[m.field_dofs(i)][t]  # (ne, 3 local fns, ncols): at vertex v its own dof
            fields.append((F, np.matmul(g1[..., 0], F), np.matmul(g1[..., 1], F)))
        out = []
        for zeta in self.LEVELS:
            z = np.array([zeta])
            H = np.zeros((3, 3) + g0[0, 0].shape)
            for (a, b), g in g0.items():
                H[a, b] = g
            for (kind, pw, comp), (val, dxf, dyf) in zip(m.fields, fields):
                if kind == "a":  # u_comp += phi_p(z) ap_comp
                    v, dv = (float(x[0]) for x in m._phi(pw, z))
                    H[comp, 0] += v * dxf
                    H[comp, 1] += v * dyf
                    H[comp, 2] += dv * val
                else:  # u_z += psi_q(z) cq
                    v, dv = (float(x[0]) for x in m._psi(pw, z))
                    H[2, 0] += v * dxf
                    H[2, 1] += v * dyf
                    H[2, 2] += dv * val
            out.append(H.reshape(3, 3, -1, U.shape[1]))
        return np.concatenate(out, axis=2)

    def __call__(self, U: np.ndarray, finite: bool = False, elements: np.ndarray | None = None) -> np.ndarray:
        """Stresses (6, npts[, ncols]) [Pa], Voigt xx, yy, zz, yz, xz, xy: the small-strain
        stress C : sym(H), or with ``finite`` the Cauchy stress of the St. Venant-Kirchhoff law
        of the same displacement, F S F' / det F with S = C : E and the Green-Lagrange strain
        E = (H + H' + H' H) / 2 (the second-order terms the small strain drops: a flexure end
        turning by a few degrees under ~1 % strain reads ~2 % more; the non-linear reference
        measures the rest, BENCHMARKS.md section 13).  ``elements``: only those elements'
        points (see :meth:`gradients`)."""
        one = np.ndim(U) == 1
        H = self.gradients(U, elements)
        lam, mu = self.lame
        I3 = np.eye(3)[:, :, None, None]
        E = 0.5 * (H + H.transpose(1, 0, 2, 3))
        if finite:
            E = E + 0.5 * np.einsum("cakn,cbkn->abkn", H, H)
        S = 2 * mu * E + lam * (E[0, 0] + E[1, 1] + E[2, 2])[None, None] * I3
        if finite:
            F = H + I3
            J = (F[0, 0] * (F[1, 1] * F[2, 2] - F[1, 2] * F[2, 1]) - F[0, 1] * (F[1, 0] * F[2, 2] - F[1, 2] * F[2, 0])
                 + F[0, 2] * (F[1, 0] * F[2, 1] - F[1, 1] * F[2, 0]))
            S = np.einsum("ackn,cdkn,bdkn->abkn", F, S, F) / J[None, None]
        s = np.stack([S[0, 0], S[1, 1], S[2, 2], S[1, 2], S[0, 2], S[0, 1]])
        return s[..., 0] if one else s

    def von_mises(self, s: np.ndarray) -> np.ndarray:
        return von_mises(s)

    def finite_peak(self, U: np.ndarray, small: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(peak von Mises [Pa] of the finite-rotation measure, index of its point) per column
        of ``U`` (ndofs, ncols), given the small-strain von Mises ``small`` (npts, ncols) of the
        same columns (cheap: linear in the states).  The finite measure is evaluated only on
        the elements holding a point within PEAK_CANDIDATE (20 %) of a column's small-strain
        peak: it differs from the small strain by the rotations' second-order terms, ~2 % at a
        flexure end turning a few degrees, so no point further down can overtake the peak.
        Should the candidates read more than PEAK_CANDIDATE / 2 above their small strain (a
        rotation far beyond what the linear model is for), every point is evaluated."""
        U = np.asarray(U).reshape(np.shape(U)[0], -1)
        top = small.max(axis=0)
        # (an unloaded state, top 0, has its peak 0 anywhere: it adds no candidate)
        cand = np.any((small >= (1.0 - PEAK_CANDIDATE) * top[None, :]) & (top[None, :] > 0), axis=1)
        ne = self._m.cm.n_elements
        elems = np.unique(np.nonzero(cand)[0] % (3 * ne) // 3)
        vm = self.von_mises(self(U, finite=True, elements=elems))  # (npts of elems, ncols)
        with np.errstate(divide="ignore", invalid="ignore"):
            pts = self._points_of(elems)
            rise = np.nanmax(np.where(small[pts] > 0, vm / small[pts], 1.0)) - 1.0
        if not np.isfinite(rise) or rise > 0.5 * PEAK_CANDIDATE:
            vm = self.von_mises(self(U, finite=True))
            return vm.max(axis=0), vm.argmax(axis=0)
        at = pts[vm.argmax(axis=0)]
        at[top <= 0] = 0  # (an unloaded state: the first point, as an argmax over zeros)
        return vm.max(axis=0), at

    def _points_of(self, elems: np.ndarray) -> np.ndarray:
        """Global stress-point indices of ``elems``' points, in the (level, element, vertex)
        order of ``__call__(..., elements=elems)``."""
        ne = self._m.cm.n_elements
        local = (3 * np.asarray(elems)[:, None] + np.arange(3)[None, :]).ravel()
        return np.concatenate([lv * 3 * ne + local for lv in range(len(self.LEVELS))])

    @cached_property
    def points(self) -> np.ndarray:
        """(3, npts) positions [m] of the stress points: element vertices at each level."""
        mesh = self._m.cm.mesh
        xy = mesh.p[:, mesh.t[:3].T.ravel()]
        h = self._m.thickness
        return np.hstack([np.vstack([xy, np.full(xy.shape[1], 0.5 * h * z)]) for z in self.LEVELS])

    @cached_property
    def element(self) -> np.ndarray:
        ne = self._m.cm.n_elements
        return np.tile(np.arange(ne).repeat(3), len(self.LEVELS))
