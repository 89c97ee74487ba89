"""``clutchfem solve``: FE speed sweep of a concept or a user mesh."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import List, Optional

import typer
from rich.table import Table

from ..errors import ClutchfemError
from .common import console, fail, load_design, material_from


def solve(
    concept: Optional[str] = typer.Option(None, "--concept", help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value"),
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="user mesh (.msh with groups bore/contact) or STEP"),
    drum_radius: Optional[float] = typer.Option(None, "--drum-radius", help="drum inner radius [m]"),
    mu: float = typer.Option(0.165, "--mu", help="shoe-drum friction coefficient [-]"),
    rotation: str = typer.Option("ccw", "--rotation", help="hub rotation: ccw or cw"),
    material: Optional[str] = typer.Option(None, "--material", help="51CrV4, titanium, aluminium"),
    E: Optional[float] = typer.Option(None, "--E", help="Young's modulus [Pa]"),
    nu: Optional[float] = typer.Option(None, "--nu", help="Poisson's ratio [-]"),
    rho: Optional[float] = typer.Option(None, "--rho", help="density [kg/m^3]"),
    thickness: Optional[float] = typer.Option(None, "--thickness", help="axial thickness [m] (user mesh default 0.011)"),
    rpm: str = typer.Option("0:14000:250", "--rpm", help="speeds: 8000 | 1000,2000 | start:stop:step [rpm]"),
    vtk: bool = typer.Option(False, "--vtk", help="write .vtu fields (and PNG renders) for the speeds in --vtk-rpm"),
    vtk_rpm: Optional[str] = typer.Option(None, "--vtk-rpm", help="speeds for VTK output (default: max of --rpm)"),
    out: Optional[Path] = typer.Option(None, "--out", help="output folder for tables/fields"),
    json_: bool = typer.Option(False, "--json", help="print one JSON object to stdout"),
    mesh_size: Optional[float] = typer.Option(None, "--mesh-size", help="global element size [m]"),
    model: str = typer.Option("sector", "--model", help="sector (cyclic) or full"),
    softening: str = typer.Option("modal", "--spin-softening", help="modal | exact | off"),
    no_stress: bool = typer.Option(False, "--no-stress", help="skip stress recovery"),
):
    """Speed sweep: engagement, contact forces and arc, friction torque (drum held), stresses."""
    from ..solver import ClutchSolver, parse_rpm

    try:
        mat = material_from(material, E, nu, rho)
        speeds = parse_rpm(rpm)
        cm, R, h, c, p = load_design(concept, set_, mesh, mesh_size, model, thickness, drum_radius)
        solver = ClutchSolver(cm, mat, drum_radius=R, mu=mu, rotation=rotation,
                              spin_softening=softening, thickness=h)
        res = solver.sweep(speeds, stresses=not no_stress)
        if out is not None:
            out.mkdir(parents=True, exist_ok=True)
            res.curve.to_csv(out / "curve.csv", index=False)
            if not res.shoes.empty:
                res.shoes.to_csv(out / "shoes.csv", index=False)
            (out / "result.json").write_text(json.dumps(res.to_json(), indent=2))
        if vtk:
            from ..output import write_vtk

            target = out or Path("out/solve")
            which = parse_rpm(vtk_rpm) if vtk_rpm else [float(speeds.max())]
            files = write_vtk(solver, which, target)
            if not json_:
                for f in files:
                    console.print(f"wrote {f}")
        if json_:
            print(json.dumps(res.to_json()))
        else:
            _print_sweep(res, mat)
    except ClutchfemError as exc:
        fail(exc)


def _print_sweep(res, mat) -> None:
    eng = res.engagement_rpm
    console.print(f"engagement speed: {eng:.0f} rpm (first touch at the shoe {res.first_touch})" if eng
                  else "engagement speed: none in the speed range (never touches the drum)")
    t = Table(title=f"speed sweep ({mat.name})")
    for col in ("rpm", "normal force [N]", "torque [N m]", "contact arc [deg]", "max von Mises [MPa]",
                "safety factor", "max displ. [mm]"):
        t.add_column(col, justify="right")
    df = res.curve
    step = max(1, len(df) // 15)
    for _, r in df.iloc[::step].iterrows():
        t.add_row(f"{r.rpm:.0f}", f"{r.normal_force_N:.1f}", f"{r.torque_Nm:.3f}", f"{r.contact_arc_deg:.1f}",
                  f"{r.max_von_mises_Pa / 1e6:.0f}" if not math.isnan(r.max_von_mises_Pa) else "-",
                  f"{r.safety_factor:.2f}" if not math.isnan(r.safety_factor) else "-",
                  f"{r.max_displacement_m * 1e3:.3f}")
    console.print(t)
    console.print(f"wall time: setup {res.timings['setup_s']:.2f} s, sweep {res.timings['sweep_s']:.2f} s")
