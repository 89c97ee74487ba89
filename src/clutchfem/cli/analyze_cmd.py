"""``clutchfem analyze``: the clutch designer's answers for one design."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import List, Optional

import typer
from rich.table import Table

from ..errors import ClutchfemError
from .common import console, fail, load_design, material_from


def analyze(
    concept: Optional[str] = typer.Option(None, "--concept", help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value"),
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="(not yet: analyze needs concept mass properties)"),
    engine: Optional[Path] = typer.Option(None, "--engine", help="engine torque CSV (rpm, torque N m)"),
    mu: float = typer.Option(0.165, "--mu", help="friction coefficient [-]"),
    rotation: str = typer.Option("ccw", "--rotation", help="ccw or cw"),
    a: float = typer.Option(1.3, "--a", help="requirement: engagement > a x idle rpm (ASSUMED default)"),
    b: float = typer.Option(1.0, "--b", help="requirement: slip < b x rpm of max torque (ASSUMED default)"),
    material: Optional[str] = typer.Option(None, "--material", help="51CrV4, titanium, aluminium"),
    json_: bool = typer.Option(False, "--json", help="print the JSON document"),
    out: Optional[Path] = typer.Option(None, "--out", help="folder for plots and tables"),
    mesh_size: Optional[float] = typer.Option(None, "--mesh-size", help="global element size [m]"),
):
    """Engagement (static, with ripple), slip rpm, torque margin, stress, plus/minus character."""
    from ..clutch.analyze import Requirements, analyze as run
    from ..clutch.engine import EngineCurve

    try:
        if mesh is not None:
            raise ClutchfemError("analyze needs --concept NAME (user meshes carry no shoe mass properties yet; "
                                 "use 'clutchfem solve --mesh' for their FE curves)")
        cm, _, _, c, p = load_design(concept, set_, None, mesh_size, "sector", None, None)
        eng = EngineCurve.from_csv(engine) if engine else EngineCurve.default()
        an = run(cm, p, material_from(material, None, None, None), mu=mu, rotation=rotation, engine=eng,
                 requirements=Requirements(a=a, b=b), design=c.name)
        if out is not None:
            from ..report import torque_plot

            out.mkdir(parents=True, exist_ok=True)
            torque_plot(an, eng, out / f"{c.name}_torque_rpm.png", f"{c.name}: torque vs engine speed")
            an.curves.to_csv(out / f"{c.name}_curves.csv", index=False)
            (out / f"{c.name}_analysis.json").write_text(json.dumps(an.to_json(), indent=2))
        if json_:
            print(json.dumps(an.to_json()))
            return
        t = Table(title=f"{c.name}: clutch answers")
        t.add_column("quantity")
        t.add_column("value", justify="right")
        fmt = lambda v, f, u: "-" if v is None or (isinstance(v, float) and math.isnan(v)) else f"{v:{f}} {u}"
        t.add_row("engagement speed (static)", fmt(an.engagement_rpm, ".0f", "rpm"))
        t.add_row("engagement speed (with 2-stroke ripple, 3 sigma)", fmt(an.engagement_rpm_with_ripple, ".0f", "rpm"))
        t.add_row("slip speed (drum held, full throttle)", fmt(an.slip_rpm, ".0f", "rpm") + f"  ({an.slip_note})")
        t.add_row("torque at rpm of max engine torque", fmt(an.torque_at_max_engine_torque_Nm, ".2f", "N m"))
        t.add_row("torque margin over max engine torque", fmt(an.torque_margin_Nm, ".2f", "N m"))
        t.add_row(f"max von Mises at {an.max_stress_rpm:.0f} rpm", fmt(an.max_von_mises_Pa / 1e6, ".0f", "MPa"))
        t.add_row("safety factor against yield", fmt(an.safety_factor, ".2f", ""))
        t.add_row("slip power (heat) at slip speed", fmt(an.slip_power_W, ".0f", "W"))
        t.add_row("shoe character (FE, friction on vs off)", an.shoe_character)
        t.add_row("first contact on the shoe", str(an.first_touch))
        t.add_row("engagement > a x idle", str(an.requirements["engagement_ok"]))
        t.add_row("slip < b x rpm(max torque)", str(an.requirements["slip_ok"]))
        console.print(t)
    except ClutchfemError as exc:
        fail(exc)
