"""The command line's shared options: one declaration each, grouped in ``--help`` panels.

Every command that takes a design takes it the same way: a CONCEPT argument with ``--set
name=value`` overrides, or ``--mesh FILE`` for your own part.  Every quantity option takes a
number with a unit suffix of its dimension (``--drum-radius 34.4mm``, ``--E 200GPa``,
``--idle-rpm 2700rpm``), read by the one parser of :mod:`clutchfem.core.units`.
"""

from __future__ import annotations

import copy
import functools
import inspect
from pathlib import Path
from types import SimpleNamespace
from typing import Annotated, List, Optional

import typer

__all__ = ["DESIGN", "ENGINE", "LIFE", "MODEL", "OPERATING", "OUTPUT", "SHARED", "STUDY", "takes"]

DESIGN = "Design"
OPERATING = "Operating point"
MODEL = "Model"
ENGINE = "Engine and requirements"
STUDY = "Study engine"
OUTPUT = "Output"
LIFE = "Life"

Concept = Annotated[Optional[str], typer.Argument(
    metavar="CONCEPT", help="concept name (clutchfem geometry --list); or give --mesh FILE", show_default=False)]
Set = Annotated[List[str], typer.Option(
    "--set", metavar="NAME=VALUE", help="concept parameter name=value with its unit (flexure_thickness=2.4mm, shoe_arc=80deg); repeat",
    rich_help_panel=DESIGN)]
Mesh = Annotated[Optional[Path], typer.Option(
    "--mesh", metavar="FILE", help="your own part instead of a concept: gmsh .msh (curve groups bore, contact) or STEP; x-y plane, "
                   "axis at the origin", rich_help_panel=DESIGN)]
MeshSize = Annotated[Optional[str], typer.Option(
    "--mesh-size", metavar="LENGTH", help="global element size, e.g. 0.8mm (default: 6 mm with flexures, fillets and the "
                 "contact surface refined for --fidelity best, a uniform 1.2 mm for fast)", rich_help_panel=DESIGN)]
Model = Annotated[str, typer.Option("--model", metavar="sector|full", help="sector (one cyclic sector) or full (360 deg)",
                                    rich_help_panel=DESIGN)]

DrumRadius = Annotated[Optional[str], typer.Option(
    "--drum-radius", metavar="LENGTH", help="drum inner radius of a --mesh part, e.g. 34.4mm (required with --mesh; a concept's: "
                          "--set drum_radius=...)", rich_help_panel=OPERATING)]
Thickness = Annotated[Optional[str], typer.Option(
    "--thickness", metavar="LENGTH", help="axial thickness of a --mesh part, e.g. 11mm (default 11 mm, ASSUMED; a concept's: --set "
                "thickness=...)",
    rich_help_panel=OPERATING)]
Mu = Annotated[Optional[str], typer.Option("--mu", metavar="NUMBER", help="shoe-drum friction coefficient (default 0.165, seed 000)",
                                           rich_help_panel=OPERATING)]
Rotation = Annotated[Optional[str], typer.Option("--rotation", metavar="ccw|cw", help="hub's sense of rotation: ccw (default) or cw",
                                                 rich_help_panel=OPERATING)]
MaterialName = Annotated[Optional[str], typer.Option(
    "--material", metavar="NAME", help="51CrV4 (default), titanium or aluminium", rich_help_panel=OPERATING)]
E = Annotated[Optional[str], typer.Option("--E", metavar="STRESS", help="Young's modulus, e.g. 200GPa (overrides the material's)",
                                          rich_help_panel=OPERATING)]
Nu = Annotated[Optional[str], typer.Option("--nu", metavar="NUMBER", help="Poisson's ratio (overrides the material's)",
                                           rich_help_panel=OPERATING)]
Rho = Annotated[Optional[str], typer.Option("--rho", metavar="DENSITY", help="density, e.g. 7850kg/m^3 (overrides the material's)",
                                            rich_help_panel=OPERATING)]
DrumWall = Annotated[Optional[str], typer.Option(
    "--drum-wall", metavar="LENGTH|rigid", help="elastic drum of this wall thickness, e.g. 2mm, or rigid (default: 2 mm steel "
                      "ring, ASSUMED, for --fidelity best; rigid for fast)", rich_help_panel=OPERATING)]
DrumState = Annotated[Optional[str], typer.Option(
    "--drum-state", metavar="held|spinning", help="elastic drum held (default) or spinning with the clutch", rich_help_panel=OPERATING)]

