"""``clutchfem solve``: the FE speed sweep of a design (a concept or a user mesh)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional

import numpy as np
import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError
from . import options as O
from .common import check_out_dir, console, design_from, fail, material_from, operating_point, working, wrote


@O.takes("concept", "set_", "mesh", "mesh_size", "model", "drum_radius", "thickness", "mu", "rotation",
         "material", "E", "nu", "rho", "drum_wall", "drum_state", "softening", "fidelity", "formulation",
         "layers", "out", "json_")
def solve(
    o,
    rpm: str = typer.Option("0:14000:250", "--rpm", help="speeds in rpm: 8000 | 1000,2000 | start:stop:step",
                            rich_help_panel=O.OPERATING),
    no_stress: bool = typer.Option(False, "--no-stress", help="skip stress recovery", rich_help_panel=O.MODEL),
    no_errors: bool = typer.Option(False, "--no-errors", help="skip the error estimate (a mesh twice as fine)",
                                   rich_help_panel=O.MODEL),
    vtk: bool = typer.Option(False, "--vtk", help="write the fields for ParaView: one .pvd time series over the "
                             "speeds of --vtk-rpm (a .vtu of the whole part per speed, SI units, zone ids; 3d: "
                             "quadratic tetrahedra over the full thickness) and a PNG of von Mises at the highest "
                             "of them (plane models)", rich_help_panel=O.OUTPUT),
    vtk_rpm: Optional[str] = typer.Option(None, "--vtk-rpm", help="speeds in rpm of the .pvd series (default: the "
                                          "speeds of --rpm, at most 30 of them: every k-th and the highest)", rich_help_panel=O.OUTPUT),
):
    """Speed sweep of a design: engagement, contact forces and arc, friction torque (drum
    held), stresses, each speed solved exactly (the answers do not depend on the grid)."""
    from .. import dumps, field_picture, model_warnings, parse_rpm, sweep_errors, write_vtk

    try:
        check_out_dir(o.out)
        mat = material_from(o.material, o.E, o.nu, o.rho)
        op = operating_point(mu=o.mu, rotation=o.rotation, softening=o.softening, fidelity=o.fidelity,
                             formulation=o.formulation, rpm=rpm,
                             layers=o.layers, drum_wall=o.drum_wall, drum_state=o.drum_state, material=mat)
        speeds = op.speeds()
        which = parse_rpm(vtk_rpm) if vtk_rpm else series_speeds(speeds)
        if vtk:
            speeds = np.union1d(speeds, which)
        with working(f"solve {o.concept or o.mesh}") as stage:
            stage("meshing")
            design = design_from(o.concept, o.set_, o.mesh, op=op, mesh_size=o.mesh_size, model=o.model,
                                 drum_radius=o.drum_radius, thickness=o.thickness)
            stage(f"{len(speeds)} speed" + ("s" if len(speeds) != 1 else ""))
            res = design.sweep(speeds, stresses=not no_stress)
            warns = list(res.warnings) + model_warnings(res, design.model.material.yield_strength)
            stage("discretisation and model-form errors")
            errs = sweep_errors(design, res) if not no_errors and res.contact is not None else {}
        label = design.label
        doc = {**res.to_json(), "label": label, "design_hash": design.hash, "warnings": warns, "errors": errs, "inputs": design.inputs()}
        files, notes = [], []
        if o.out is not None:
            res.curve.to_csv(o.out / f"{label}_curve.csv", index=False)
            files.append(o.out / f"{label}_curve.csv")
            if not res.shoes.empty:
                res.shoes.to_csv(o.out / f"{label}_shoes.csv", index=False)
                files.append(o.out / f"{label}_shoes.csv")
            (o.out / f"{label}_result.json").write_text(dumps(doc, indent=2))
            files.append(o.out / f"{label}_result.json")
        if vtk:
            target = check_out_dir(o.out or Path("out/solve"))
            files += write_vtk(res, which, target, stem=label, cm=design.cm)
            top = float(np.max(which))
            if design.model.formulation != "3d":
                files.append(field_picture(res, top, target / f"{label}_fields_{int(round(top))}rpm.png",
                                           cm=design.cm, title=f"{label}: von Mises at {top:.0f} rpm"))
            else:  # the picture is a plane drawing; the 3-D fields are for ParaView
                notes.append("--vtk with --formulation 3d: no PNG (the picture draws a plane model); open the .pvd "
                             "in ParaView (quadratic tetrahedra, the whole part mirrored to the full thickness)")
        wrote(files)
        if o.json_:
            print(dumps(doc))
            return
        for n in notes:
            console.print(f"note: {escape(n)}")
        _print_sweep(res, mat)
        _print_errors(errs)
        for w in warns:
            console.print(f"[bold red]WARNING:[/] {escape(w)}")
    except ClutchfemError as exc:
        fail(exc)


#: frames of the default .pvd series (about 1.6 MB a frame for concept 1's whole part)
MAX_FRAMES = 30


def series_speeds(speeds) -> np.ndarray:
    """The default speeds of the .pvd series: those of --rpm, every k-th of them (and the
    highest) when there are more than :data:`MAX_FRAMES`."""
    s = np.sort(np.asarray(speeds, dtype=float))
    if len(s) <= MAX_FRAMES:
        return s
    step = math.ceil(len(s) / MAX_FRAMES)
    return np.union1d(s[::step], s[-1:])


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
