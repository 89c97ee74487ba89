"""Cutting files, manufacturability checks and the as-cut part (issue 22): the DXF and STEP
hold the exact part (closed, units, radii to 1 um, volume to 1e-6), a process changes the
tool path and never the part, features below a process limit are refused by name, and the
exported part analysed again (STEP and DXF) gives the design's engagement and slip within
the discretisation band."""

from __future__ import annotations

import json

import ezdxf
import numpy as np
import pytest
from typer.testing import CliRunner

import clutchfem as cf
from clutchfem.cli import app
from clutchfem.cutting import as_cut, design_from_run, part_outline
from clutchfem.cutting.ascut import analyse_outline
from clutchfem.mesh import mesh_mass_properties
from clutchfem.mesh.dxf import read_dxf

COARSE = cf.MeshSettings(size="3mm")


@pytest.fixture(scope="module")
def concept1():
    """Concept 1's defaults on the coarse mesh: the design several tests export (never changed
    by them), meshed and assembled once."""
    return cf.Design.from_concept("concept1", mesh=COARSE)


def _entities(path, layers):
    doc = ezdxf.readfile(str(path))
    out = []
    for e in doc.modelspace():
        if e.dxf.layer in layers:
            d = e.dxfattribs()
            d.pop("handle", None)
            d.pop("owner", None)
            out.append((e.dxftype(), repr(sorted(d.items())), repr(getattr(e, "control_points", None))))
    return sorted(out), doc


@pytest.mark.slow
@pytest.mark.parametrize("name, values", [("concept1", {}), ("concept4", {"profile": "table",
                                                                          "table_c8": "0.45mm"})])
def test_dxf_and_step_hold_the_exact_part(tmp_path, name, values):
    d = cf.Design.from_concept(name, mesh=COARSE, **values)
    p = d.params
    # the two cutting files (and the run's records) only: the drawing sheet is test_drawing's
    r = cf.export(d, dxf=tmp_path / "part.dxf", step=tmp_path / "part.step", analyze_design=False)
    dxf = next(f for f in r.files if f.suffix == ".dxf")
    ents, doc = _entities(dxf, {"OUTER", "INNER", "BORE"})
    assert doc.header["$INSUNITS"] == 4 and ents
    assert {t for t, _, _ in ents} <= {"LINE", "ARC", "CIRCLE", "SPLINE"}
    loops = read_dxf(dxf)  # chained end to end: raises if any outline is open
    assert max(lp.gap() for lp in loops) < 1e-12
    # the outer radius is drum radius - clearance to 1 um (the table profile: R_d - c(s))
    assert abs(r.outer_radius_m - (p.drum_radius - min(p.table if p.profile == "table" else (p.clearance,)))) < 1e-6
    if p.profile == "table":
        root, tip = d.concept.shoe_arc(p)
        pts = np.vstack([s.sample(200) for lp in loops for s in lp.segments if s.kind == "spline"])
        th = -np.arctan2(pts[:, 1], pts[:, 0])  # minus arrangement: the canonical frame mirrored
        th = np.mod(th - root + np.pi, 2 * np.pi) + root - np.pi
        sel = (th >= root) & (th <= tip)
        assert sel.sum() > 50
        want = p.outer_radius(th[sel], root, tip)
        assert np.max(np.abs(np.hypot(pts[sel, 0], pts[sel, 1]) - want)) < 1e-6
    # areas: the DXF's, the OCC model's, the STEP solid's volume, the design's mass
    a_dxf = sum(lp.area for lp in loops)
    assert a_dxf == pytest.approx(r.area_m2, rel=1e-9)
    # OCC integrates a face bounded by B-splines to ~1e-6 (its surface-property tolerance);
    # lines and arcs to rounding
    assert r.area_m2 == pytest.approx(r.outline.occ_area, rel=1e-6 if p.profile == "table" else 1e-12)
    assert r.volume_m3 == pytest.approx(r.area_m2 * p.thickness, rel=1e-6)
    # the design's mass as analyze reports it (its part step: mesh_mass_properties of the
    # design's mesh, material and thickness), without the FE analysis around it
    mesh_mass = mesh_mass_properties(d.cm, d.model.material.rho, d.thickness)["mass_kg"]
    assert r.mass_kg == pytest.approx(mesh_mass, rel=1e-5)
    rec = json.loads((tmp_path / "inputs.json").read_text())
    assert rec["design_hash"] == r.design_hash and rec["clutchfem"] == cf.__version__ and rec["params"]


