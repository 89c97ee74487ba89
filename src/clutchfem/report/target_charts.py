"""Charts of the design-to-targets runs (pyplot-free figures, :func:`clutchfem.core.figure`).

Every axis names its quantity and unit; limits of the targets are drawn where they apply.
Figures are saved at a modest resolution (PNG under ~150 kB) because the report embeds them.
"""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np

from ..core import figure, save_figure
from ..geometry import get_concept
from ..targets import DIMENSIONLESS, better

DPI = 90
C_BEFORE, C_AFTER = "tab:gray", "tab:red"


def _save(fig, path) -> Path:
    if fig.get_layout_engine() is None:
        fig.tight_layout()
    return save_figure(fig, path, dpi=DPI)


# ---------------------------------------------------------------------------------------
# compensation
# ---------------------------------------------------------------------------------------
def compensation_profile(comp, path) -> Path:
    """Clearance along the shoe (before, after, free displacement at X) and the contact
    pressure along the shoe at X (before, after), target arc shaded."""
    fig, (a1, a2) = figure(2, 1, figsize=(10.5, 6.4), sharex=True, layout="constrained")
    b, a = comp.state_before, comp.state_after
    for ax in (a1, a2):
        ax.axvspan(*comp.arc, color="tab:green", alpha=0.08, label=f"target arc ({100 * comp.target_arc:.0f} %)")
        ax.grid(alpha=0.3)
    a1.plot(b.s, b.clearance_m * 1e3, color=C_BEFORE, lw=2, label="clearance before")
    a1.plot(a.s, a.clearance_m * 1e3, color=C_AFTER, lw=2, label="clearance after (table profile)")
    a1.plot(b.s, b.free_m * 1e3, color="tab:blue", ls="--", lw=1.2,
            label=f"free shoe's outward displacement at {comp.rpm:.0f} rpm (no drum)")
    knots = np.linspace(0, 1, len(comp.after_texts) - 1)
    kv = [comp.after.table[k] * 1e3 for k in range(len(knots))]
    a1.plot(knots, kv, "o", color=C_AFTER, ms=3.5, label="table control values")
    a1.set_ylabel("radial clearance / displacement [mm]")
    a1.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    a1.set_title(f"{comp.concept}: shoe profile compensation at {comp.rpm:.0f} rpm")
    a2.plot(b.s, b.pressure_Pa / 1e6, color=C_BEFORE, lw=1.5, marker=".", ms=3,
            label=f"before: contact {100 * b.contact_share:.1f} % of the arc")
    a2.plot(a.s, a.pressure_Pa / 1e6, color=C_AFTER, lw=1.5, marker=".", ms=3,
            label=f"after: contact {100 * a.contact_share:.1f} % of the arc")
    top = np.nanmax(a.pressure_Pa) / 1e6
    hi = max(3 * top, 1e-3)
    a2.set_ylim(-0.03 * hi, hi)  # the nodes out of contact (p = 0) drawn whole, above the axes' floor
    peak = np.nanmax(b.pressure_Pa) / 1e6
    if peak > a2.get_ylim()[1]:
        a2.annotate(f"before: peak {peak:.0f} MPa at the tip (off scale)", xy=(0.99, a2.get_ylim()[1] * 0.95),
                    ha="right", va="top", fontsize=7, color=C_BEFORE)
    a2.set_xlabel("arc position s along the shoe [-] (0: root at the flexure, 1: tip)")
    a2.set_ylabel("contact pressure [MPa]")
    a2.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return _save(fig, path)


def compensation_torque(before, after, engine, path, rpm: float, nominal_deg: float) -> Path:
    """Torque vs rpm and contact share vs rpm, before and after (two analyses); the share is
    the contact arc over the shoe's own arc ``nominal_deg`` (the analysis's ``arc_fraction``
    divides by the lining angle span measured from the pivot ray, 73 deg on concept 4's
    90 deg shoe, and exceeds 100 % once the whole shoe touches)."""
    fig, (a1, a2) = figure(1, 2, figsize=(10, 4.8), layout="constrained")
    for an, c, lab in ((before, C_BEFORE, "before"), (after, C_AFTER, "after")):
        cv = an.curves
        a1.plot(cv["rpm"], cv["fe_torque_Nm"], color=c, lw=2,
                label=f"{lab}: engages {an.engagement_rpm:.0f} rpm, slip {an.slip_rpm:.0f} rpm"
                if an.slip_rpm is not None else f"{lab}: engages {an.engagement_rpm:.0f} rpm")
        a2.plot(cv["rpm"], 100 * cv["contact_arc_deg"] / nominal_deg, color=c, lw=2, label=lab)
    r = np.linspace(*engine.rpm_range, 200)
    a1.plot(r, engine.torque_at(r), color="k", ls="--", lw=1, label="engine full-throttle torque (ASSUMED curve)")
    for ax in (a1, a2):
        ax.axvline(rpm, color="tab:green", ls=":", lw=1)
        ax.grid(alpha=0.3)
        ax.set_xlabel("engine speed [rpm]")
    a1.set_ylabel("clutch torque, drum held [N m]")
    a1.set_ylim(0, 3.0 * float(np.max(engine.torque_at(r))))
    a1.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    a2.set_ylabel("contact arc [% of the nominal shoe arc]")
    top = max(float(np.nanmax(an.curves["contact_arc_deg"])) for an in (before, after)) / nominal_deg * 100
    a2.set_ylim(0, max(105.0, 1.05 * top))
    a2.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    a1.set_title("torque vs speed")
    a2.set_title(f"contact arc vs speed (compensated at {rpm:.0f} rpm)")
    return _save(fig, path)


