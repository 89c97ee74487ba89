"""The slip test, step by step: :func:`heat_transient` runs repeated slip events with cooling
pauses on the heat model and gathers the answer (:class:`~.result.SlipHeatResult`).

Scenario (thesis test, issue 14): chain brake on (drum held), full throttle; the engine
settles at the slip speed omega and the shoes rub the drum at v = omega R_d.  The friction
power mu v lam_i of every contact node (:mod:`.load`) is split between the shoe and the
drum (:mod:`.partition`); the shoe's share conducts into the part (:mod:`.assembly`), which
loses heat through its two faces and into the crankshaft.  Repeated slip events with
cooling pauses show whether heat accumulates.

Steps of :func:`heat_transient`:

1. check the inputs; assemble the heat model;
2. the friction power per node (gamma = 1) and the patch length L along the drum
   (int phi_i ds over the loaded contact nodes, per shoe);
3. the probes (hottest shoe-face node, flux-weighted patch mean, hottest flexure node,
   hub mean, part mean);
4. the heat partition gamma, evaluated once at t_ref = one slip event and kept for the
   whole run (the equation stays linear and the energy split exact).  Its FE shoe side is
   the flux-weighted mean patch temperature rise of a homogeneous pre-run of one event,
   divided by the mean patch flux q = P_fric / (n L h);
5. the initial field (steady state of the idling clutch by default);
6. the run, with equal steps per slip event (even, for the 2 dt estimate) and the pause
   likewise; the time error is estimated by repeating the run with 2 dt (Richardson for
   order 2: err ~ max |T_dt - T_2dt| / 3 over the probes, ``time_error_estimate_K``);
7. the answers: energy balance (whole part), peaks and their places, the cycle table,
   the hot yield strength.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Literal

import numpy as np
from skfem import Basis, ElementTriP2, FacetBasis, LinearForm, asm

from ..core import InputError, ParameterError
from ..mesh import ClutchMesh, describe_node, p2_basis, zone_of_node
from .assembly import HeatModel, build_heat_model
from .load import SlipHeatLoad
from .params import (
    ASSUMED,
    DrumThermal,
    SlipScenario,
    ThermalEnvironment,
    ThermalMaterial,
    finite_positive,
    hot_yield_ratio,
)
from .partition import HeatPartition, heat_partition
from .result import SlipHeatResult
from .stepping import Probe, Run, Segment, integrate, steady_state

__all__ = ["heat_transient"]


#: full temperature fields kept over a run (evenly spaced, plus every slip/pause end): the
#: frames of its ParaView time series
FRAMES = 60


def heat_transient(cm: ClutchMesh, thickness: float | None, material: ThermalMaterial | None,
              load: SlipHeatLoad, *, seconds: float | None = None, cycles: int | None = None,
              pause: float | None = None, scenario: SlipScenario | None = None,
              env: ThermalEnvironment | None = None, drum: DrumThermal | None = None,
              heat_fraction: float | None = None,
              shoe_side: Literal["fe", "semi_infinite"] = "fe") -> SlipHeatResult:
    """Repeated slip events (``cycles`` x [``seconds`` of slip, ``pause`` of cooling]) with the
    friction heat of ``load`` entering the part ``cm`` (thickness [m]; None: the mesh's).

    ``heat_fraction``: the part's share gamma of the friction heat (0: no heat, a cooling
    what-if), or None to compute it
    with :func:`heat_partition` (``shoe_side`` 'fe': the part's own FE response at the end
    of one slip event, or 'semi_infinite').  ``seconds``/``cycles``/``pause`` override the
    fields of ``scenario`` (:class:`SlipScenario`).  See the module docstring for the steps."""
    timings = {}
    t_start = time.perf_counter()
    material = material or ThermalMaterial()
    env = env or ThermalEnvironment()
    drum = drum or DrumThermal()
    sc, heat_fraction, h = _checked_inputs(cm, thickness, load, drum, scenario, seconds, cycles, pause,
                                           heat_fraction, shoe_side)
    model = build_heat_model(cm, h, material, env, no_edge_nodes=_loaded(load))
    timings["assemble_s"] = model.timings["assemble_s"]
    patch = _patch(model, load)
    probes, defs, flex_nodes = _probes(model, patch)
    t0 = time.perf_counter()
    part = _partition(model, material, drum, load, patch, sc, heat_fraction, shoe_side)
    timings["partition_s"] = time.perf_counter() - t0
    T0, initial = _initial_field(model, env)
    run, err = _run(model, T0, part.fraction_part * patch.Q1, sc, probes, timings)
    return _answer(model, material, env, load, sc, patch, part, defs, flex_nodes, T0, initial, run, err,
                   timings, t_start)


# ---------------------------------------------------------------------------------------
# 1. inputs
# ---------------------------------------------------------------------------------------
def _checked_inputs(cm, thickness, load, drum, scenario, seconds, cycles, pause, heat_fraction,
                    shoe_side) -> tuple[SlipScenario, float | None, float]:
    """(scenario with the overrides, heat fraction, thickness), every input checked."""
    if not isinstance(load, SlipHeatLoad):
        raise InputError(f"load must be a SlipHeatLoad (got {type(load).__name__})")
    if not isinstance(drum, DrumThermal):
        raise InputError(f"drum must be a DrumThermal (got {type(drum).__name__})")
    sc = scenario or SlipScenario()
    over = {k: v for k, v in (("seconds", seconds), ("cycles", cycles), ("pause", pause)) if v is not None}
    if over:
        sc = sc.replace(**over)
    if shoe_side not in ("fe", "semi_infinite"):
        raise ParameterError("shoe_side", shoe_side, "one of 'fe', 'semi_infinite'")
    if heat_fraction is not None:
        heat_fraction = finite_positive("heat_fraction", heat_fraction, "a share of the friction heat in [0, 1]",
                                        zero_ok=True)
        if heat_fraction > 1.0:
            raise ParameterError("heat_fraction", heat_fraction, "a share of the friction heat in [0, 1]")
    h = thickness if thickness is not None else cm.thickness
    if h is None:
        raise ParameterError("thickness", None, "an axial thickness > 0 m (the mesh carries none)")
    N = p2_basis(cm.mesh).N
    if load.node_index.max() >= N:
        raise ParameterError("node_index", int(load.node_index.max()), f"a node id of this mesh, 0 <= id < {N}")
    return sc, heat_fraction, h


def _loaded(load: SlipHeatLoad) -> np.ndarray:
    """The nodes that carry a contact force."""
    return load.node_index[load.lam_N > 0]


# ---------------------------------------------------------------------------------------
# 2. the patch
# ---------------------------------------------------------------------------------------
@dataclass
class _Patch:
    Q1: np.ndarray  # friction power per node, gamma = 1 [W]
    P_model: float  # its sum (the model: sector or full part) [W]
    L_model: float  # loaded length of the contact surface in the model [m]
    L_patch: float  # per shoe [m]
    n_total: int  # shoes of the whole clutch
    contact_facets: np.ndarray


def _patch(model: HeatModel, load: SlipHeatLoad) -> _Patch:
    """Step 2: the friction power per node (gamma = 1) and the patch geometry."""
    cm, N = model.cm, model.N
    mesh = cm.mesh
    Q1 = np.zeros(N)
    np.add.at(Q1, load.node_index, load.nodal_power_W)
    contact_f = cm.boundary("contact") if "contact" in (mesh.boundaries or {}) else mesh.boundary_facets()
    fb = FacetBasis(mesh, ElementTriP2(), facets=contact_f, intorder=5)
    trib = asm(LinearForm(lambda v, w: v), fb)
    L_model = float(trib[_loaded(load)].sum())
    if not L_model > 0:
        raise InputError("heat_transient: the loaded nodes do not lie on the contact surface (zero patch length)")
    n_model = cm.n_shoes_model if cm.sector_angle is not None else max(cm.n_shoes_total, 1)
    return _Patch(Q1=Q1, P_model=float(Q1.sum()), L_model=L_model, L_patch=L_model / n_model,
                  n_total=max(cm.n_shoes_total, 1), contact_facets=contact_f)


# ---------------------------------------------------------------------------------------
# 3. probes
# ---------------------------------------------------------------------------------------
def _probes(model: HeatModel, patch: _Patch) -> tuple[list[Probe], dict, np.ndarray | None]:
    """Step 3: (probes, their definitions, the flexure nodes or None)."""
    cm, basis = model.cm, model.basis
    mesh = cm.mesh
    sub = mesh.subdomains or {}
    zones = model.node_zone()
    flex_names = sorted(n for n in sub if n.startswith("flexure"))
    flex_nodes = np.unique(np.concatenate([zones[n] for n in flex_names])) if flex_names else None
    face_nodes = np.unique(basis.get_dofs(patch.contact_facets).all())
    probes = [Probe("shoe_face", nodes=face_nodes),
              Probe("patch_mean", weights=patch.Q1 / patch.P_model)]
    defs = {"shoe_face_C": "hottest P2 node of the 'contact' surface",
            "part_max_C": "hottest P2 node of the part"}
    if flex_nodes is not None:
        probes.append(Probe("flexure", nodes=flex_nodes))
        defs["flexure_C"] = "hottest P2 node of the zones " + ", ".join(flex_names)
    if "hub" in sub:
        wh = asm(LinearForm(lambda v, w: v), Basis(mesh, ElementTriP2(), elements=np.asarray(sub["hub"]), intorder=4))
        defs["hub_C"] = "area-weighted mean temperature of the 'hub' zone"
    else:
        wh = asm(LinearForm(lambda v, w: v), FacetBasis(mesh, ElementTriP2(), facets=cm.boundary("bore"), intorder=5))
        defs["hub_C"] = "length-weighted mean temperature of the bore edge (the mesh has no 'hub' zone)"
    probes.append(Probe("hub", weights=wh / wh.sum()))
    wa = asm(LinearForm(lambda v, w: v), basis)  # int phi_i dA: area (= mass) weights
    probes.append(Probe("part_mean", weights=wa / wa.sum()))
    defs["part_mean_C"] = "area-weighted mean temperature of the part (its heat content / (rho c h A))"
    return probes, defs, flex_nodes


# ---------------------------------------------------------------------------------------
# 4. heat partition, 5. initial field, 6. the run
# ---------------------------------------------------------------------------------------
def _segments(sc: SlipScenario, factor: int = 1) -> list[Segment]:
    """Every slip event and pause with its number of steps (/ ``factor``: 2 for the 2 dt run)."""
    n_slip, n_pause = sc.steps()
    segs = []
    for _ in range(sc.cycles):
        segs.append(Segment(sc.seconds, n_slip // factor, True))
        if n_pause:
            segs.append(Segment(sc.pause, n_pause // factor, False))
    return segs


def _partition(model: HeatModel, material: ThermalMaterial, drum: DrumThermal, load: SlipHeatLoad,
               patch: _Patch, sc: SlipScenario, heat_fraction: float | None, shoe_side: str) -> HeatPartition:
    """The part's share of the friction heat: given, or from :func:`heat_partition` (step 4)."""
    if heat_fraction is not None:
        nan = float("nan")
        return HeatPartition(fraction_part=heat_fraction, peclet=nan, slip_speed_m_s=load.slip_speed_m_s,
                             patch_length_m=patch.L_patch, duty=nan, dwell_time_s=nan, pass_period_s=nan,
                             t_ref_s=sc.seconds, r_shoe_K_m2_W=nan, r_drum_track_K_m2_W=nan,
                             r_drum_flash_K_m2_W=nan, drum_method="given", shoe_side="given")
    Rs = None
    if shoe_side == "fe":
        n_slip, _ = sc.steps()
        pre = integrate(model, np.zeros(model.N), patch.Q1, [Segment(sc.seconds, n_slip, True)],
                        [Probe("patch_mean", weights=patch.Q1 / patch.P_model)], homogeneous=True)
        q_mean = patch.P_model / (patch.L_model * model.thickness)
        Rs = float(pre.probes["patch_mean"][-1]) / q_mean
    return heat_partition(material, drum, slip_speed_m_s=load.slip_speed_m_s, patch_length_m=patch.L_patch,
                          drum_radius_m=load.drum_radius_m, n_patches=patch.n_total, t_ref_s=sc.seconds,
                          shoe_response_K_m2_W=Rs)


