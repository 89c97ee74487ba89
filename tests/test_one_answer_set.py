"""One answer set (issue 37): the same design gives the same main answers, to the digits each
face shows, from ``analyze``, the report, the workshop drawing and the app -- each face
analysing the design itself (no analysis handed from one to the other)."""

from __future__ import annotations

import re

import pytest

import clutchfem as cf
from clutchfem.app import DesignSession
from clutchfem.app.session import answer_rows

#: a coarse mesh (the faces agreeing to their digits is the point, not the answers' accuracy):
#: the design of tests/test_design_identity.py, whose mesh a full run shares
MESH = cf.MeshSettings.preset("fast", size=6e-3)


def _design():
    return cf.Design.from_concept("concept4", flexure_thickness="1.9mm", fidelity="fast", mesh=MESH)


@pytest.mark.slow
def test_app_analyze_report_and_drawing_show_the_same_answers(tmp_path, monkeypatch):
    monkeypatch.setenv("CLUTCHFEM_FIDELITY", "fast")
    want = cf.analyze(_design())
    band = {k: want.errors[k]["total"] for k in ("engagement_rpm", "slip_rpm", "max_von_mises_Pa")}
    eng, slip = f"{want.engagement_rpm:.0f} rpm", f"{want.slip_rpm:.0f} rpm"
    peak = f"{want.max_von_mises_Pa / 1e6:.0f} MPa"
    e_b, s_b, p_b = (f"{band['engagement_rpm']:.0f} rpm", f"{band['slip_rpm']:.0f} rpm",
                     f"{band['max_von_mises_Pa'] / 1e6:.0f} MPa")
    sf = f"{want.safety_factor:.2f}"

    # the report of the same design (its own analysis)
    cf.write_report(_design(), tmp_path / "report")
    md = (tmp_path / "report" / "report.md").read_text()
    assert re.search(rf"\| engagement speed \(static, FE\) \| {eng} \+- {e_b}", md), md[:2000]
    assert re.search(rf"\| slip speed \(drum held, full throttle\) \| {slip} \+- {s_b}", md)
    assert re.search(rf"\| max von Mises at \d+ rpm \(engine max\) \| {peak} \+- {p_b}", md)
    assert re.search(rf"\| safety factor against yield \(\d+ MPa\) \| {sf} ", md)

    # the workshop drawing of the same design (export analyses it itself)
    res = cf.export(_design(), tmp_path / "cut", drawing=tmp_path / "cut" / "sheet.svg")
    svg = next(p for p in res.files if p.suffix == ".svg").read_text()
    for text in (f"{eng} ± {e_b}", f"{slip} ± {s_b}", f"{peak} ± {p_b}", f">{sf}<"):
        assert text in svg, text

    # the app: the answers it ends on are analyze's (the value column of each main answer)
    s = DesignSession("concept4")
    assert s.set_value("flexure_thickness", 1.9) is None
    s.mesh = MESH  # (the session's mesh setting: the same design as the other faces')
    done = s.complete(s.run())
    assert done.rows == answer_rows(want)
    shown = dict((q, v) for q, v, _ in done.rows)
    assert shown["engagement speed (static)"] == f"{eng} +- {e_b}"
    assert shown["slip speed (drum held, full throttle)"] == f"{slip} +- {s_b}"
