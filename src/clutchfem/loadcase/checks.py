"""Is the answer right, and does the model apply?  Checks every sweep runs on itself.

* **Equilibrium residual** per speed: the discrete equations the load case claims to solve,
  r = T' [(K - w^2 M) u - w^2 f1 - D lam] (without the M term when spin softening is off),
  relative to the applied load T' [w^2 f1 + w^2 M u + D lam].  Exact solves (softening off or
  exact) leave round-off times the conditioning; the Ritz mode acceleration leaves its
  truncation error, so the residual is also that approximation's error indicator.
* **Torque balance** per speed: the moment of the bore reactions about the axis balances the
  moment of the applied loads (rigid rotations are in the null space of K, and on a
  one-sector model the two cut lines' reactions cancel), a global check of the constraints
  independent of the LCP.  Without spin softening the applied moment is the friction torque
  alone (the centrifugal and normal contact loads have no moment about the axis).  With it,
  the linearised softening load w^2 M u applied at the undeformed position has a moment
  w^2 rho' M u about the axis that the real centrifugal load, acting at the deformed
  position, does not have: a model-form artefact of linear spin softening without the
  consistent stress-stiffening term (see BENCHMARKS.md, model-form error).
* **Condition estimate** of the reduced stiffness T' K T: ||K||_1 ||K^-1||_1 with the second
  factor from Hager/Higham's estimator (``scipy.sparse.linalg.onenormest``, a few solves
  with the existing factorisation).
* **Model applicability** (:func:`model_warnings`): stress above yield, a node outside the
  contact group passing the drum radius (only the contact surface is held by the drum),
  displacements large against the part (the small-displacement model is stretched), speeds
  near the divergence speed of the free part, no drum at all.

Past the thresholds below a sweep fails loudly (:class:`~clutchfem.core.SolverError`)
instead of returning a number nobody can trust.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse.linalg as spla

from ..core import EquilibriumError, SolverError

#: relative equilibrium residual above which a sweep is refused.  Exact solves leave ~1e-8
#: (round-off x conditioning); the Ritz mode acceleration leaves its truncated high modes,
#: up to ~1e-4 near divergence while its answers are within ~2e-6 of the exact softening
#: (measured: benchmarks/bench_stress.py), since those modes are stiff and not amplified
RESIDUAL_FAIL = 1e-3
#: the same for the pre-stress Ritz space's preconditioned check, whose residual is the
#: relative displacement error it leaves: measured equal to it against the per-speed
#: factorisation (concept 3.1, best path, 12 000-14 000 rpm: residual 1.04 / 1.40 / 1.82e-3,
#: displacement error 1.04 / 1.40 / 1.82e-3, peak stress 0.97 / 1.26 / 1.60e-3, contact
#: forces 2e-5).  Between RESIDUAL_FAIL and this, the answer is kept and ``analyze`` adds the
#: residual at the answer's speed to its band (the per-speed fallback costs 50-100x)
RESIDUAL_FAIL_RITZ = 5e-3
#: condition estimate of T' K T above which the model is refused (double precision keeps
#: ~16 digits: 1e14 leaves two) and above which a warning is given
CONDITION_FAIL = 1e14
CONDITION_WARN = 1e12
#: share of the divergence speed above which a warning is given
DIVERGENCE_WARN = 0.9
#: max displacement / drum radius above which the small-displacement model is said to be
#: stretched (the model-form error of geometric non-linearity: BENCHMARKS.md)
DISPLACEMENT_WARN = 0.05


def condition_estimate(model) -> float:
    """1-norm condition estimate of the reduced stiffness (cached on the model)."""
    if "_cond" not in model.__dict__:
        Kr, f = model.Kr, model.factor
        n1 = float(abs(Kr).sum(axis=0).max())
        op = spla.LinearOperator(Kr.shape, matvec=f.solve, rmatvec=f.solve, matmat=f.solve, dtype=float)
        model.__dict__["_cond"] = n1 * float(spla.onenormest(op))
    return model.__dict__["_cond"]


def rotation_field(basis, ndofs: int | None = None) -> np.ndarray:
    """rho (ndofs,): the displacement of a unit rigid rotation about the axis, (-y, x), on
    the vector P2 ``basis`` (a model whose unknowns extend it, the thick plane model's higher
    modes, gives their count ``ndofs``: a rigid rotation does not move them)."""
    rho = np.zeros(basis.N if ndofs is None else ndofs)
    for comp, sign in ((0, -1.0), (1, 1.0)):
        # every node's dof of this component (2-D P2: vertices, facets; 3-D P2: vertices, edges)
        d = np.concatenate([a[comp] for a in (basis.nodal_dofs, basis.facet_dofs, basis.edge_dofs)
                            if a.shape[0] > comp])
        rho[d] = sign * basis.doflocs[1 - comp, d]
    return rho


def equilibrium(model, contact, softened: bool, fields, omegas: np.ndarray, lam: np.ndarray,
                chunk: int = 64, preconditioned: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """(relative residual, torque-balance error) per state (see module docstring).  The
    torque-balance error is |T_bore + T_applied| / (sum of |moments| of the applied loads).
    Costs two sparse products with the sweep's reduced basis and small dense ones per speed.
    ``preconditioned``: the residual is measured as the displacement it would cause,
    ||K^-1 T' r|| / ||K^-1 T' load|| (the basis and active load columns back-solved once;
    explicit fields: one blocked back-solve per chunk): for softening
    operators with much stiff-mode content (the pre-stress stiffness K_sigma1), whose Ritz
    truncation leaves force residuals ~1e4 x larger than the error they cause; fewer states
    than ~1.5 basis vectors: the states' own residuals back-solved instead)."""
    ns = len(omegas)
    res = np.zeros(ns)
    tq = np.zeros(ns)
    if ns == 0:
        return res, tq
    K, T, f1 = model.K, model.T, model.f1
    M = model.M if softened else None
    D = None if contact is None else contact.load
    rho = rotation_field(model.basis, model.ndofs)
    # the model's own facets (a 3-D model's bore is a face of its extruded mesh)
    bore = np.unique(model.basis.get_dofs(getattr(model, "boundary", model.cm.boundary)("bore")).all())
    # reduced fields (basis @ coef) are checked through the basis's columns, unless the
    # preconditioned check would back-solve more of them (~3 a basis vector) than the states'
    # own residuals need (2 a state: a one-speed sweep such as the error step's finer mesh)
    explicit = fields.U is not None or (preconditioned and 2 * ns < 3 * fields.basis.shape[1])
    if not explicit:
        KB = K @ fields.basis
        MB = M @ fields.basis if softened else None
    if preconditioned and not explicit:
        # K^-1 T' R is linear in the basis coefficients and the contact forces: back-solve the
        # few basis / load columns once instead of every speed's residual
        solve = model.factor.solve
        ZK, Zf = solve(T.T @ KB), solve(T.T @ f1)
        ZM = solve(T.T @ MB) if softened else None
        act = np.nonzero(np.any(lam > 0, axis=0))[0] if D is not None else np.zeros(0, dtype=int)
        ZD = solve((T.T @ D[:, act]).toarray()).reshape(ZK.shape[0], -1) if len(act) else None
    for a in range(0, ns, chunk):
        sl = slice(a, min(a + chunk, ns))
        w2 = omegas[sl] ** 2
        if not explicit:
            C = fields.coef[:, sl]
            Ku = KB @ C
            Mu = MB @ C if softened else None
        else:
            U = fields.block(sl)
            Ku = K @ U
            Mu = M @ U if softened else None
        load = f1[:, None] * w2[None, :]
        if softened:
            load = load + Mu * w2[None, :]
        if D is not None:
            load = load + D @ lam[sl].T
        R = Ku - load  # all dofs: the reactions at the clamped ones
        if preconditioned and not explicit:
            zl = Zf[:, None] * w2[None, :]
            if softened:
                zl = zl + (ZM @ C) * w2[None, :]
            if ZD is not None:
                zl = zl + ZD @ lam[sl][:, act].T
            num = np.linalg.norm(ZK @ C - zl, axis=0)
            scale = np.linalg.norm(zl, axis=0)
        elif preconditioned:
            num = np.linalg.norm(model.factor.solve(T.T @ R), axis=0)
            scale = np.linalg.norm(model.factor.solve(T.T @ load), axis=0)
        else:
            num, scale = np.linalg.norm(T.T @ R, axis=0), np.linalg.norm(T.T @ load, axis=0)
        res[sl] = num / np.maximum(scale, 1e-300)
        t_bore = rho[bore] @ R[bore]
        t_applied = rho @ load
        tq[sl] = np.abs(t_bore + t_applied) / np.maximum(np.abs(rho) @ np.abs(load), 1e-300)
    return res, tq


