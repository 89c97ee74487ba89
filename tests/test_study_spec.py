"""Study specs, sampling, the design hash and the result store (no FE: fast).

Spec errors must name the key, its value and what is allowed; samples are seeded and stay
in their ranges (a Latin hypercube hits every stratum of every dimension once); the
design hash identifies a design, not the way it was typed; the store survives a reopen,
replaces rows and gains new columns.
"""

from __future__ import annotations

import sqlite3

import numpy as np
import pytest

from clutchfem.core import InputError
from clutchfem.evaluation import COLUMNS, ResultStore, model_version
from clutchfem.evaluation.hashing import design_hash
from clutchfem.studies import EXAMPLE_SPEC, SpecError, parse_spec

BASE = """
[design]
concept = "concept4"
[settings]
mesh_size = "3mm"
[vary]
method = "grid"
[vary.params]
flexure_thickness = {min = "1.6mm", max = "1.9mm", steps = 4}
"""


def test_example_spec_is_valid_and_has_about_12_points():
    spec = parse_spec(EXAMPLE_SPEC, source="<example>")
    pts = spec.points()
    assert len(pts) == spec.count() == 12
    assert spec.design == "concept4"
    assert sorted({p["clearance"] for p in pts}) == pytest.approx([0.30e-3, 0.33e-3, 0.36e-3], rel=1e-12)
    assert sorted({p["shoe_arc"] for p in pts}) == pytest.approx([92.0, 97.0, 102.0, 115.0], rel=1e-12)
    assert dict(spec.settings.fixed)["shoe_thickness"] == pytest.approx(7.5e-3, rel=1e-12)
    assert spec.error_sample == 3 and spec.error_points() == [0, 6, 11]  # evenly spaced, ends included


def _with(replace: dict[str, str] | None = None, add: str = "") -> str:
    text = BASE
    for old, new in (replace or {}).items():
        assert old in text
        text = text.replace(old, new)
    return text + add


# (spec text, key named, a fragment of the allowed statement)
CASES = [
    (_with(add="\n[extra]\nx = 1\n"), "extra", "unknown key"),
    (_with({'method = "grid"': 'method = "grd"'}), "vary.method", "'grid'"),
    (_with({'min = "1.6mm"': "min = 1.6"}), "vary.params.flexure_thickness.min", "plain numbers are in m"),
    (_with({'min = "1.6mm"': 'min = "1.6deg"'}), "vary.params.flexure_thickness.min", "a length in m"),
    (_with({"steps = 4": "steps = 1"}), "vary.params.flexure_thickness.steps", "an integer >= 2"),
    (_with({"steps = 4": "steps = 4, values = [1]"}), "vary.params.flexure_thickness", "not both"),
    (_with({", steps = 4": ""}), "vary.params.flexure_thickness", "exactly one of steps"),
    (_with({'max = "1.9mm"': 'max = "1.5mm"'}), "vary.params.flexure_thickness.max", "above min"),
    (_with({"flexure_thickness =": "flexure_thicknes ="}), "vary.params", "a parameter of concept4"),
    (_with({'concept = "concept4"': 'concept = "concept9"'}), "design.concept", "concept4"),
    (_with({'mesh_size = "3mm"': 'mesh_size = "3mm"\nmu = 2'}), "settings.mu", "[0, 1]"),
    (_with({'mesh_size = "3mm"': 'mesh_size = "3mm"\ndrum_radius = "34mm"'}), "settings.drum_radius",
     "concept parameter"),
    (_with({'mesh_size = "3mm"': 'mesh_size = "3mm"\ncolour = "red"'}), "settings.colour", "unknown setting"),
    (_with({'mesh_size = "3mm"': 'mesh_size = "3mm"\nengine = "no-such.csv"'}), "settings.engine",
     "engine curve"),
    (_with({'method = "grid"': 'method = "sobol"\nsamples = 12',
            ', steps = 4': ''}), "vary.samples", "power of 2"),
    (_with({'method = "grid"': 'method = "lhs"', ', steps = 4': ''}), "vary.samples", "samples"),
    (_with({'method = "grid"': 'method = "list"', '{min = "1.6mm", max = "1.9mm", steps = 4}':
            '{values = ["1.6mm", "1.7mm"]}'}, add='shoe_arc = {values = [80, 85, 90]}\n'), "vary.params",
     "one length"),
    (_with({'flexure_thickness = {min = "1.6mm", max = "1.9mm", steps = 4}':
            'profile = {min = 1, max = 2, steps = 2}'}), "vary.params.profile", "a choice"),
    (_with({'flexure_thickness = {min = "1.6mm", max = "1.9mm", steps = 4}':
            'profile = {values = ["round"]}'}), "vary.params.profile.values[0]", "'concentric'"),
    (_with({'[vary]': '[design.set]\nflexure_thickness = "1.7mm"\n[vary]'}), "vary.params.flexure_thickness",
     "not both"),
    (_with({'[vary]': '[requirements]\na = -1\n[vary]'}), "requirements.a", "> 0"),
    (_with({'concept = "concept4"': 'concept = "concept4"\nmesh = "part.msh"'}), "design", "exactly one"),
]


@pytest.mark.parametrize("text,key,allowed", CASES, ids=[c[1] + "-" + c[2][:12] for c in CASES])
def test_spec_errors_name_key_value_and_allowed(text, key, allowed):
    with pytest.raises(SpecError) as info:
        parse_spec(text, source="t.toml")
    e = info.value
    assert e.key == key, str(e)
    assert allowed in e.allowed, str(e)
    msg = str(e)
    assert msg.startswith("study spec t.toml: key '" + key + "'") and allowed in msg