def _initial_field(model: HeatModel, env: ThermalEnvironment) -> tuple[np.ndarray, str]:
    """(T0, the initial state as reported): steady idling state, ambient or uniform."""
    initial = env.initial
    T0 = None
    if initial == "steady":
        T0 = steady_state(model)
        if T0 is None:
            initial = "ambient (no heat path out of the part: no steady state)"
    if T0 is None:
        T0 = np.full(model.N, env.initial_temperature if initial == "uniform" else env.ambient_temperature)
    return T0, initial


def _run(model: HeatModel, T0: np.ndarray, Q: np.ndarray, sc: SlipScenario, probes: list[Probe],
         timings: dict) -> tuple[Run, float | None]:
    """(the run, its Richardson time-error estimate [K] or None)."""
    run = integrate(model, T0, Q, _segments(sc), probes, frames=FRAMES)
    timings["solve_s"] = run.solve_s
    if not sc.error_estimate:
        return run, None
    coarse = integrate(model, T0, Q, _segments(sc, 2), probes)
    timings["error_estimate_s"] = coarse.solve_s
    diffs = [np.max(np.abs(run.part_max[::2] - coarse.part_max))]
    for p in probes:
        diffs.append(np.max(np.abs(run.probes[p.name][::2] - coarse.probes[p.name])))
    return run, float(max(diffs) / 3.0)