@pytest.mark.slow
def test_process_and_kerf_change_the_tool_path_not_the_part(tmp_path, concept1):
    from scipy.spatial import cKDTree

    d = concept1
    parts, paths = [], []
    part = None  # the part's outline finely sampled, and its k-d tree (one part: made once)
    for k, kw in enumerate([{}, {"process": "wire-edm"}, {"process": "waterjet"},
                            {"process": "wire-edm", "kerf": "0.25mm"}]):
        r = cf.export(d, dxf=tmp_path / f"p{k}.dxf", analyze_design=False, **kw)
        parts.append(_entities(tmp_path / f"p{k}.dxf", {"OUTER", "INNER", "BORE"})[0])
        paths.append(_entities(tmp_path / f"p{k}.dxf", {"TOOLPATH"})[0])
        if r.toolpath:  # every point of the tool path is half the kerf from the part
            if part is None:
                part = cKDTree(np.vstack([lp.points(spacing=2e-6) for lp in r.outline.loops]))
            pts = np.vstack([lp.points(spacing=0.1e-3) for lp in r.toolpath])
            dist, _ = part.query(pts)
            assert np.all(np.abs(dist - 0.5 * r.rules.kerf) < 1e-7)
    assert parts[1] == parts[0] and parts[2] == parts[0] and parts[3] == parts[0]
    assert not paths[0] and paths[1] and paths[1] != paths[2] and paths[1] != paths[3]


@pytest.mark.slow
def test_features_below_the_process_limit_are_refused_by_name(tmp_path):
    d = cf.Design.from_concept("concept1", fillet_radius="0.15mm", mesh=COARSE)
    with pytest.raises(cf.CuttingError) as e:
        cf.export(d, tmp_path / "a", process="wire-edm", analyze_design=False)
    msg = str(e.value)
    assert "fillet radius 0.15 mm (= fillet_radius)" in msg and "wire-edm minimum inside radius 0.2 mm" in msg
    assert not (tmp_path / "a").exists()  # nothing written
    d = cf.Design.from_concept("concept1", slot_width="0.95mm", fillet_radius="0.45mm", tip_gap="1.5mm", mesh=COARSE)
    with pytest.raises(cf.CuttingError) as e:
        cf.export(d, tmp_path / "b", process="waterjet", analyze_design=False)
    assert "slot width 0.95 mm (= slot_width)" in str(e.value) and "waterjet minimum slot width 1 mm" in str(e.value)
    # the shop's own limits let it through (its cutting file written; the drawing sheet is
    # test_drawing's)
    r = cf.export(d, dxf=tmp_path / "b" / "part.dxf", process="waterjet", min_inside_radius="0.4mm",
                  min_slot="0.9mm", analyze_design=False)
    assert r.rules.min_slot == 0.9e-3 and (tmp_path / "b" / "part.dxf").stat().st_size > 0


