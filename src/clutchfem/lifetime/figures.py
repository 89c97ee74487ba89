"""The pictures and files of a life run (:func:`life_files`): ``<label>_life.json`` (the
:meth:`~clutchfem.lifetime.Life.to_json` document), ``<label>_life_answers.png`` (engagement and
slip speed against the starts with the requirement limits, the contact arc and the slip energy
per start) and ``<label>_life_pressure.png`` (the contact pressure along the shoe's arc new and
worn at the rpm of maximum engine torque, and the worn depth along the arc); with the fields
of worn states (``life(fields=...)``) also ``<label>_life.pvd``, the ParaView collection of
``<label>_life_fields/state_NNN.vtu`` (one per kept state, its time the number of starts: the
part's mesh as it stands with the displacement, von Mises stress and worn depth).  Drawn with
:func:`clutchfem.core.figures.figure` / :func:`~clutchfem.core.figures.save_figure` (the
picture rule: every number with its unit, no legend over the data)."""

from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import quoteattr

import meshio
import numpy as np

from ..core import InputError, figure, save_figure, write

__all__ = ["life_files"]


def _answers_png(L, path: Path) -> Path:
    fig, axs = figure(2, 2, figsize=(10.0, 7.5), layout="constrained")
    n = L.starts
    lim = L.limits
    (a_eng, a_slip), (a_arc, a_energy) = axs
    a_eng.plot(n, L.engagement_rpm, "o-", ms=3, color="C0", label="engagement speed")
    a_eng.axhline(lim["engagement_min_rpm"], color="C3", ls="--",
                  label=f"limit: > {lim['requirement_factors']['a']:g} x idle = {lim['engagement_min_rpm']:.0f} rpm")
    a_eng.set_title("engagement speed")
    a_eng.set_ylabel("engagement speed [rpm]")
    slip = np.where(np.isfinite(L.slip_rpm), L.slip_rpm, np.nan)
    a_slip.plot(n, slip, "o-", ms=3, color="C1", label="slip speed (drum held, full throttle)")
    a_slip.axhline(lim["slip_max_rpm"], color="C3", ls="--",
                   label=f"limit: < {lim['requirement_factors']['b']:g} x rpm of max engine torque = "
                         f"{lim['slip_max_rpm']:.0f} rpm")
    a_slip.set_title("slip speed")
    a_slip.set_ylabel("slip speed [rpm]")
    a_arc.plot(n, L.contact_arc_deg, "o-", ms=3, color="C2")
    a_arc.set_title(f"contact arc at {lim['rpm_max_engine_torque']:.0f} rpm")
    a_arc.set_ylabel("contact arc [deg]")
    a_energy.plot(n, L.slip_energy_per_start_J, "o-", ms=3, color="C4")
    a_energy.set_title("slip energy of one free start")
    a_energy.set_ylabel("slip energy per start [J]")
    for ax in (a_eng, a_slip, a_arc, a_energy):
        ax.set_xlabel("starts [-]")
        ax.grid(alpha=0.3)
    for ax in (a_eng, a_slip):
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=1)
    miss = ", ".join(f"{q} missed at {v:.0f} starts" if v is not None else f"{q} met throughout"
                     for q, v in L.first_miss.items())
    fig.suptitle(f"{L.design}: the clutch over {n[-1]:.0f} starts ({miss}; Archard k = "
                 f"{L.band['wear_coefficient']:.1e}, ASSUMED)", fontsize=10)
    return save_figure(fig, path)