# ---------------------------------------------------------------------------------------
# 7. answers
# ---------------------------------------------------------------------------------------
def _energy(run: Run, scale: float) -> dict:
    """The energy tallies for the whole part [J] and the balance error."""
    E = {"input_J": run.energy["input_J"] * scale, "stored_J": run.energy["stored_J"] * scale,
         "lost_faces_J": run.energy["face_J"] * scale, "lost_bore_J": run.energy["bore_J"] * scale,
         "lost_edges_J": run.energy["edge_J"] * scale}
    lost = E["lost_faces_J"] + E["lost_bore_J"] + E["lost_edges_J"]
    # the initial state may carry a steady heat flow (crankshaft -> faces) that the losses
    # include; the balance is stored = input - losses either way
    E["balance_error_J"] = E["stored_J"] - (E["input_J"] - lost)
    E["balance_error_rel"] = abs(E["balance_error_J"]) / max(E["input_J"], abs(E["stored_J"]), abs(lost), 1e-300)
    return E


def _flexure_peak(run: Run, basis: Basis, flex_nodes: np.ndarray | None):
    """(peak [C], its time [s], the hottest flexure node's position, that node), Nones
    without a flexure."""
    flex = run.probes.get("flexure")
    if flex is None:
        return None, None, None, None
    kf = int(np.argmax(flex))
    # where: no re-run is needed: the flexure maximum at its peak time is the largest
    # nodal maximum of the flexure over the run
    fn = flex_nodes[int(np.argmax(run.nodal_max[flex_nodes]))]
    return float(flex[kf]), float(run.times[kf]), (float(basis.doflocs[0, fn]), float(basis.doflocs[1, fn])), fn


