"""Shared CLI plumbing: consoles, error exit, and loading a design (concept or user mesh)."""

from __future__ import annotations

from typing import Optional

import typer
from rich.console import Console

from ..errors import ClutchfemError

console = Console()
err = Console(stderr=True)


def fail(exc: Exception) -> None:
    err.print(f"[bold red]error:[/] {exc}")
    raise typer.Exit(code=2)


def mesh_settings(size: Optional[float], model: str):
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


def load_design(concept, set_, mesh, mesh_size, model, thickness, drum_radius):
    from ..geometry import get_concept
    from ..mesh import load_user_geometry, mesh_concept

    if (concept is None) == (mesh is None):
        raise ClutchfemError("give exactly one of --concept NAME or --mesh FILE")
    if concept is not None:
        c = get_concept(concept)
        p = c.Params.from_assignments(set_)
        cm = mesh_concept(c, p, mesh_settings(mesh_size, model))
        return cm, (drum_radius if drum_radius is not None else p.drum_radius), (thickness or p.thickness), c, p
    if set_:
        raise ClutchfemError("--set applies to --concept designs only")
    if thickness is None:
        thickness = 11e-3
    cm = load_user_geometry(mesh, mesh_size=mesh_size, thickness=thickness, drum_radius=drum_radius)
    return cm, drum_radius, thickness, None, None