def check_numerics(residual: np.ndarray, cond: float, rpm: np.ndarray, preconditioned: bool = False) -> list[str]:
    """Refuse (SolverError) past the thresholds; return warnings below them.  ``preconditioned``
    (the pre-stress Ritz space's check, whose residual is the relative displacement error):
    refused past :data:`RESIDUAL_FAIL_RITZ`; between :data:`RESIDUAL_FAIL` and it, a warning,
    and ``analyze`` carries the residual in the answers' bands."""
    warns = []
    if not math.isfinite(cond) or cond > CONDITION_FAIL:
        raise SolverError(f"the stiffness matrix is too ill-conditioned to trust (1-norm condition estimate "
                          f"{cond:.2g} > {CONDITION_FAIL:.0e}): a flexure far too slender for its mesh, "
                          "badly shaped elements or a part that is barely held; refine or thicken it")
    if cond > CONDITION_WARN:
        warns.append(f"ill-conditioned stiffness (condition estimate {cond:.2g}): results may carry "
                     f"~{cond * 1e-16:.0e} relative round-off")
    if residual.size:
        k = int(np.argmax(residual))
        fail = RESIDUAL_FAIL_RITZ if preconditioned else RESIDUAL_FAIL
        if not np.all(np.isfinite(residual)) or residual[k] > fail:
            raise EquilibriumError(f"equilibrium residual {residual[k]:.2g} at {rpm[k]:.0f} rpm exceeds "
                                   f"{fail:g} of the applied load: the solution is not in equilibrium "
                                   "(spin softening near divergence? --spin-softening exact or prestress-exact checks it)")
        if residual[k] > RESIDUAL_FAIL:
            warns.append(f"spin softening: the pre-stress Ritz space leaves a displacement error of up to "
                         f"{100 * residual[k]:.2g} % (its equilibrium residual at {rpm[k]:.0f} rpm), and up to 15x "
                         "that in the stress curve's peak and the fatigue states' stresses (measured); "
                         "--spin-softening prestress-exact removes it.  analyze carries it in the answers' error "
                         "bands and re-solves the peak stress per speed")
    return warns


