"""Shared CLI plumbing: consoles, error exit, output folders, the operating point from the
options, and loading a design (concept or user mesh)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Optional

import typer
from rich.console import Console

from ..core import InputError

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
    from ..core import ParameterError
    from ..loadcase import OperatingPoint

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
    from ..core import ParameterError
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
    from ..core import Material, get_material

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
    from ..geometry import get_concept
    from ..loadcase import Design
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


def grouped_assignments(items, groups: dict, option: str) -> dict:
    """``name=value`` strings (``option``, e.g. ``--thermal``) spread over several parameter
    sets: ``groups`` maps a prefix to a :class:`~clutchfem.params.ParamSet` class.  A name
    may be written plain when exactly one set has it (``face_htc=80``) and must carry its
    prefix when several do (``drum.conductivity=16``); units as in ``--set``.  Returns
    {prefix: {name: value}}; unknown, ambiguous or repeated names are refused, naming the
    option and every known name."""
    from ..core import ParameterError

    owners: dict[str, list[str]] = {}
    for prefix, cls in groups.items():
        for name in cls.model_fields:
            owners.setdefault(name, []).append(prefix)
    known = ", ".join(sorted(f"{p}.{n}" if len(owners[n]) > 1 else n
                             for p, c in groups.items() for n in c.model_fields))
    raw: dict[str, list[str]] = {p: [] for p in groups}
    for item in items:
        if "=" not in item:
            raise ParameterError(item, None, "expected the form name=value", f"option {option}")
        name, value = (s.strip() for s in item.split("=", 1))
        prefix, _, bare = name.rpartition(".")
        if prefix:
            if prefix not in groups or bare not in groups[prefix].model_fields:
                raise ParameterError(name, value, f"unknown parameter; known: {known}", f"option {option}")
        else:
            where = owners.get(bare)
            if not where:
                raise ParameterError(name, value, f"unknown parameter; known: {known}", f"option {option}")
            if len(where) > 1:
                raise ParameterError(name, value, "ambiguous: write " + " or ".join(f"{p}.{bare}" for p in where),
                                     f"option {option}")
            prefix = where[0]
        raw[prefix].append(f"{bare}={value}")
    out = {}
    for prefix, cls in groups.items():
        try:
            out[prefix] = cls.parse_assignments(raw[prefix])
        except ParameterError as exc:
            raise ParameterError(exc.name, exc.value, exc.allowed, f"option {option} ({cls.context})") from None
    return out


def build_params(cls, values: dict, option: str):
    """``cls(**values)``, its errors naming the option the user typed."""
    from ..core import ParameterError

    try:
        return cls(**values)
    except ParameterError as exc:
        raise ParameterError(exc.name, exc.value, exc.allowed, f"option {option} ({cls.context})") from None


def describe_groups(groups: dict) -> list[tuple[str, str, str, str]]:
    """(name as typed, unit, default, allowed and meaning) of every parameter of ``groups``."""
    owners: dict[str, int] = {}
    for cls in groups.values():
        for n in cls.model_fields:
            owners[n] = owners.get(n, 0) + 1
    rows = []
    for prefix, cls in groups.items():
        for r in cls.describe():
            name = f"{prefix}.{r['name']}" if owners[r["name"]] > 1 else r["name"]
            rows.append((name, r["unit"], str(r["default"]), f"{r['allowed']}: {r['description']}"))
    return rows
