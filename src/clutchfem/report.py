"""Designer-facing plots and the one-page summary of an analysed design."""

from __future__ import annotations

import json
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .clutch.baseline import baseline_torque_at_rpm  # noqa: E402


def torque_plot(an, engine, path: Path, title: str) -> Path:
    c = an.curves
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.plot(c["rpm"], c["fe_torque_Nm"], "k-", lw=2, label="FE (contact + friction)")
    ax.plot(c["rpm"], c["analytic_fe_arc_Nm"], "b--", label="analytical, FE contact arc")
    ax.plot(c["rpm"], c["analytic_nominal_arc_Nm"], "r:", label="analytical, nominal full arc (thesis)")
    r = np.linspace(*engine.rpm_range, 200)
    ax.plot(r, engine.torque_at(r), "g-", label="engine (ASSUMED curve)")
    ax.plot(c["rpm"], baseline_torque_at_rpm(c["rpm"].to_numpy(), "new"), color="0.6", lw=1,
            label="today's spring clutch (new)")
    if an.engagement_rpm:
        ax.axvline(an.engagement_rpm, color="m", ls="--", lw=1, label=f"engagement {an.engagement_rpm:.0f} rpm")
    if an.slip_rpm:
        ax.axvline(an.slip_rpm, color="orange", ls="-", lw=1, label=f"slip {an.slip_rpm:.0f} rpm")
    req = an.requirements
    ax.axvspan(0, req["a"] * req["idle_rpm"], color="red", alpha=0.07, label=f"no engagement below a x idle (a={req['a']})")
    ax.axvspan(req["b"] * req["rpm_max_torque"], c["rpm"].max(), color="orange", alpha=0.07,
               label=f"slip must be below b x rpm(max torque) (b={req['b']})")
    finite = c[["fe_torque_Nm", "analytic_fe_arc_Nm"]].replace([np.inf], np.nan).max().max()
    ax.set_ylim(0, max(8.0, min(1.3 * float(finite or 8.0), 60)))
    ax.set_xlabel("engine speed [rpm]")
    ax.set_ylabel("torque [N m]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def arc_stress_plot(res_curve, an, path: Path) -> Path:
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    a1.plot(res_curve["rpm"], res_curve["contact_arc_deg"], "k-")
    a1.set_xlabel("rpm")
    a1.set_ylabel("contact arc per shoe [deg]")
    a1.set_title(f"contact arc (nominal shoe arc {an.coupling['phi2_deg'] - an.coupling['phi1_deg']:.0f} deg)")
    a1.grid(alpha=0.3)
    a2.plot(res_curve["rpm"], res_curve["max_von_mises_Pa"] / 1e6, "r-")
    a2.set_xlabel("rpm")
    a2.set_ylabel("max von Mises [MPa]")
    a2.set_title("peak stress")
    a2.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def default_design_report(out: Path, concept_name: str | None = None) -> list[Path]:
    """Analyse the built-in default design and write plots, JSON and a Markdown summary."""
    from .clutch.analyze import analyze
    from .clutch.engine import EngineCurve
    from .geometry import MeshSettings, concepts, get_concept
    from .materials import get_material
    from .mesh import mesh_concept

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    name = concept_name or ("concept4" if "concept4" in concepts() else "concept1")
    c = get_concept(name)
    p = c.params()
    cm = mesh_concept(c, p, MeshSettings())
    engine = EngineCurve.default()
    mat = get_material("51CrV4")
    an = analyze(cm, p, mat, engine=engine, design=name)
    files = [torque_plot(an, engine, out / f"{name}_torque_rpm.png", f"{name}: torque vs engine speed (drum held)")]
    (out / f"{name}_analysis.json").write_text(json.dumps(an.to_json(), indent=2))
    files.append(out / f"{name}_analysis.json")
    an.curves.to_csv(out / f"{name}_curves.csv", index=False)
    files.append(out / f"{name}_curves.csv")
    return files