def model_warnings(res, yield_strength: float) -> list[str]:
    """Plain warnings where the model's answer is suspect or the design fails (module doc):
    no drum, peak stress above yield, a node outside the contact group passing the drum,
    displacements large for the linear model, speeds near the divergence speed.

    Parameters
    ----------
    res : SweepResult
        A solved sweep.
    yield_strength : float
        The material's yield strength [Pa].

    Returns
    -------
    list of str
        One sentence per warning (empty: none); the same texts a sweep and ``analyze`` carry.

    Examples
    --------
    >>> import clutchfem as cf
    >>> r = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm")).sweep("0:14000:7000")
    >>> cf.model_warnings(r, yield_strength=1250e6)
    []
    >>> cf.model_warnings(r, yield_strength=300e6)           # a weaker material
    ['STRESS ABOVE YIELD: peak von Mises ... MPa at 14000 rpm exceeds the yield strength 300 MPa ...']
    """
    out = []
    c = res.curve
    if res.contact is None:
        out.append("no drum: free spin only (no contact, no torque, no engagement speed); give the drum "
                   "radius to analyse the clutch")
    if "max_von_mises_Pa" in c and c["max_von_mises_Pa"].notna().any():
        vm_all = c["max_von_mises_Pa"].to_numpy()
        k = int(np.nanargmax(vm_all))
        vm = float(vm_all[k])
        if vm > yield_strength:
            first = float(c["rpm"][c["max_von_mises_Pa"] > yield_strength].min())
            out.append(f"STRESS ABOVE YIELD: peak von Mises {vm / 1e6:.0f} MPa at {c['rpm'].iloc[k]:.0f} rpm "
                       f"exceeds the yield strength {yield_strength / 1e6:.0f} MPa (from {first:.0f} rpm on): "
                       "a linear-elastic answer past yield is not physical")
    if res.contact is not None and len(c):
        k, depth, where = drum_intrusion(res)
        if depth > 0:
            out.append(f"PART REACHES THE DRUM OUTSIDE THE CONTACT SURFACE: at {res.rpm[k]:.0f} rpm a node at "
                       f"({where[0] * 1e3:.2f}, {where[1] * 1e3:.2f}) mm passes the drum radius by "
                       f"{depth * 1e3:.3g} mm; only the contact group is held by the drum, so the answer "
                       "there is not physical (add that surface to the contact group, or change the design)")
        umax = float(c["max_displacement_m"].max())
        R = res.contact.drum_radius
        if umax > DISPLACEMENT_WARN * R:
            out.append(f"LARGE DISPLACEMENT: up to {umax * 1e3:.3g} mm, {100 * umax / R:.1f} % of the drum radius: "
                       "the small-displacement (linear) model is stretched")
    if res.divergence_rpm is not None and len(res.rpm) and res.rpm.max() > DIVERGENCE_WARN * res.divergence_rpm:
        past = res.rpm.max() >= res.divergence_rpm
        out.append(f"speeds up to {res.rpm.max():.0f} rpm come "
                   + ("past" if past else f"within {100 * (1 - DIVERGENCE_WARN):.0f} % of")
                   + f" the divergence speed {res.divergence_rpm:.0f} rpm of the free part (spin softening)"
                   + (": only the drum holds the shoes there (stability checked)" if past else "")
                   + "; answers there are very sensitive to every input")
    return out


