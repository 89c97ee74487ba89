"""The workshop drawing (issue 37): the SVG read back against the geometry, the labels clear
of the part and inside the sheet, and the thinnest ligament against closed forms."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.path import Path as MPath

import clutchfem as cf
from clutchfem.cutting import measure, part_outline, thinnest_ligament
from clutchfem.cutting.sheet import build_sheet, draw_sheet
from clutchfem.loadcase import design_hash
from clutchfem.mesh import Loop, Segment

SVG = "{http://www.w3.org/2000/svg}"


# -- the thinnest ligament against closed forms ------------------------------------------
@pytest.mark.parametrize("t", [0.6e-3, 1.75e-3, 3.2e-3])
def test_ligament_of_a_straight_strip_is_its_thickness(t):
    """Two 8 x 8 mm blocks joined by a 10 mm strip of thickness t: the thinnest section is
    the strip, t wide, between its two walls."""
    y0 = 4e-3 - t / 2
    pts = [(0, 0), (8e-3, 0), (8e-3, y0), (18e-3, y0), (18e-3, 0), (26e-3, 0), (26e-3, 8e-3), (18e-3, 8e-3),
           (18e-3, y0 + t), (8e-3, y0 + t), (8e-3, 8e-3), (0, 8e-3)]
    segs = [Segment("line", a, b, tag="flexure_0" if 8e-3 < 0.5 * (a[0] + b[0]) < 18e-3 else "hub")
            for a, b in zip(pts, pts[1:] + pts[:1])]
    lg = thinnest_ligament(SimpleNamespace(loops=(Loop(tuple(segs)),)))
    assert lg.width == pytest.approx(t, rel=1e-9)
    assert 8e-3 <= lg.at[0] <= 18e-3 and lg.at[1] == pytest.approx(4e-3, abs=1e-9)
    assert {round(lg.p[1], 12), round(lg.q[1], 12)} == {round(y0, 12), round(y0 + t, 12)}
    assert lg.where == "flexure 0" and lg.count == 1


def test_ligament_of_concept4_is_the_heel_not_the_parameter():
    """Concept 4: the thinnest section is between the slot-end round and the root face,
    |y_c| - rho of the round (canonical frame, root face on y = 0), not flexure_thickness."""
    d = cf.Design.from_concept("concept4")
    p = d.params
    lay = p.full_layout()
    c_e, rho_e = lay.round_e[0], lay.round_e[3]
    want = abs(c_e[1]) - rho_e
    lg = thinnest_ligament(part_outline(d.concept, p))
    assert lg.width == pytest.approx(want, abs=1e-7)
    assert lg.width < p.flexure_thickness  # the discrepancy the docstring explains
    assert lg.radius == pytest.approx(c_e[0], abs=0.1e-3) and lg.count == p.n_shoes
    # concentric-arc flexure (concept 1): exactly its thickness
    d1 = cf.Design.from_concept("concept1")
    assert thinnest_ligament(part_outline(d1.concept, d1.params)).width == pytest.approx(
        d1.params.flexure_thickness, rel=1e-9)


# -- the drawing read back --------------------------------------------------------------
def _svg_texts(path) -> dict[str, str]:
    """{group id: its text} of every group holding text."""
    root = ET.parse(path).getroot()
    out = {}
    for g in root.iter(SVG + "g"):
        gid = g.get("id", "")
        texts = ["".join(t.itertext()) for t in g.iter(SVG + "text")]
        if texts and (gid.startswith("dim:") or gid.startswith("title:")):
            out[gid] = " ".join(texts).strip()
    return out


def _number(text: str) -> tuple[float, int]:
    """The nominal value of a dimension text ('3x R0.8', '(1.35)', '1.75 ±0.02', '90°') and
    its number of decimals."""
    s = re.sub(r"^\d+x ", "", text).strip("()")
    m = re.search(r"[-+]?\d+(?:\.(\d+))?", s.replace("Ø", "").replace("R", ""))
    return float(m.group(0)), len(m.group(1) or "")


def _check(dims: dict, expected: dict) -> int:
    """Every dimension on the sheet equals its expected value to the digits shown."""
    n = 0
    for gid, text in dims.items():
        key = gid[4:]
        fam = key.split(":")[0]
        want = expected.get(key, expected.get(fam))
        assert want is not None, f"{gid} = {text!r}: no expected value for it"
        v, dec = _number(text)
        ok = any(abs(v - w) <= 0.5 * 10.0 ** -dec + 1e-9 for w in np.atleast_1d(want))
        assert ok, f"{gid} = {text!r}, the geometry says {want}"
        n += 1
    return n


def _concentric_radii_mm(outline) -> list[float]:
    return sorted({round(s.radius * 1e3, 9) for s in outline.segments() if s.kind == "arc"
                   and math.hypot(*s.centre) < 1e-9 and not s.tag.endswith("/bore")})


def _small_arcs_mm(outline, drum) -> list[float]:
    return sorted({round(s.radius * 1e3, 9) for s in outline.segments() if s.kind == "arc"
                   and s.radius < 0.25 * drum and not s.tag.endswith("/bore")})


def _contact_sweep_deg(outline) -> float:
    return sum(abs(math.degrees(s.sweep)) for s in outline.segments()
               if "/contact" in s.tag and s.tag.split("/")[0].endswith("_0"))


def test_drawing_of_concept4_reads_back_title_block_and_dimensions(tmp_path):
    d = cf.Design.from_concept("concept4")
    p = d.params
    r = cf.export(d, drawing=tmp_path / "c4.svg", process="wire-edm", analyze_design=False,
                  tolerances={"flexure_thickness": 2e-5})
    svg = (tmp_path / "c4.svg").read_text()
    texts = _svg_texts(tmp_path / "c4.svg")
    # title block
    assert texts["title:drawing_number"] == design_hash(d) == r.design_hash
    assert texts["title:scale"] == "2:1"
    assert texts["title:general_tolerances"].startswith(f"contour ±{r.rules.tolerance * 1e3:g} mm (wire-edm)")
    assert texts["title:material"] == d.model.material.name
    assert texts["title:mass"] == f"{p.thickness * r.area_m2 * d.model.material.rho * 1e3:.1f} g"
    assert texts["title:units"] == "mm" and texts["title:thickness"] == "11 mm"
    assert "FE, plane stress" not in svg and "<path" in svg and ">Ø13<" in svg  # text kept as text
    # the dimensions, each against the geometry's own value [mm, deg]
    lay = p.full_layout()
    L, g, rh = p.flexure_length, math.radians(p.flexure_angle), p.hub_radius
    n = p.n_shoes
    expected = {
        "bore": 2 * p.bore_radius * 1e3,
        "radius:contact": (p.drum_radius - p.clearance) * 1e3,
        "radius:shoe": (p.drum_radius - p.clearance - p.shoe_thickness) * 1e3,
        "radius:hub": p.hub_radius * 1e3,
        "fillet": [p.fillet_radius * 1e3, lay.round_e[3] * 1e3],
        "shoe_arc": p.shoe_arc, "pitch": 360 / n, "tip_gap": 360 / n - p.shoe_arc,
        "thickness": p.thickness * 1e3, "shoe_thickness": p.shoe_thickness * 1e3,
        "flexure_length": L * 1e3, "flexure_thickness_hub": p.flexure_thickness * 1e3,
        "flexure_thickness_shoe": p.flexure_thickness * p.flexure_taper * 1e3, "flexure_angle": p.flexure_angle,
        "flexure_position": math.degrees(math.atan2(L * math.cos(g), rh + L * math.sin(g))),
        "flexure_end": float(np.linalg.norm(lay.S)) * 1e3, "flexure_toe": lay.r_l0 * 1e3,
        "ligament": (abs(lay.round_e[0][1]) - lay.round_e[3]) * 1e3,
    }
    dims = {k: v for k, v in texts.items() if k.startswith("dim:")}
    assert _check(dims, expected) >= 20
    keys = {g[4:] for g in dims} | {g[4:].split(":")[0] for g in dims}
    assert set(expected) <= keys, set(expected) - keys  # every feature is there
    assert sum(g.startswith("dim:fillet") for g in dims) == 3  # acute, obtuse hub fillets, slot-end round
    assert dims["dim:flexure_thickness_hub"] == "3x 1.75 ±0.02"  # the --tol tolerance on its dimension
    assert r.to_json()["thinnest_ligament"]["width_m"] == pytest.approx(expected["ligament"] * 1e-3, abs=1e-9)


def test_drawing_of_concept5_reads_back_its_dimensions(tmp_path):
    d = cf.Design.from_concept("concept5")
    p = d.params
    o = part_outline(d.concept, p)
    lg = thinnest_ligament(o)
    draw_sheet([tmp_path / "c5.svg"], outline=o, features=measure(o), rules=None, toolpath=None, label="concept5",
               design_hash="abcdef123456", material="51CrV4", mass_kg=0.1, ligament=lg)
    texts = _svg_texts(tmp_path / "c5.svg")
    assert texts["title:general_tolerances"] == "ISO 2768-mK" and texts["title:drawing_number"] == "abcdef123456"
    n, arc = p.n_shoes, _contact_sweep_deg(o)
    expected = {"bore": 2 * p.bore_radius * 1e3, "radius": _concentric_radii_mm(o),
                "radius:contact": (p.drum_radius - p.clearance) * 1e3,
                "radius:hub:2": p.core_radius * 1e3,
                "fillet": p.fillet_radius * 1e3, "shoe_arc": arc, "pitch": 360 / n, "tip_gap": 360 / n - arc,
                "thickness": p.thickness * 1e3, "shoe_thickness": p.shoe_thickness * 1e3,
                "ligament": p.flexure_thickness * 1e3}
    assert _small_arcs_mm(o, p.drum_radius) == [p.fillet_radius * 1e3]
    dims = {k: v for k, v in texts.items() if k.startswith("dim:")}
    assert _check(dims, expected) >= 20


def test_no_label_on_the_part_or_off_the_sheet():
    """Every text's box (the renderer's) is inside the sheet, crosses no drawn outline and
    lies outside the part's material in the main view."""
    for concept in ("concept4", "concept1"):
        d = cf.Design.from_concept(concept)
        o = part_outline(d.concept, d.params)
        fig = build_sheet(outline=o, features=measure(o), rules=cf.ProcessRules.of("wire-edm"), toolpath=None,
                          label=concept, design_hash="0" * 12, material="51CrV4", mass_kg=0.1,
                          ligament=thinnest_ligament(o))
        r = fig.canvas.get_renderer()
        ax = fig.axes[0]
        sheet = fig.bbox
        outlines = [ln for ln in ax.lines if (ln.get_gid() or "").startswith("outline:")]
        paths = [MPath(ax.transData.transform(ln.get_xydata())) for ln in outlines]
        outer = next(ln for ln in outlines if ln.get_gid() == "outline:main:OUTER")
        filled = MPath(ax.transData.transform(outer.get_xydata()), closed=True)
        texts = [t for t in ax.texts if t.get_text().strip()]
        assert sum((t.get_gid() or "").startswith("dim:") for t in texts) >= 15
        for t in texts:
            b = t.get_window_extent(r)
            assert sheet.x0 <= b.x0 and b.x1 <= sheet.x1 and sheet.y0 <= b.y0 and b.y1 <= sheet.y1, t.get_text()
            assert abs(t.get_rotation() % 360) < 1e-9, t.get_text()  # horizontal: never upside down
            assert not any(pth.intersects_bbox(b, filled=False) for pth in paths), (concept, t.get_text())
            assert not filled.intersects_bbox(b, filled=True), (concept, t.get_text())
