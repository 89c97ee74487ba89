"""One design, one name (issue 37): the design identity is computed in one place and every
face (analyze, solve, report, export, the app's downloads, a study row) carries its hash."""

from __future__ import annotations

import json

import pytest

import clutchfem as cf
from clutchfem.evaluation import Settings, context_hash, design_hash
from support.cli import cli_in_process

FAST = cf.MeshSettings.preset("fast", size=6e-3)  # (coarse: the hash is what is compared)
POINT = {"flexure_thickness": 1.9e-3}


def unmeshed(fidelity: str = "fast", mesh=FAST, **values) -> cf.Design:
    c = cf.get_concept("concept4")
    return cf.Design(None, cf.OperatingPoint(fidelity=fidelity), params=c.params(**values), concept=c,
                     mesh_settings=mesh)


def test_the_identity_names_the_design_not_its_spelling_nor_the_speeds_asked():
    a = unmeshed(flexure_thickness="1.9mm")
    b = unmeshed(flexure_thickness=0.0019000000000000002)
    assert a.hash == b.hash and a.label == f"concept4-{a.hash}" and len(a.hash) == 12
    asked = cf.Design(None, cf.OperatingPoint(fidelity="fast", rpm="8000"), params=a.params, concept=a.concept,
                      mesh_settings=FAST)
    assert asked.hash == a.hash  # the speeds an answer is asked at are not the design
    doc = a.identity.document
    assert doc["params"]["flexure_thickness"] == 0.0019 and doc["op"]["fidelity"] == "fast"
    assert doc["model_version"] == cf.loadcase.model_version("concept4") and doc["op"]["material"]["E"] == 210e9
    for other in (unmeshed("best", flexure_thickness="1.9mm"), unmeshed(mesh=cf.MeshSettings.preset("fast")),
                  unmeshed(flexure_thickness="1.91mm"),
                  cf.Design(None, cf.OperatingPoint(fidelity="fast", material="titanium"), params=a.params,
                            concept=a.concept, mesh_settings=FAST)):
        assert other.hash != a.hash  # fidelity, mesh, parameters and material are part of it


def test_the_default_design_keeps_its_short_name_whatever_speeds_are_asked():
    c = cf.get_concept("concept4")
    for rpm in (None, "0:14000:250"):
        d = cf.Design(None, cf.OperatingPoint(rpm=rpm), params=c.params(), concept=c)
        assert d.label == "concept4"  # solve's --rpm no longer renames the default design


def test_a_study_point_and_the_design_have_one_hash():
    st = Settings("concept4", op=cf.OperatingPoint(fidelity="fast"), mesh=FAST)
    d = unmeshed(flexure_thickness="1.9mm")
    assert design_hash(POINT, st) == d.hash == d.inputs()["design_hash"]
    fixed = Settings("concept4", fixed=tuple(POINT.items()), op=cf.OperatingPoint(fidelity="fast"), mesh=FAST)
    assert design_hash({}, fixed) == d.hash  # fixed or varied: one design
    # the engine and the requirements are the study's context, not the design
    assert context_hash(st) != context_hash(Settings("concept4", op=st.op, mesh=FAST, a=1.4))
    assert design_hash(POINT, Settings("concept4", op=st.op, mesh=FAST, a=1.4)) == d.hash


def test_one_design_under_two_contexts_is_two_rows_of_one_store(tmp_path):
    from clutchfem.evaluation import COLUMNS, ResultStore

    path = tmp_path / "results.sqlite"
    with ResultStore(path, COLUMNS, context="e1") as st:
        st.put({"design_hash": "abc", "model_version": "v", "status": "ok", "slip_rpm": 1.0})
    with ResultStore(path, COLUMNS, context="e2") as st:
        st.put({"design_hash": "abc", "model_version": "v", "status": "ok", "slip_rpm": 2.0})
        assert st.frame("v")["slip_rpm"].tolist() == [2.0]
    with ResultStore(path, COLUMNS) as st:
        assert sorted(st.frame("v")["slip_rpm"]) == [1.0, 2.0]