def compensation_convergence(comp, path) -> Path:
    fig, ax = figure(1, 1, figsize=(6.0, 3.8), layout="constrained")
    its = [s.iteration for s in comp.steps[1:]]
    ax.semilogy(its, [s.measured_cv for s in comp.steps[1:]], "o-", color=C_AFTER,
                label="pressure cv over the target arc (FE contact)")
    ax.semilogy(its, [max(s.step_m, 1e-10) * 1e3 for s in comp.steps[1:]], "s--", color="tab:blue",
                label="largest control-value change [mm]")
    ax.set_xlabel("fixed-point iteration (one rebuild and contact solve each)")
    ax.set_ylabel("[-] / [mm]")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2))
    return _save(fig, path)


# ---------------------------------------------------------------------------------------
# optimisation
# ---------------------------------------------------------------------------------------
def optimization_path(res, path) -> Path:
    """Every evaluated design: objective and each constraint (relative to its limit) vs the
    evaluation number; feasible designs filled, the incumbent's path drawn."""
    rows = [r for r in res.path if r["status"] == "ok"]
    cons = res.targets.constraints()
    fig, axes = figure(1 + len(cons), 1, figsize=(7.5, 2.4 + 1.5 * len(cons)), sharex=True, layout="constrained")
    axes = np.atleast_1d(axes)
    n = np.array([r["n"] for r in rows])
    feas = np.array([r["assessment"]["h"] <= 0 for r in rows])
    obj_mass = res.targets.objective == "mass"
    y = np.array([r["mass_kg"] * 1e3 if obj_mass else r["torque_margin_Nm"] for r in rows])
    ax = axes[0]
    ax.scatter(n[~feas], y[~feas], s=12, facecolors="none", edgecolors="tab:gray", label="infeasible")
    ax.scatter(n[feas], y[feas], s=14, color="tab:green", label="meets every target")
    inc_n, inc_y, best = [], [], None
    for r, yy in zip(rows, y):
        if better(r["assessment"], None if best is None else best["assessment"]):
            best = r
        inc_n.append(r["n"])
        inc_y.append(best["mass_kg"] * 1e3 if obj_mass else best["torque_margin_Nm"])
    ax.step(inc_n, inc_y, where="post", color="tab:red", lw=1.5, label="incumbent")
    ax.set_ylabel("part mass [g]" if obj_mass else "torque margin [N m]")
    final = res.best if res.best.get("mass_kg") is not None else best  # the search's answer (checked on its own mesh)
    if final is not None:
        ax.plot([], [], " ", label=f"final design: {final['mass_kg'] * 1e3:.1f} g" if obj_mass
                else f"final design: {final['torque_margin_Nm']:+.2f} N m")
    fig.legend(*ax.get_legend_handles_labels(), fontsize=7, ncol=4, loc="outside lower center")
    ax.grid(alpha=0.3)
    fig.suptitle(f"{res.concept}: optimisation path ({len(res.path)} designs, {res.seconds:.0f} s)")
    for ax, (name, key, limit, sense) in zip(axes[1:], cons):
        v = np.array([r.get(key) if r.get(key) is not None else np.nan for r in rows], dtype=float)
        unit = " [-]" if key in DIMENSIONLESS else " [rpm]"
        ax.scatter(n, v, s=8, c=np.where(feas, "tab:green", "tab:gray"))
        ax.axhline(limit, color="tab:red", ls="--", lw=1)
        ax.set_title(f"{key.replace('_rpm', '').replace('_', ' ')} {sense} "
                     + (f"{limit:g}" if key in DIMENSIONLESS else f"{limit:.0f} rpm") + " (dashed)", fontsize=8)
        ax.set_ylabel(key.replace("_rpm", "").replace("_with_ripple", "\nwith ripple").replace("_", " ") + unit,
                      fontsize=8)
        ax.grid(alpha=0.3)
        lo, hi = np.nanpercentile(v, [2, 98]) if np.isfinite(v).any() else (0, 1)
        pad = 0.1 * (hi - lo + 1e-9)
        ax.set_ylim(min(lo, limit) - pad, max(hi, limit) + pad)
    axes[-1].set_xlabel("design evaluated (#)")
    return _save(fig, path)