@pytest.mark.slow
@pytest.mark.parametrize("name", ["concept1", "concept4"])
def test_step_and_dxf_round_trip_within_the_discretisation_band(tmp_path, name):
    """The exported part read back (STEP: a prism in mm; DXF: mm) and analysed: engagement
    and slip as the design's within both discretisation bands (each from two mesh levels)."""
    ms = cf.MeshSettings(size="2.4mm")
    d = cf.Design.from_concept(name, mesh=ms)
    fine = cf.Design.from_concept(name, mesh=ms.replace(size=1.2e-3, flexure_factor=0.2, fillet_factor=0.25))
    eng = cf.EngineCurve.default()
    from clutchfem.analysis import slip_step

    e_d, s_d = d.case().engagement_rpm, slip_step(d.case(), eng).rpm
    e_f, s_f = fine.case().engagement_rpm, slip_step(fine.case(), eng).rpm
    # the two files read back (the drawing sheet, not read here, is test_drawing's and
    # test_report_links_the_cutting_files')
    r = cf.export(d, dxf=tmp_path / "part.dxf", step=tmp_path / "part.step", analyze_design=False)
    step = next(f for f in r.files if f.suffix == ".step")
    dxf = next(f for f in r.files if f.suffix == ".dxf")
    h = 1.5e-3
    res = {}
    for path in (step, dxf):
        x = cf.Design.from_mesh(path, drum_radius=d.drum_radius, mesh_size=h,
                                **({} if path.suffix == ".step" else {"thickness": d.thickness}))
        assert x.thickness == pytest.approx(d.thickness, rel=1e-9)
        res[path.suffix] = (x.case().engagement_rpm, slip_step(x.case(), eng).rpm)
    _, e_h2, s_h2 = analyse_outline(r.outline.loops, d.thickness, d, eng, 0.5 * h)
    band_e = 2 * abs(e_d - e_f) + 2 * abs(res[".step"][0] - e_h2)
    band_s = 2 * abs(s_d - s_f) + 2 * abs(res[".step"][1] - s_h2.rpm)
    for suffix, (e, s) in res.items():
        assert abs(e - e_d) <= band_e, (suffix, e, e_d, band_e)
        assert abs(s - s_d) <= band_s, (suffix, s, s_d, band_s)


@pytest.mark.slow
def test_as_cut_kerf_error_moves_engagement_and_slip(tmp_path, concept1):
    d = concept1
    outline = part_outline(d.concept, d.params)
    out = as_cut(outline, d, kerf_error=0.05e-3, mesh_size=2e-3, band=False)
    rows = {r["variant"]: r for r in out["rows"]}
    nom, wide, narrow = rows["nominal"], rows["kerf +0.05 mm"], rows["kerf -0.05 mm"]
    # a wider kerf removes material: lighter part, engagement moves; the two signs move it opposite ways
    assert wide["mass_kg"] < nom["mass_kg"] < narrow["mass_kg"]
    assert (wide["engagement_rpm"] - nom["engagement_rpm"]) * (narrow["engagement_rpm"] - nom["engagement_rpm"]) < 0
    area = outline.area
    perim = sum(s.length for lp in outline.loops for s in lp.segments)
    dm = (nom["mass_kg"] - wide["mass_kg"]) / (d.thickness * d.model.material.rho)
    assert dm == pytest.approx(perim * 0.025e-3, rel=0.02) and dm < area


@pytest.mark.slow
def test_from_run_folder_reads_back_the_same_design(tmp_path):
    d = cf.Design.from_concept("concept3", shoe_arc="70deg", mesh=COARSE)
    # a run folder: its inputs.json is what is read back (its cutting file written with it; the
    # drawing sheet is test_drawing's)
    r = cf.export(d, dxf=tmp_path / "a" / "part.dxf", analyze_design=False)
    back = design_from_run(tmp_path / "a", COARSE)
    assert back.params == d.params and back.name == d.name
    r2 = cf.export(back, dxf=tmp_path / "b.dxf", analyze_design=False)  # (its part: no drawing sheet needed)
    assert r2.area_m2 == r.area_m2