Softening = Annotated[Optional[str], typer.Option(
    "--spin-softening", metavar="NAME", help="prestress (default: spin softening + centrifugal pre-stress), ritz, exact, off, prestress-exact (the per-speed reference of prestress)",
    rich_help_panel=MODEL)]
Fidelity = Annotated[Optional[str], typer.Option(
    "--fidelity", metavar="best|fast|live", help="best (default; the environment variable CLUTCHFEM_FIDELITY sets "
                     "another): the best estimate of the real part (thick plane model with the 3-D thickness effect, "
                     "elastic 2 mm drum ASSUMED, refined mesh, peak stress and torque corrected for non-linearity); "
                     "fast: the uncorrected 2-D path (plane stress, rigid drum, 1.2 mm mesh; ~3-10x larger error "
                     "band, about half the time), for sweeps that want it; live: the best path's answers from the "
                     "reduced model of the design's region (clutchfem reduce; milliseconds, no mesh, its own measured "
                     "error in every band)", rich_help_panel=MODEL)]
Formulation = Annotated[Optional[str], typer.Option(
    "--formulation", metavar="NAME", help="auto (default: the fidelity's), plane-stress, plane-strain, thick (2-D mesh with "
                        "through-thickness modes) or 3d (P2 tetrahedra, --layers)", rich_help_panel=MODEL)]
Layers = Annotated[Optional[str], typer.Option("--layers", metavar="N", help="3d: element layers through half the thickness",
                                               rich_help_panel=MODEL)]

Engine = Annotated[Optional[Path], typer.Option(
    "--engine", metavar="CSV", help="engine torque CSV (columns rpm, torque [N m]); default: the built-in 56.5 cc saw curve "
                     "(ASSUMED shape)", rich_help_panel=ENGINE)]
IdleRpm = Annotated[Optional[str], typer.Option("--idle-rpm", metavar="SPEED", help="engine idle speed, e.g. 2700rpm (default 2700, "
                                                                   "ASSUMED)", rich_help_panel=ENGINE)]
A = Annotated[Optional[str], typer.Option("--a", metavar="NUMBER", help="requirement: engagement > a x idle rpm (default 1.3, ASSUMED)",
                                          rich_help_panel=ENGINE)]
B = Annotated[Optional[str], typer.Option(
    "--b", metavar="NUMBER", help="requirement: slip < b x rpm of max engine torque (default 1.0, ASSUMED)", rich_help_panel=ENGINE)]

Workers = Annotated[Optional[int], typer.Option(
    "--workers", metavar="N", help="local cluster of N process workers (default: one per core; 0: in this process, no Dask)",
    rich_help_panel=STUDY)]
Scheduler = Annotated[Optional[str], typer.Option(
    "--scheduler", metavar="ADDRESS", help="address of an existing dask.distributed scheduler, e.g. tcp://10.0.0.5:8786",
    rich_help_panel=STUDY)]

Out = Annotated[Optional[Path], typer.Option("--out", metavar="DIR", help="output folder (created if missing)",
                                             rich_help_panel=OUTPUT)]
Json = Annotated[bool, typer.Option("--json", help="print one JSON document on stdout", rich_help_panel=OUTPUT)]

# the wear of a life run (clutchfem life, tolerance --life)
WearRegime = Annotated[Optional[str], typer.Option(
    "--wear-regime", metavar="dry|lubricated", help="Archard's typical k and band: dry 1e-5 (1e-6..1e-4, default) "
    "or lubricated 1e-8 (1e-9..1e-7)", rich_help_panel=LIFE)]
WearCoefficient = Annotated[Optional[str], typer.Option(
    "--wear-coefficient", metavar="NUMBER", help="Archard's k of the shoe (> 0; default: the regime's, ASSUMED)",
    rich_help_panel=LIFE)]
Hardness = Annotated[Optional[str], typer.Option(
    "--hardness", metavar="STRESS", help="shoe hardness, e.g. 4.4GPa (default, ASSUMED)", rich_help_panel=LIFE)]
DrumWearCoefficient = Annotated[Optional[str], typer.Option(
    "--drum-wear-coefficient", metavar="NUMBER", help="Archard's k of the drum (default: the shoe's)",
    rich_help_panel=LIFE)]
DrumHardness = Annotated[Optional[str], typer.Option(
    "--drum-hardness", metavar="STRESS", help="drum hardness (default 4.4 GPa, ASSUMED)", rich_help_panel=LIFE)]
