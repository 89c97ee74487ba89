"""``clutchfem life``: the clutch over its life -- the starts, their slip energy, the wear-in of
the contact arc and the drift of engagement and slip as the shoe face wears
(:func:`clutchfem.life`)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Optional

import typer
from rich.markup import escape
from rich.table import Table

from .. import ClutchfemError, InputError, ParameterError
from . import options as O
from .common import (
    check_out_dir,
    console,
    design_from,
    engine_from,
    err,
    fail,
    operating_point,
    quantity,
    requirements_from,
    working,
    wrote,
)
from .life_options import DRIVE_OPTIONS, life_given, params_from, rebuild_from, wear_from

PANEL = "Life"
#: worn states whose fields ``--out`` keeps for its .pvd (``cf.life(fields=...)``)
FIELD_STATES = 12
@O.takes("concept", "set_", "mesh", "mesh_size", "model", "drum_radius", "thickness", "mu", "fidelity",
         "rotation", "engine", "idle_rpm", "a", "b", "out", "json_", "wear_regime", "wear_coefficient", "hardness", "drum_wear_coefficient", "drum_hardness",
         "max_wear_step", "wear_rate_change", "rebuild_depth")
def life(
    o,
    starts: str = typer.Option("100000", "--starts", metavar="N", help="number of starts of the life (1..1e8)",
                               rich_help_panel=PANEL),
    duty: Optional[Path] = typer.Option(None, "--duty", metavar="FILE", help="duty cycle: a TOML file with a [duty] "
                                        "table (starts_per_hour = \"20 1/h\", held_slips_per_hour, held_slip_duration "
                                        "= \"1 s\", cutting_share); default: starts only, chain running free",
                                        rich_help_panel=PANEL),
    engine_inertia: Optional[str] = typer.Option(None, "--engine-inertia", metavar="INERTIA", help="crank, flywheel "
                                                 "and clutch, e.g. 1e-3kg*m^2 (default 1e-3 kg m^2, ASSUMED)",
                                                 rich_help_panel=PANEL),
    driven_inertia: Optional[str] = typer.Option(None, "--driven-inertia", metavar="INERTIA", help="drum, sprocket "
                                                 "and chain on the drum axis (ASSUMED default)", rich_help_panel=PANEL),
    drag_torque: Optional[str] = typer.Option(None, "--drag-torque", metavar="TORQUE", help="chain drag, chain "
                                              "running free, e.g. 0.25N*m (ASSUMED default)", rich_help_panel=PANEL),
    cutting_torque: Optional[str] = typer.Option(None, "--cutting-torque", metavar="TORQUE", help="load of a start "
                                                 "in the cut (with --duty's cutting_share; ASSUMED default)",
                                                 rich_help_panel=PANEL),
    throttle_ramp: Optional[str] = typer.Option(None, "--throttle-ramp", metavar="TIME", help="time to open the "
                                                "throttle, e.g. 0.2s (ASSUMED default)", rich_help_panel=PANEL),
):
    """The clutch over its life: engagement and slip speed, torque and contact arc against the
    number of starts as the shoe face wears (Archard, k ASSUMED with its band), the slip energy
    of a start, and the first start at which a requirement is missed."""
    from .. import DriveLine, DutyCycle, dumps, life_files
    from .. import life as run

    try:
        check_out_dir(o.out)
        n = quantity("--starts", starts, "-", 1.0, 1e8)
        dc = None
        if duty is not None:
            try:
                dc = DutyCycle.from_toml(duty)
            except ParameterError as exc:
                raise ParameterError(exc.name, exc.value, exc.allowed, f"option --duty {duty}",
                                     shown=exc.shown) from None
            except InputError as exc:
                raise InputError(f"option --duty: {exc}") from None
        drive = params_from(DriveLine, {"--engine-inertia": engine_inertia, "--driven-inertia": driven_inertia,
                                    "--drag-torque": drag_torque, "--cutting-torque": cutting_torque,
                                    "--throttle-ramp": throttle_ramp}, DRIVE_OPTIONS)
        wear = wear_from(life_given(o))
        depth = rebuild_from(o.rebuild_depth)
        eng, idle = engine_from(o.engine, o.idle_rpm)
        req = requirements_from(o.a, o.b)
        op = operating_point(mu=o.mu, rotation=o.rotation, fidelity=o.fidelity)
        with working(f"life {o.concept or o.mesh}") as stage:
            stage("meshing")
            design = design_from(o.concept, o.set_, o.mesh, op=op, mesh_size=o.mesh_size, model=o.model,
                                 drum_radius=o.drum_radius, thickness=o.thickness)
            stage(f"{n:.0f} starts: the worn states")
            L = run(design, starts=n, duty=dc, engine=eng, drive=drive, wear=wear, requirements=req,
                    idle_rpm=idle, log=stage, fields=FIELD_STATES if o.out is not None else 0, **depth)
        if o.out is not None:
            wrote(life_files(L, o.out))
        if o.json_:
            print(dumps(L.to_json()))
            return
        print_table(L)
    except ClutchfemError as exc:
        fail(exc)
    except KeyboardInterrupt:  # typer would exit 130 silently
        err.print("interrupted (Ctrl-C): stopped; no file of this run was written")
        raise typer.Exit(code=130) from None


def _v(x, fmt: str, unit: str) -> str:
    return "-" if x is None or not math.isfinite(x) else f"{x:{fmt}} {unit}"


def print_table(L) -> None:
    """The answers new and at the end of the life, the first misses with their band."""
    t = Table(title=escape(f"{L.design}: the clutch over {L.starts[-1]:.0f} starts"
                           + ("" if L.hours is None else f" ({L.hours[-1]:.0f} h)")))
    t.add_column("quantity")
    t.add_column("new", justify="right")
    t.add_column("end of life", justify="right")
    rows = [("engagement speed", "engagement_rpm", ".0f", "rpm"), ("slip speed (drum held)", "slip_rpm", ".0f", "rpm"),
            (f"torque at {L.limits['rpm_max_engine_torque']:.0f} rpm", "torque_at_max_engine_torque_Nm", ".2f", "N m"),
            (f"contact arc at {L.limits['rpm_max_engine_torque']:.0f} rpm", "contact_arc_deg", ".1f", "deg"),
            ("slip energy of a free start", "slip_energy_per_start_J", ".1f", "J"),
            ("time to lock-up", "time_to_lockup_s", ".3f", "s"), ("peak slip power", "peak_slip_power_W", ".0f", "W"),
            ("shoe face temperature rise in a start", "shoe_face_rise_K", ".1f", "K")]
    for q, k, fmt, unit in rows:
        y = getattr(L, k)
        t.add_row(escape(q), _v(float(y[0]), fmt, unit), _v(float(y[-1]), fmt, unit))
    t.add_row("shoe worn (deepest) / drum worn", "0 um",
              f"{1e6 * L.worn_profile_m[-1].max():.1f} um / {1e6 * L.drum_worn_m[-1]:.2f} um")
    console.print(t)
    for q, v in L.first_miss.items():
        b = L.band["first_miss_band_starts"][q]
        lim = L.limits["engagement_min_rpm" if q == "engagement" else "slip_max_rpm"]
        what = f"{q} ({'>' if q == 'engagement' else '<'} {lim:.0f} rpm)"
        if v is None:
            console.print(escape(f"{what}: met over all {L.starts[-1]:.0f} starts"))
        else:
            console.print(escape(f"{what}: first missed at {v:.0f} starts (band over Archard's k: "
                                 f"{b[0]:.0f} .. {b[1]:.0f} starts)"))
    console.print(escape(f"energy balance of the starts: {L.energy_balance:.1e} (relative); "
                         f"{L.wear_steps['states']} wear states; {L.seconds:.1f} s"))
    console.print("[dim]ASSUMED: " + escape(f"Archard k = {L.band['wear_coefficient']:.1e} (band "
                                             f"{L.band['wear_coefficient_band'][0]:.0e}..."
                                             f"{L.band['wear_coefficient_band'][1]:.0e}), the drive line's "
                                             "inertias and loads, the throttle ramp (see --json 'assumptions')")
                  + "[/]")
    for note in L.notes:
        console.print(f"[dim]{escape(note)}[/]")