# ---------------------------------------------------------------------------------------
# tolerances
# ---------------------------------------------------------------------------------------
def tolerance_histograms(res, path) -> Path:
    keys = ["engagement_rpm", "engagement_rpm_with_ripple", "slip_rpm", "max_von_mises_Pa"]
    fig, axes = figure(2, 2, figsize=(9, 7.2), layout="constrained")
    limits = {key: (limit, sense) for _, key, limit, sense in res.spec}
    ok = [r for r in res.rows if r["status"] == "ok"]
    for ax, key in zip(axes.ravel(), keys):
        st = res.stats[key]
        sc = st["scale"]
        y = np.array([r[key] for r in ok if r.get(key) is not None], dtype=float) * sc
        if y.size:
            ax.hist(y, bins=max(6, min(30, int(math.sqrt(y.size)) * 2)), color="tab:blue", alpha=0.75)
        lines = []
        if st["nominal"] is not None:
            lines.append((st["nominal"] * sc, "k", "-", f"nominal {st['nominal'] * sc:.0f} {st['unit']}"))
        if key in limits:
            lim, sense = limits[key]
            lines.append((lim * sc, "tab:red", "--", f"spec {sense} {lim * sc:.0f} {st['unit']}"))
        if key == "max_von_mises_Pa":
            sf = limits.get("safety_factor")
            ys = ok[0].get("yield_strength_Pa") if ok else None
            if sf and ys:
                lines.append((ys / sf[0] * sc, "tab:red", "--",
                              f"spec (safety factor >= {sf[0]:g}): <= {ys / sf[0] * sc:.0f} MPa"))
        if y.size:  # the data set the scale; a limit far off is named at the edge
            lo_, hi_ = float(y.min()), float(y.max())
            pad = 0.15 * max(hi_ - lo_, 1e-3 * max(abs(hi_), 1.0))
            x0, x1 = lo_ - pad, hi_ + pad
            near = [v for v, *_ in lines if lo_ - 4 * pad <= v <= hi_ + 4 * pad]
            x0, x1 = min([x0] + near), max([x1] + near)
            ax.set_xlim(x0, x1)
            for v, c, ls, lab in lines:
                if x0 <= v <= x1:
                    ax.axvline(v, color=c, ls=ls, lw=1.2, label=lab)
                else:
                    ax.plot([], [], color=c, ls=ls, label=lab + (" (off the left)" if v < x0 else " (off the right)"))
        sd = st["sd"]
        ax.set_title(f"{st['label']}: sd {sd * sc:.3g} {st['unit']}" if sd is not None else st["label"], fontsize=9)
        ax.set_xlabel(f"{st['label']} [{st['unit']}]", fontsize=8)
        ax.set_ylabel("parts")
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2))
        ax.grid(alpha=0.3)
    fig.suptitle("\n".join(textwrap.wrap(f"{res.concept}: {res.n} parts ({res.dist}), tolerances "
                                          + ", ".join(f"{k} +-{tolerance_text(res, k)}" for k in res.tolerances), 110)),
                 fontsize=9)
    return _save(fig, path)


def tolerance_text(res, name) -> str:
    """The tolerance of parameter ``name`` in a tolerance study as designers write it
    (``0.05 mm``, ``0.5 deg``, ``0.01``)."""
    P = get_concept(res.concept).Params
    t = res.tolerances[name]
    u = P.unit(name)
    return f"{t * 1e3:g} mm" if u == "m" else (f"{t:g} deg" if u == "deg" else f"{t:g}")


def tolerance_ranking(res, path) -> Path:
    keys = [k for k in ("engagement_rpm", "slip_rpm", "max_von_mises_Pa") if k in res.ranking]
    fig, axes = figure(1, max(1, len(keys)), figsize=(3.4 * max(1, len(keys)) + 1.0, 0.45 * len(res.tolerances) + 1.8),
                       sharey=True)
    axes = np.atleast_1d(axes)
    names = list(res.tolerances)
    for ax, key in zip(axes, keys):
        rk = res.ranking[key]
        d = {it["name"]: it for it in rk["items"]}
        ypos = np.arange(len(names))
        v = np.array([d[n]["src"] for n in names])
        lo = np.array([d[n]["ci95"][0] for n in names])
        hi = np.array([d[n]["ci95"][1] for n in names])
        ax.barh(ypos, v, color=np.where(v >= 0, "tab:blue", "tab:orange"), alpha=0.8)
        ax.errorbar(v, ypos, xerr=[v - lo, hi - v], fmt="none", ecolor="k", capsize=3, lw=1)
        ax.axvline(0, color="k", lw=0.8)
        ax.set_yticks(ypos)
        ax.set_yticklabels(names, fontsize=8)
        # a coefficient is within +-1 for independent inputs, not its bootstrap interval on a few
        # correlated parts (1.04 measured on 12): the axes hold the whole bar
        reach = float(np.nanmax(np.abs(np.concatenate([v, lo, hi, [1.0]]))))
        ax.set_xlim(-1.05 * reach, 1.05 * reach)
        ax.set_xlabel("standardised regression coefficient [-]", fontsize=8)
        ax.set_title(f"{rk['label']}\nR^2 = {rk['r2']:.3f} [{rk['r2_ci95'][0]:.3f}, {rk['r2_ci95'][1]:.3f}]",
                     fontsize=8)
        ax.grid(alpha=0.3, axis="x")
    return _save(fig, path)