MaxWearStep = Annotated[Optional[str], typer.Option(
    "--max-wear-step", metavar="LENGTH", help="cap on the worn depth of one wear step, e.g. 2um (default 10 um)",
    rich_help_panel=LIFE)]
WearRateChange = Annotated[Optional[str], typer.Option(
    "--wear-rate-change", metavar="NUMBER", help="largest change of the wear rate in one wear step as a share of "
    "the largest rate (default 0.25; 0.01..10; halve it with --max-wear-step to see the step error)",
    rich_help_panel=LIFE)]
RebuildDepth = Annotated[Optional[str], typer.Option(
    "--rebuild-depth", metavar="LENGTH|never", help="worn depth after which the part is meshed again with its worn "
    "profile (default 0.1 mm; never: the wear stays in the contact gaps)", rich_help_panel=LIFE)]

#: the shared options: parameter name -> (declaration, default); a command names the ones it
#: takes with :func:`takes` instead of declaring them again
SHARED: dict[str, tuple] = {
    "concept": (Concept, None), "set_": (Set, []), "mesh": (Mesh, None), "mesh_size": (MeshSize, None),
    "model": (Model, "sector"), "drum_radius": (DrumRadius, None), "thickness": (Thickness, None),
    "mu": (Mu, None), "rotation": (Rotation, None), "material": (MaterialName, None), "E": (E, None),
    "nu": (Nu, None), "rho": (Rho, None), "drum_wall": (DrumWall, None), "drum_state": (DrumState, None),
    "softening": (Softening, None), "fidelity": (Fidelity, None), "formulation": (Formulation, None),
    "layers": (Layers, None), "engine": (Engine, None), "idle_rpm": (IdleRpm, None), "a": (A, None),
    "b": (B, None), "workers": (Workers, None), "scheduler": (Scheduler, None), "out": (Out, None),
    "json_": (Json, False),
    "wear_regime": (WearRegime, None), "wear_coefficient": (WearCoefficient, None), "hardness": (Hardness, None),
    "drum_wear_coefficient": (DrumWearCoefficient, None), "drum_hardness": (DrumHardness, None),
    "max_wear_step": (MaxWearStep, None), "wear_rate_change": (WearRateChange, None),
    "rebuild_depth": (RebuildDepth, None),
}


#: the commands a live design (``--fidelity live``: the reduced model) answers; the others
#: need the FE and refuse it, naming the fidelity that does
LIVE_COMMANDS = ("analyze", "tolerance", "calibrate", "guidelines", "optimize")


def takes(*names: str, live: bool = False):
    """A command that takes the shared options ``names`` (:data:`SHARED`, in this order) before
    its own: typer sees them in the command's signature (arguments, ``--help`` panels), and the
    function receives them as one namespace, its first parameter ``o`` (``o.concept``,
    ``o.set_``, ...), followed by its own options.  ``live``: the command answers
    ``--fidelity live`` (else it is refused as a usage error, before any work)."""
    unknown = [n for n in names if n not in SHARED]
    if unknown:
        raise KeyError(f"not shared options: {unknown}")

    def decorate(fn):
        sig = inspect.signature(fn, eval_str=True)
        own = list(sig.parameters.values())[1:]  # after ``o``
        shared = [inspect.Parameter(n, inspect.Parameter.POSITIONAL_OR_KEYWORD, annotation=SHARED[n][0],
                                    default=copy.copy(SHARED[n][1])) for n in names]
        params = shared + own

        @functools.wraps(fn)
        def command(**given):
            o = SimpleNamespace(**{n: given.pop(n) for n in names})
            asks_live = str(getattr(o, "fidelity", None) or "").strip().lower() == "live"
            if not live and asks_live:
                raise typer.BadParameter(f"live (the reduced model) answers {' and '.join(LIVE_COMMANDS)} only; "
                                         f"this command needs the FE: best (default) or fast", param_hint="'--fidelity'")
            if "concept" in names and not asks_live:  # a design command: the spinner first, then the FE
                from .common import working  # stack (~1.5 s); a live design needs none of it (docs/reduced.md)

                with working(f"{fn.__name__}: loading the FE stack"):
                    # analyze itself is light (a live answer needs none of the FE stack); check_speeds
                    # lives with the FE steps (analysis.torque), which load the mesh and the FE model
                    from .. import analyze, check_speeds  # noqa: F401
            return fn(o, **given)

        del command.__wrapped__  # typer reads the signature below, not the function's own
        command.__signature__ = sig.replace(parameters=params)
        command.__annotations__ = {p.name: p.annotation for p in params}
        return command

    return decorate