def test_missing_table_and_bad_toml():
    with pytest.raises(SpecError, match="key 'vary' is missing"):
        parse_spec('[design]\nconcept = "concept4"\n')
    with pytest.raises(InputError, match="not valid TOML"):
        parse_spec("[design\nconcept = 4")


def test_units_and_ranges_go_through_the_concept_paramset():
    # a suffix and a plain number in the parameter's unit are the same value; the allowed
    # range is the concept's own (concept 4: flexure_thickness in [0.5 mm, 4 mm])
    a = parse_spec(_with({'min = "1.6mm", max = "1.9mm"': 'min = 0.0016, max = "1900um"'}))
    b = parse_spec(BASE)
    assert a.points() == b.points()
    with pytest.raises(SpecError, match=r"\[0.5 mm, 4 mm\]"):
        parse_spec(_with({'max = "1.9mm"': 'max = "4.1mm"'}))


def test_grid_step_lists_and_integer_ranges():
    s = parse_spec(_with({"steps = 4": 'step = "0.1mm"'}, add='n_shoes = {min = 2, max = 4, steps = 3}\n'))
    pts = s.points()
    assert len(pts) == 4 * 3
    assert sorted({p["n_shoes"] for p in pts}) == [2, 3, 4]
    assert all(isinstance(p["n_shoes"], int) for p in pts)


@pytest.mark.parametrize("method,n", [("lhs", 10), ("sobol", 8)])
def test_space_filling_samples_are_seeded_and_in_range(method, n):
    text = _with({'method = "grid"': f'method = "{method}"\nsamples = {n}\nseed = 7', ", steps = 4": ""},
                 add='shoe_arc = {min = "80deg", max = "100deg"}\nprofile = {values = ["concentric", "linear"]}\n')
    s1, s2 = parse_spec(text), parse_spec(text)
    p1 = s1.points()
    assert p1 == s2.points()
    assert len(p1) == 2 * n  # the samples crossed with the list
    other = parse_spec(text.replace("seed = 7", "seed = 8")).points()
    assert other != p1
    t = np.array([p["flexure_thickness"] for p in p1])
    a = np.array([p["shoe_arc"] for p in p1])
    assert t.min() >= 1.6e-3 and t.max() <= 1.9e-3 and a.min() >= 80 and a.max() <= 100
    if method == "lhs":  # one sample in each of the n strata of each dimension
        for v, lo, hi in ((t[::2], 1.6e-3, 1.9e-3), (a[::2], 80.0, 100.0)):
            strata = np.floor((v - lo) / (hi - lo) * n).astype(int)
            assert sorted(strata) == list(range(n))


def test_design_hash_identifies_the_design_not_its_spelling():
    s = parse_spec(BASE)
    st = s.settings
    h = design_hash({"flexure_thickness": 1.7e-3}, st)
    assert h == design_hash({"flexure_thickness": 0.0017000000000000001}, st)
    # a default given explicitly is the same design (concept 4's shoe_arc default is 90 deg)
    assert h == design_hash({"flexure_thickness": 1.7e-3, "shoe_arc": 90.0}, st)
    assert h != design_hash({"flexure_thickness": 1.71e-3}, st)
    other = parse_spec(BASE.replace('mesh_size = "3mm"', 'mesh_size = "3mm"\nmu = 0.2')).settings
    assert h != design_hash({"flexure_thickness": 1.7e-3}, other)
    coarse = parse_spec(BASE.replace('"3mm"', '"2mm"')).settings
    assert h != design_hash({"flexure_thickness": 1.7e-3}, coarse)
    v = model_version("concept4")
    assert v.startswith("0.") and "+" in v and v == model_version("concept4")


def test_store_put_finished_replace_and_new_columns(tmp_path):
    path = tmp_path / "r.sqlite"
    with ResultStore(path, COLUMNS) as st:
        st.put({"design_hash": "a", "model_version": "v1", "status": "ok", "engagement_rpm": 4000.0})
        st.put({"design_hash": "b", "model_version": "v1", "status": "failed", "message": "boom"})
        st.put({"design_hash": "a", "model_version": "v2", "status": "refused"})
        assert st.finished("v1") == {"a": "ok", "b": "failed"}
        assert st.finished("v1", ["b", "zz"]) == {"b": "failed"}
        st.put({"design_hash": "b", "model_version": "v1", "status": "ok"})  # --retry-failed replaces
        assert st.finished("v1") == {"a": "ok", "b": "ok"}
    # another process reads it (WAL) and a newer column list extends the table on open
    with sqlite3.connect(path) as db:
        assert db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"
        assert db.execute("SELECT count(*) FROM results").fetchone()[0] == 3
    cols = list(COLUMNS) + [("new_answer_rpm", "REAL", "a later column")]
    with ResultStore(path, cols) as st:
        df = st.frame("v1", ["b", "a"])
        assert list(df["design_hash"]) == ["b", "a"] and "new_answer_rpm" in df
        assert df.loc[1, "engagement_rpm"] == 4000.0
    (tmp_path / "bad.sqlite").write_text("not a database, just text" * 100)
    with pytest.raises(InputError, match="not a usable SQLite file"):
        ResultStore(tmp_path / "bad.sqlite", COLUMNS)