def drum_intrusion(res) -> tuple[int, float, tuple[float, float]]:
    """(state index, depth [m], node position) of the deepest pass of a node that is not a
    contact node beyond the drum circle, |x + u| - R_d (depth <= 0: none passes).

    Only nodes with r_0 + max|u| >= R_d can pass (|x + u| <= r_0 + |u|; max|u| over every
    node and state is the curve's ``max_displacement_m``), so only their rows of the fields
    are formed: the same deepest pass as checking every node."""
    b = res.fields.fe_basis
    xd = np.concatenate([a[0] for a in (b.nodal_dofs, b.facet_dofs, b.edge_dofs) if a.shape[0] > 0])
    X = b.doflocs[:, xd]
    nd = res.contact.nodes
    keep = ~np.isin(xd, nd.dof_x)
    # a one-sector model's cut_b copies of contact nodes are contact nodes too
    r0 = np.hypot(X[0], X[1])
    keep &= r0 < nd.drum_radius - 0.5 * float(np.min(nd.gap0, initial=0.0)) - 1e-12
    umax = float(np.nanmax(res.curve["max_displacement_m"], initial=0.0)) if len(res.curve) else 0.0
    keep &= r0 + umax * (1 + 1e-9) >= nd.drum_radius
    best = (0, -np.inf, (math.nan, math.nan))
    if not keep.any() or res.fields.n == 0:
        return best
    xd, X = xd[keep], X[:, keep]
    f = res.fields
    rows = np.concatenate([xd, xd + 1])
    U = f.U[rows] if f.U is not None else f.basis[rows] @ f.coef
    k = len(xd)
    r = np.hypot(X[0][:, None] + U[:k], X[1][:, None] + U[k:]) - nd.drum_radius
    i, j = np.unravel_index(int(np.argmax(r)), r.shape)
    return int(j), float(r[i, j]), (float(X[0, i]), float(X[1, i]))