def _cycle_table(run: Run, sc: SlipScenario, flex_nodes: np.ndarray | None) -> list[dict]:
    """Per slip event: the hottest node (and flexure node) at the end of the slip and of the pause."""
    _, n_pause = sc.steps()
    cyc = []
    seg_ends = run.segment_end
    k_end = 0
    for c in range(sc.cycles):
        row = {"cycle": c + 1}
        T_slip = seg_ends[k_end]
        k_end += 1
        row["end_of_slip_part_max_C"] = float(T_slip.max())
        if flex_nodes is not None:
            row["end_of_slip_flexure_C"] = float(T_slip[flex_nodes].max())
        if n_pause:
            T_p = seg_ends[k_end]
            k_end += 1
            row["end_of_pause_part_max_C"] = float(T_p.max())
            if flex_nodes is not None:
                row["end_of_pause_flexure_C"] = float(T_p[flex_nodes].max())
        cyc.append(row)
    return cyc


def _first_crossing(t: np.ndarray, y: np.ndarray, level: float) -> float | None:
    """First time y reaches ``level`` (linear between steps), None if never."""
    above = np.nonzero(y >= level)[0]
    if len(above) == 0:
        return None
    k = int(above[0])
    if k == 0:
        return float(t[0])
    y0, y1 = y[k - 1], y[k]
    return float(t[k - 1] + (level - y0) / (y1 - y0) * (t[k] - t[k - 1]))