def test_a_store_of_an_older_version_is_rekeyed_with_its_rows(tmp_path):
    import sqlite3

    from clutchfem.evaluation import COLUMNS, ResultStore

    path = tmp_path / "results.sqlite"
    db = sqlite3.connect(path)
    db.execute("CREATE TABLE results (design_hash TEXT, model_version TEXT, status TEXT, "
               "PRIMARY KEY (design_hash, model_version))")
    db.execute("INSERT INTO results VALUES ('abc', 'v', 'ok')")
    db.commit()
    db.close()
    with ResultStore(path, COLUMNS, context="e1") as st:
        st.put({"design_hash": "abc", "model_version": "v", "status": "failed"})
    with ResultStore(path, COLUMNS) as st:
        assert sorted(st.frame("v")["status"]) == ["failed", "ok"]  # the old row kept, the new one beside it


def _files_hash(folder, pattern):
    (f,) = folder.glob(pattern)
    return f


@pytest.mark.slow
def test_every_face_gives_concept4_at_1_9mm_one_hash(tmp_path):
    """analyze, solve, report, export (files, JSON, STEP header, DXF text), a study row, export
    of that row and the app's inputs.json: one design (concept 4, 1.9 mm flexure, fast), one
    hash."""
    from clutchfem.app.downloads import inputs_document
    from clutchfem.app.session import DesignSession, Outcome
    from clutchfem.evaluation import COLUMNS, ResultStore, run_points

    want = unmeshed(flexure_thickness="1.9mm").hash
    common = ("concept4", "--set", "flexure_thickness=1.9mm", "--fidelity", "fast", "--mesh-size", "6mm")
    cli_in_process("analyze", *common, "--out", tmp_path / "an", ok=True)
    doc = json.loads(_files_hash(tmp_path / "an", f"concept4-{want}_analysis.json").read_text())
    assert doc["design_hash"] == doc["inputs"]["design_hash"] == want
    cli_in_process("solve", *common, "--rpm", "8000", "--no-errors", "--no-stress", "--out", tmp_path / "so", ok=True)
    assert json.loads(_files_hash(tmp_path / "so", f"concept4-{want}_result.json").read_text())["design_hash"] == want
    cli_in_process("report", *common, "--no-errors", "--out", tmp_path / "re", ok=True)
    assert json.loads((tmp_path / "re" / "inputs.json").read_text())["design_hash"] == want
    assert json.loads((tmp_path / "re" / "page.json").read_text())["design_hash"] == want
    assert f"design hash {want}" in (tmp_path / "re" / "report.html").read_text()
    cli_in_process("export", *common, "--no-analysis", "--out", tmp_path / "ex", ok=True)
    ex = tmp_path / "ex"
    assert json.loads((ex / "export.json").read_text())["design_hash"] == want
    assert json.loads((ex / "inputs.json").read_text())["design_hash"] == want
    assert f"design hash {want}" in (ex / f"concept4-{want}.step").read_text()
    assert f"design hash {want}" in (ex / f"concept4-{want}.dxf").read_text()
    # a study row of the same design, and export of that row
    st = Settings("concept4", op=cf.OperatingPoint(fidelity="fast"), mesh=FAST)
    (tmp_path / "study").mkdir()
    run = run_points([POINT], st, tmp_path / "study" / "results.sqlite", workers=0, progress=False)
    with ResultStore(run.store, COLUMNS, context=run.context_hash) as rs:
        assert rs.frame(run.model_version)["design_hash"].tolist() == [want]
    cli_in_process("export", "--study", tmp_path / "study", "--row", want[:8], "--no-analysis", "--out",
                   tmp_path / "ex2", ok=True)
    assert json.loads((tmp_path / "ex2" / "export.json").read_text())["design_hash"] == want
    # the app at the same design: its inputs.json download
    s = DesignSession("concept4", out_dir=tmp_path / "app")
    assert s.set_value("flexure_thickness", 1.9) is None and s.set_value("fidelity", "fast") is None
    s.mesh = FAST
    d = s.design()
    got = inputs_document(Outcome(cf.analyze(d, errors=False), d.label, d))
    assert got["design_hash"] == want and got["label"] == f"concept4-{want}"