def _pressure_png(L, path: Path) -> Path:
    fig, (ap, aw) = figure(1, 2, figsize=(10.0, 4.8), layout="constrained")
    ap.plot(L.pressure_s_new, L.pressure_new_Pa / 1e6, "o-", ms=3, color="C0", label="new (0 starts)")
    ap.plot(L.pressure_s_worn, L.pressure_worn_Pa / 1e6, "s-", ms=3, color="C1",
            label=f"worn ({L.starts[-1]:.0f} starts)")
    ap.set_title(f"contact pressure at {L.limits['rpm_max_engine_torque']:.0f} rpm")
    ap.set_xlabel("arc fraction along the shoe, root 0 .. tip 1 [-]")
    ap.set_ylabel("contact pressure [MPa]")
    ap.grid(alpha=0.3)
    ap.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    aw.plot(L.profile_s, 1e6 * L.worn_profile_m[-1], "-", color="C1")
    aw.set_title(f"worn depth of the shoe after {L.starts[-1]:.0f} starts")
    aw.set_xlabel("arc fraction along the shoe, root 0 .. tip 1 [-]")
    aw.set_ylabel("worn depth [um]")
    aw.grid(alpha=0.3)
    fig.suptitle(f"{L.design}: contact pressure new and worn; drum worn {1e6 * L.drum_worn_m[-1]:.2f} um",
                 fontsize=10)
    return save_figure(fig, path)


def _pvd(L, path: Path) -> list[Path]:
    """``path`` (.pvd) and one .vtu per kept state in ``<stem>_fields/`` beside it."""
    folder = path.with_name(path.stem + "_fields")
    if folder.exists() and not folder.is_dir():
        raise InputError(f"--out {path.parent}: {folder.name} exists and is not a folder: remove it or choose "
                         "another --out")
    folder.mkdir(exist_ok=True)
    rows, written = [], []
    for k, f in enumerate(L.fields):
        pts = np.zeros((len(f["points_m"]), 3))
        pts[:, :2] = f["points_m"]
        data = {"worn_depth_m": np.asarray(f["worn_m"], dtype=float)}
        if f["displacement_m"] is not None:
            data["displacement_m"] = np.asarray(f["displacement_m"], dtype=float)
            data["von_mises_Pa"] = np.asarray(f["von_mises_Pa"], dtype=float)
        cells = [("triangle", np.asarray(f["triangles"], dtype=np.int64))] if f["triangles"] is not None else \
            [("vertex", np.arange(len(pts), dtype=np.int64)[:, None])]
        vtu = folder / f"state_{k:03d}.vtu"
        meshio.write(vtu, meshio.Mesh(pts, cells, point_data=data), file_format="vtu")
        written.append(vtu)
        rows.append(f'    <DataSet timestep="{f["starts"]:.10g}" group="" part="0" '
                    f'file={quoteattr(f"{folder.name}/{vtu.name}")}/>')
    path.write_text('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
                    "  <Collection>\n" + "\n".join(rows) + "\n  </Collection>\n</VTKFile>\n")
    return [path, *written]


def life_files(L, out) -> list[Path]:
    """Write ``<label>_life.json``, ``<label>_life_answers.png`` and ``<label>_life_pressure.png``
    and, when the run kept the fields of worn states (``life(fields=...)``), the ParaView
    collection ``<label>_life.pvd`` with its .vtu files (module docstring) into the folder
    ``out``; returns their paths.

    Parameters
    ----------
    L : Life
        A life run (:func:`~clutchfem.lifetime.life`).
    out : path
        An existing folder.

    Returns
    -------
    list of Path

    Examples
    --------
    >>> import clutchfem as cf, tempfile
    >>> d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"))
    >>> L = cf.life(d, starts=500, rebuild_depth=None)
    >>> [p.name.split("_life")[1] for p in cf.life_files(L, tempfile.mkdtemp())]
    ['.json', '_answers.png', '_pressure.png']
    """
    out = Path(out)
    if not out.is_dir():
        raise InputError(f"life files: {out} is not a folder")
    stem = L.label or L.design
    paths = [out / f"{stem}_life{s}" for s in (".json", "_answers.png", "_pressure.png")]
    for p in paths:
        if p.exists() and not p.is_file():
            raise InputError(f"--out {out}: {p.name} exists and is not a file: remove it or choose another --out")
    write(paths[0], L.to_json(), indent=2)
    _answers_png(L, paths[1])
    _pressure_png(L, paths[2])
    if L.fields:
        paths += _pvd(L, out / f"{stem}_life.pvd")
    return paths