def _answer(model: HeatModel, material: ThermalMaterial, env: ThermalEnvironment, load: SlipHeatLoad,
            sc: SlipScenario, patch: _Patch, part: HeatPartition, defs: dict,
            flex_nodes: np.ndarray | None, T0: np.ndarray, initial: str, run: Run, err: float | None,
            timings: dict, t_start: float) -> SlipHeatResult:
    """Step 7: gather the answers into the result."""
    cm, basis = model.cm, model.basis
    t = run.times
    s = model.scale
    E = _energy(run, s)
    kpk = int(np.argmax(run.part_max))
    node = int(run.part_argmax[kpk])
    xy = basis.doflocs[:, node]
    flex = run.probes.get("flexure")
    fpk, ftime, fxy, fn = _flexure_peak(run, basis, flex_nodes)
    lim = material.limit_temperature
    cyc = _cycle_table(run, sc, flex_nodes)
    ratio = material.yield_ratio(lim)
    bounds = (hot_yield_ratio(lim, "proportional") * material.yield_strength,
              hot_yield_ratio(lim, "effective") * material.yield_strength)
    n_slip, _ = sc.steps()
    timings["total_s"] = time.perf_counter() - t_start
    return SlipHeatResult(
        times_s=t, flexure_C=flex, shoe_face_C=run.probes["shoe_face"], hub_C=run.probes["hub"],
        part_mean_C=run.probes["part_mean"],
        part_max_C=run.part_max, probe_definitions=defs,
        peak_temperature_C=float(run.part_max[kpk]), peak_time_s=float(t[kpk]),
        peak_xy_m=(float(xy[0]), float(xy[1])), peak_zone=zone_of_node(cm, basis, node),
        peak_location=describe_node(cm, basis, node),
        flexure_peak_C=fpk, flexure_peak_time_s=ftime, flexure_peak_xy_m=fxy,
        flexure_peak_location=None if fn is None else describe_node(cm, basis, fn),
        limit_temperature_C=float(lim),
        time_to_limit_s=None if flex is None else _first_crossing(t, flex, lim),
        yield_ratio_at_limit=float(ratio), yield_strength_at_limit_Pa=float(ratio * material.yield_strength),
        yield_strength_at_limit_bounds_Pa=(float(bounds[0]), float(bounds[1])),
        yield_strength_at_flexure_peak_Pa=(None if fpk is None
                                           else float(material.yield_ratio(fpk) * material.yield_strength)),
        slip_rpm=float(load.omega_rad_s * 60.0 / (2.0 * math.pi)), slip_power_W=patch.P_model * s,
        friction_work_J=patch.P_model * s * sc.seconds * sc.cycles, heat_into_part_J=E["input_J"],
        partition=part, energy=E, cycles=cyc, initial_field_C=T0, final_field_C=run.final,
        nodal_max_C=run.nodal_max, ambient_temperature_C=float(env.ambient_temperature), initial_state=initial,
        frame_times_s=np.array([f[0] for f in run.frames]), frames_C=np.array([f[1] for f in run.frames]),
        dt_s=float(sc.seconds / n_slip), n_steps=int(len(t) - 1), time_error_estimate_K=err,
        scenario=sc.model_dump(), timings=timings, assumed=ASSUMED)