@pytest.mark.slow
def test_cli_export_and_hostile_options(tmp_path):
    run = CliRunner().invoke
    res = run(app, ["export", "concept4", "--process", "wire-edm", "--units", "in", "--no-analysis",
                    "--dxf", str(tmp_path / "p.dxf"), "--drawing", str(tmp_path / "p.svg"), "--json"])
    assert res.exit_code == 0, res.output
    assert ezdxf.readfile(str(tmp_path / "p.dxf")).header["$INSUNITS"] == 1
    assert (tmp_path / "p.svg").exists() and (tmp_path / "p.png").exists() and (tmp_path / "inputs.json").exists()
    loops = read_dxf(tmp_path / "p.dxf")
    assert max(np.hypot(*s.sample(50).T).max() for lp in loops for s in lp.segments) == pytest.approx(0.0338, abs=1e-6)
    (tmp_path / "dir.dxf").mkdir()
    for args, needle in [
        (["--process", "plasma", "--out", str(tmp_path)], "process"),
        (["--kerf", "0.3rpm", "--out", str(tmp_path)], "kerf"),
        (["--dxf", str(tmp_path / "dir.dxf")], "is a folder"),
        (["--dxf", str(tmp_path / "p.txt")], "must end in .dxf"),
        ([], "nothing to write"),
        (["--kerf", "3mm", "--out", str(tmp_path)], "slot width 2 mm (= slot_width or tip_gap) x3 < custom minimum slot"),
        (["--kerf", "0.3mm", "--min-slot", "0.2mm", "--out", str(tmp_path)], "min_slot"),
        (["--units", "cm", "--out", str(tmp_path)], "units"),
    ]:
        res = run(app, ["export", "concept1", "--no-analysis", *args])
        assert res.exit_code == 2 and needle in res.output and "Traceback" not in res.output, (args, res.output)
    res = run(app, ["export", "--from", str(tmp_path / "nowhere"), "--out", str(tmp_path)])
    assert res.exit_code == 2 and "inputs.json" in res.output
    res = run(app, ["export", "concept1", "--from", str(tmp_path), "--out", str(tmp_path)])
    assert res.exit_code == 2 and "exactly one design" in res.output


@pytest.mark.slow
def test_design_of_a_compensate_folder_and_of_a_study_row(tmp_path):
    """--from picks the compensated design ('after') of a compensate folder; --study/--row
    the row's concept, parameters and operating point (a store written by the study engine's
    own ResultStore)."""
    from clutchfem.cutting import design_from_study
    from clutchfem.evaluation import COLUMNS, ResultStore

    before = cf.Design.from_concept("concept4", mesh=COARSE)
    after = cf.Design.from_concept("concept4", profile="table", table_c3="0.5mm", mu=0.2, mesh=COARSE)
    a0, a1 = (cf.analyze(x, errors=False).inputs for x in (before, after))
    (tmp_path / "comp").mkdir()
    (tmp_path / "comp" / "inputs.json").write_text(json.dumps({"before": a0, "after": a1, "run": {}}))
    back = design_from_run(tmp_path / "comp", COARSE)
    assert back.params == after.params and back.op.mu == 0.2
    (tmp_path / "study").mkdir()
    with ResultStore(tmp_path / "study" / "results.sqlite", COLUMNS) as st:
        st.put({"design_hash": "3fa9c2d41e7700aa", "model_version": "x", "status": "ok",
                "inputs_json": json.dumps({"settings": {"concept": "concept4", "mesh": {"size": 0.003}},
                                           "params": after.params.model_dump(mode="json"),
                                           "op": after.op.model_dump(mode="json")})})
    d = design_from_study(tmp_path / "study", "3fa9c2")
    assert d.params == after.params and d.op.mu == 0.2
    with pytest.raises(cf.InputError, match="no row"):
        design_from_study(tmp_path / "study", "abcdef")
    with pytest.raises(cf.InputError, match="6 hex"):
        design_from_study(tmp_path / "study", "3fa")


@pytest.mark.slow
def test_report_links_the_cutting_files(tmp_path, concept1):
    d = concept1
    a = cf.analyze(d, errors=False)
    r = cf.export(d, tmp_path, process="wire-edm", analysis=a)
    cf.write_report(d, tmp_path, analysis=a)
    md = (tmp_path / "report.md").read_text()
    html = (tmp_path / "report.html").read_text()
    for f in r.files:
        if f.suffix in (".dxf", ".step", ".pdf"):
            assert f"[{f.name}]({f.name})" in md and f"href='{f.name}'" in html
