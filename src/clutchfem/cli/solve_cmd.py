"""``clutchfem solve``: FE speed sweep of a concept or a user mesh."""

from __future__ import annotations

import math
from pathlib import Path
from typing import List, Optional

import numpy as np
import typer
from rich.markup import escape
from rich.table import Table

from ..core import ClutchfemError
from ..loadcase import OperatingPoint as _OP
from .common import check_out_dir, console, fail, length_option, load_design, material_from, operating_point


def solve(
    concept: Optional[str] = typer.Option(None, "--concept", help="concept name"),
    set_: List[str] = typer.Option([], "--set", help="concept parameter override name=value (unit suffix: mm, deg)"),
    mesh: Optional[Path] = typer.Option(None, "--mesh", help="user mesh (.msh with groups bore/contact) or STEP"),
    drum_radius: Optional[str] = typer.Option(None, "--drum-radius", help=_OP.help("drum_radius")),
    mu: Optional[str] = typer.Option(None, "--mu", help=_OP.help("mu")),
    rotation: Optional[str] = typer.Option(None, "--rotation", help=_OP.help("rotation")),
    material: Optional[str] = typer.Option(None, "--material", help=_OP.help("material")),
    E: Optional[float] = typer.Option(None, "--E", help="Young's modulus [Pa] (overrides the material's)"),
    nu: Optional[float] = typer.Option(None, "--nu", help="Poisson's ratio [-] (overrides the material's)"),
    rho: Optional[float] = typer.Option(None, "--rho", help="density [kg/m^3] (overrides the material's)"),
    thickness: Optional[str] = typer.Option(None, "--thickness", help=_OP.help("thickness")),
    rpm: str = typer.Option("0:14000:250", "--rpm", help="speeds [rpm]: 8000 | 1000,2000 | start:stop:step"),
    vtk: bool = typer.Option(False, "--vtk", help="write .vtu fields (and PNG renders) for the speeds in --vtk-rpm"),
    vtk_rpm: Optional[str] = typer.Option(None, "--vtk-rpm", help="speeds [rpm] for VTK output (default: max of --rpm)"),
    out: Optional[Path] = typer.Option(None, "--out", help="output folder for tables/fields"),
    json_: bool = typer.Option(False, "--json", help="print one JSON object to stdout"),
    mesh_size: Optional[str] = typer.Option(None, "--mesh-size", help="global element size [m] (unit suffix: mm)"),
    model: str = typer.Option("sector", "--model", help="sector (cyclic) or full"),
    softening: Optional[str] = typer.Option(None, "--spin-softening", help=_OP.help("softening")),
    formulation: Optional[str] = typer.Option(None, "--formulation", help=_OP.help("formulation")),
    layers: Optional[str] = typer.Option(None, "--layers", help=_OP.help("layers")),
    drum_wall: Optional[str] = typer.Option(None, "--drum-wall", help=_OP.help("drum_wall")),
    drum_state: Optional[str] = typer.Option(None, "--drum-state", help=_OP.help("drum_state")),
    no_stress: bool = typer.Option(False, "--no-stress", help="skip stress recovery"),
    no_errors: bool = typer.Option(False, "--no-errors", help="skip the error estimate (a mesh twice as fine)"),
):
    """Speed sweep: engagement, contact forces and arc, friction torque (drum held), stresses."""
    from ..accuracy import sweep_errors
    from ..core import dumps, write
    from ..loadcase import design_inputs, model_warnings, parse_rpm

    try:
        check_out_dir(out)
        mat = material_from(material, E, nu, rho)
        op = operating_point(mat, drum_radius=drum_radius, mu=mu, rotation=rotation, thickness=thickness,
                             softening=softening, formulation=formulation, rpm=rpm,
                             layers=layers, drum_wall=drum_wall, drum_state=drum_state)
        speeds = op.speeds()
        which = parse_rpm(vtk_rpm) if vtk_rpm else np.array([float(speeds.max())])
        if vtk:
            speeds = np.union1d(speeds, which)
        if concept is not None and op.drum_radius is not None:
            raise ClutchfemError("the drum radius of a concept is one of its geometry parameters (its "
                                 "clearance is built against it): use --set drum_radius=...; --drum-radius "
                                 "applies to --mesh only")
        size = length_option("size", mesh_size)
        design, c, p = load_design(concept, set_, mesh, size, model, op)
        res = design.sweep(speeds, stresses=not no_stress)
        warns = list(res.warnings) + model_warnings(res, design.model.material.yield_strength)
        errs = sweep_errors(design, res) if not no_errors and res.contact is not None else {}
        doc = {**res.to_json(), "warnings": warns, "errors": errs, "inputs": design_inputs(design)}
        if out is not None:
            res.curve.to_csv(out / "curve.csv", index=False)
            if not res.shoes.empty:
                res.shoes.to_csv(out / "shoes.csv", index=False)
            write(out / "result.json", doc, indent=2)
        if vtk:
            from ..fe import write_vtk

            target = check_out_dir(out or Path("out/solve"))
            files = write_vtk(res, which, target)
            if not json_:
                for f in files:
                    console.print(f"wrote {escape(str(f))}")
        if json_:
            print(dumps(doc))
        else:
            _print_sweep(res, mat)
            _print_errors(errs)
            for w in warns:
                console.print(f"[bold red]WARNING:[/] {escape(w)}")
    except ClutchfemError as exc:
        fail(exc)


