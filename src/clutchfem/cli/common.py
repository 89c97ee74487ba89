"""Shared CLI plumbing: consoles, error exit, output folders, the operating point from the
options, and loading a design (concept or user mesh)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console

from ..errors import ClutchfemError, InputError

console = Console()
err = Console(stderr=True)


def fail(exc: Exception) -> None:
    from rich.markup import escape

    err.print(f"[bold red]error:[/] {escape(str(exc))}")
    raise typer.Exit(code=2)


def check_out_dir(out: Optional[Path], option: str = "--out") -> Optional[Path]:
    """Refuse an output folder that cannot be written *before* any work: a file, a folder
    inside a file, or a folder without write permission (created if missing)."""
    if out is None:
        return None
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError(f"{option} {out}: is a file, not a folder")
    parent = out
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise InputError(f"{option} {out}: {parent} is a file, so no folder can be made inside it")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{option} {out}: no permission to write in {parent}")
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"{option} {out}: cannot create the folder ({exc.strerror})") from None
    return out


def operating_point(material=None, **given):
    """An :class:`~clutchfem.operating.OperatingPoint` from CLI option strings (None: not
    given), each parsed with its unit suffix and checked against its range."""
    from ..operating import OperatingPoint

    from ..errors import ParameterError

    try:
        values = OperatingPoint.parse_assignments([f"{k}={v}" for k, v in given.items() if v is not None])
        if material is not None:
            values["material"] = material
        return OperatingPoint(**values)
    except ParameterError as exc:  # name the option the user typed
        opt = {"softening": "--spin-softening"}.get(exc.name, "--" + str(exc.name).replace("_", "-"))
        raise ParameterError(exc.name, exc.value, exc.allowed, f"option {opt}") from None


def length_option(name: str, raw: Optional[str]):
    """A length option (``--mesh-size 0.8mm``) in m, or None."""
    if raw is None:
        return None
    from ..errors import ParameterError
    from ..geometry import MeshSettings

    try:
        value = MeshSettings._parse_value(name, raw)
        MeshSettings(**{name: value})
        return value
    except ParameterError as exc:
        raise ParameterError(exc.name, exc.value, exc.allowed, "option --mesh-size") from None


def mesh_settings(size, model: str):
    from ..geometry import MeshSettings

    kw = {"model": model}
    if size is not None:
        kw["size"] = size
    return MeshSettings(**kw)


def material_from(material: Optional[str], E, nu, rho):
    from ..materials import Material, get_material

    if E is not None or nu is not None or rho is not None:
        base = get_material(material) if material else get_material("51CrV4")
        return Material(name="user", E=E if E is not None else base.E, nu=nu if nu is not None else base.nu,
                        rho=rho if rho is not None else base.rho, yield_strength=base.yield_strength)
    return get_material(material or "51CrV4")


#: axial thickness assumed for a user mesh without --thickness [m]
USER_THICKNESS = 11e-3


def load_design(concept, set_, mesh, mesh_size, model, op, solver=None):
    """(Design, concept or None, params or None) for ``--concept NAME [--set ...]`` or
    ``--mesh FILE``; ``op`` the operating point."""
    from ..design import Design
    from ..geometry import get_concept
    from ..mesh import load_user_geometry, mesh_concept

    if (concept is None) == (mesh is None):
        raise InputError("give exactly one of --concept NAME or --mesh FILE")
    if concept is not None:
        c = get_concept(concept)
        p = c.Params.from_assignments(set_)
        cm = mesh_concept(c, p, mesh_settings(mesh_size, model))
        return Design(cm, op, params=p, solver=solver, name=c.name), c, p
    if set_:
        raise InputError("--set applies to --concept designs only")
    if op.thickness is None:
        op = op.replace(thickness=USER_THICKNESS)
    cm = load_user_geometry(mesh, mesh_size=mesh_size, thickness=op.thickness, drum_radius=op.drum_radius)
    return Design(cm, op, solver=solver, name=Path(mesh).name.rsplit(".", 1)[0]), None, None