def _print_sweep(res, mat) -> None:
    eng = res.engagement_rpm
    if res.contact is None:
        console.print("engagement speed: not computed (no drum: free spin only)")
    elif eng is not None:
        console.print(f"engagement speed: {eng:.0f} rpm (first touch at the shoe {res.first_touch})")
    else:
        lim = f" below the divergence speed {res.divergence_rpm:.0f} rpm" if res.divergence_rpm else ""
        console.print(f"engagement speed: none: the shoes never reach the drum{lim}")
    t = Table(title=f"speed sweep ({escape(mat.name)})")
    for col in ("rpm", "normal force [N]", "torque [N m]", "contact arc [deg]", "max von Mises [MPa]",
                "safety factor [-]", "max displ. [mm]"):
        t.add_column(escape(col), justify="right")
    df = res.curve
    step = max(1, len(df) // 15)
    for _, r in df.iloc[::step].iterrows():
        t.add_row(f"{r.rpm:.0f}", f"{r.normal_force_N:.1f}", f"{r.torque_Nm:.3f}", f"{r.contact_arc_deg:.1f}",
                  f"{r.max_von_mises_Pa / 1e6:.0f}" if not math.isnan(r.max_von_mises_Pa) else "-",
                  f"{r.safety_factor:.2f}" if not math.isnan(r.safety_factor) else "-",
                  f"{r.max_displacement_m * 1e3:.3f}")
    console.print(t)
    tm = res.timings
    console.print(f"wall time: model {tm.get('assemble_s', 0) + tm.get('factorize_s', 0):.2f} s, "
                  f"sweep {tm['sweep_s']:.2f} s")



def _print_errors(errs: dict) -> None:
    if not errs:
        return
    labels = {"engagement_rpm": ("engagement speed", 1.0, "rpm", ".0f"),
              "torque_Nm": (f"torque at {errs.get('at_rpm', 0):.0f} rpm", 1.0, "N m", ".3f"),
              "max_von_mises_Pa": (f"peak von Mises at {errs.get('at_rpm', 0):.0f} rpm", 1e-6, "MPa", ".0f")}
    for k, (lab, sc, u, f) in labels.items():
        e = errs.get(k)
        if not e or e["value"] is None:
            continue
        d = "n/a" if e["discretisation"] is None else f"{e['discretisation'] * sc:{f}}"
        console.print(f"{lab}: {e['value'] * sc:{f}} {u} +- {e['total'] * sc:{f}} {u} (mesh {d}, model form "
                      f"{e['model_form'] * sc:{f}}: " + ", ".join(f"{t} {100 * v:+.1f} %" for t, v in
                                                                 e["model_form_relative"].items()) + ")")
