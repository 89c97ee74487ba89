"""The reduced model (issue 36): its region, its models, its build on the study engine, its
measured error, and the live answers of ``analyze`` (a design that is never meshed)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.reduced import AnswerModel, ReducedModel, Region, StatusModel, live_analysis
from support.cli import cli_in_process
from support.reduced import built_region  # noqa: F401 -- the shared region (fixture `built`)

MESH = cf.MeshSettings(size="3mm")


def live(**values):
    return cf.Design.from_concept("concept1", mesh=MESH, fidelity="live", **values)


# -- the region ---------------------------------------------------------------------------
def test_a_live_design_is_not_meshed_and_its_region_is_the_span_around_it():
    d = live(flexure_thickness="2.2mm")
    r = Region.around(d, span=0.1)
    assert not d.meshed  # the region and its key need no mesh
    assert r.bounds("flexure_thickness") == (pytest.approx(1.98e-3), pytest.approx(2.42e-3))
    assert r.contains({"flexure_thickness": 2.4e-3}) and not r.contains({"flexure_thickness": 2.5e-3})
    assert r.outside({"flexure_thickness": 2.5e-3}) == ["flexure_thickness = 0.0025 outside 0.00198..0.00242"]
    # the key: not the base's values of the free parameters, but every fixed input
    ranges = {n: r.bounds(n) for n in r.names}
    assert Region.around(live(flexure_thickness="2.3mm"), ranges=ranges).key() == r.key()
    assert Region.around(live(flexure_thickness="2.3mm", thickness="10mm"), ranges=ranges).key() != r.key()
    assert Region.around(live(flexure_thickness="2.3mm", mu=0.2), ranges=ranges).key() != r.key()


@pytest.mark.parametrize("kw, name", [({"span": 0.0}, "span"), ({"span": 0.9}, "span"), ({"span": True}, "span"),
                                      ({"free": ["nope"]}, "nope"),
                                      ({"ranges": {"flexure_thickness": ("2.4mm", "2.0mm")}}, "flexure_thickness"),
                                      ({"ranges": {"flexure_thickness": ("0.1mm", "2.0mm")}}, "flexure_thickness")])
def test_a_bad_region_is_refused_naming_the_input(kw, name):
    with pytest.raises(cf.ParameterError) as e:
        Region.around(live(), **kw)
    assert e.value.name == name


@pytest.mark.parametrize("kw", [{"adaptive": 0.7}, {"adaptive": -0.1}, {"adaptive": True}, {"n": 2}, {"held_out": 1.5}])
def test_a_bad_build_is_refused_before_any_work_naming_the_input(kw):
    with pytest.raises(cf.ParameterError) as e:
        cf.reduce(live(), **kw)
    assert e.value.name == next(iter(kw)) and str(list(kw.values())[0]) in str(e.value)


def test_a_user_mesh_has_no_region(tmp_path):
    d = cf.Design.from_concept("concept1", mesh=MESH, fidelity="fast")
    path = d.cm.write_msh(tmp_path / "part.msh")
    user = cf.Design.from_mesh(path, drum_radius="34.4mm", fidelity="fast")
    with pytest.raises(cf.ParameterError, match="a concept's design"):
        Region.around(user)


# -- the models ---------------------------------------------------------------------------
def test_answer_model_converges_on_a_smooth_answer_and_interpolates_its_training_points():
    rng = np.random.default_rng(1)
    f = lambda U: 4000 * np.exp(0.4 * U[:, 0] - 0.1 * U[:, 1] + 0.05 * U[:, 0] * U[:, 1] ** 2)  # noqa: E731
    test = rng.random((200, 2))
    errs = []
    for n in (10, 40):
        U = rng.random((n, 2))
        m = AnswerModel.fit(U, f(U))
        errs.append(np.abs(m.predict(test) / f(test) - 1).max())
        assert np.allclose(m.predict(U), f(U), rtol=1e-4)
    assert errs[1] < errs[0] / 20 and errs[1] < 1e-3  # 10 -> 40 designs: 2.4 % -> 0.02 % here


def test_answer_model_predicts_the_matern_mean_of_its_definition():
    """The distances by one matrix product equal the differences' own norms: the kernel mean
    written out point by point, at new points and at the training points themselves."""
    rng = np.random.default_rng(4)
    m = AnswerModel(trend=rng.normal(size=4), X=rng.random((30, 3)), alpha=rng.normal(size=30), amplitude=0.02,
                    lengths=np.array([0.05, 0.7, 40.0]))
    U = np.vstack([rng.random((50, 3)), m.X])
    r = np.sqrt((((U[:, None, :] - m.X[None, :, :]) / m.lengths) ** 2).sum(axis=2))
    s5 = np.sqrt(5.0) * r
    direct = np.exp(m.trend[0] + U @ m.trend[1:] + (m.amplitude * (1 + s5 + s5**2 / 3) * np.exp(-s5)) @ m.alpha)
    assert np.allclose(m.predict(U), direct, rtol=1e-12, atol=0)


def test_concept1s_hub_post_is_a_coordinate_of_its_nine_parameter_region_and_not_of_a_line():
    """The hub post's width the reduced model takes as a coordinate is the one the concept's
    rule checks (its own angles, to round-off) at every sampled design; it runs across the
    box's axes, so a 9-parameter region's models get it, and a one-parameter region's do not
    (there it would repeat the one axis)."""
    from clutchfem.reduced.model import diagonal

    r = Region.around(live())
    pts = r.sample(20, seed=3)
    names, F = r.rule_dimensions(np.array([r.unit_of(p) for p in pts]))
    assert names == ("hub_post_width",)
    for p, f in zip(pts, F[:, 0]):
        q = live(**{k: f"{v}{'deg' if k == 'shoe_arc' else 'm'}" for k, v in p.items()}).params
        assert f == pytest.approx(q.angles()[3] * q.radii()[2], rel=1e-12)
        assert f >= 3e-3 - 1e-12  # the rule: a 3 mm post
    U = np.array([r.unit_of(p) for p in pts])
    assert diagonal(U, F)
    line = Region.around(live(), free=["flexure_thickness"])
    u = np.linspace(0, 1, 6)[:, None]
    assert not diagonal(u, line.rule_dimensions(u)[1])
    assert not diagonal(U[:, :1], U[:, :1] * 2.0) and diagonal(U[:, :2], U[:, :1] - 0.5 * U[:, 1:2])


def test_status_model_tells_the_answered_designs_from_the_others():
    U = np.random.default_rng(2).random((120, 3))
    ok = U[:, 0] ** 2 + 0.5 * U[:, 1] < 0.8  # a smooth divergence boundary
    s = StatusModel.fit(U, ok)
    test = np.random.default_rng(3).random((300, 3))
    truth = test[:, 0] ** 2 + 0.5 * test[:, 1] < 0.8
    assert np.mean((s.probability(test) > 0.5) == truth) > 0.95
    assert StatusModel.fit(U, np.ones(len(U), bool)).probability(test).min() == 1.0


@pytest.mark.parametrize("a", [0.05, -0.05])
def test_the_band_holds_every_held_out_design_even_with_no_fe_band(a):
    """The own error is measured relative to the FE's value; the band is relative to the live
    one: |live - FE| <= own |FE| = own/(1 - own) |live| holds on the design of the largest
    error too (an answer without a best-path band, like the mass, rests on it alone)."""
    import json

    from clutchfem.reduced import ReducedModel

    r = Region.around(live(), free=["flexure_thickness"])
    lo, hi = r.bounds("flexure_thickness")
    row = lambda t: {"status": "ok", "point_json": json.dumps({"flexure_thickness": t}),  # noqa: E731
                     "engagement_rpm": 1e3 * np.exp(a * np.sin(3e4 * t))}  # wiggly: errors of percent
    m = ReducedModel.fit(r, [row(t) for t in np.linspace(lo, hi, 5)])
    acc = m.measure([row(t) for t in np.linspace(lo, hi, 13)[1:-1:2]])
    assert acc["engagement_rpm"]["max_rel"] > 1e-2 and acc["engagement_rpm"]["within"] == 1.0


def test_a_design_whose_fe_band_is_wide_is_left_out_of_that_answers_fit_and_still_measured():
    """A training design whose best-path band says its value is unknown to +-60 % (concept 1's
    peak where the refined mesh met a degenerate element) does not bend the fit; a held-out
    design like it is counted apart and the band keeps the largest error of all."""
    import json

    from clutchfem.reduced import MAX_FE_BAND, ReducedModel

    r = Region.around(live(), free=["flexure_thickness"])
    lo, hi = r.bounds("flexure_thickness")
    truth = lambda t: 1e9 * (1.0 + 80.0 * (t - lo))  # noqa: E731  (a smooth peak stress [Pa])

    def row(t, value=None, band=0.02):
        v = truth(t) if value is None else value
        return {"status": "ok", "point_json": json.dumps({"flexure_thickness": t}),
                "max_von_mises_MPa": v / 1e6, "stress_err_MPa": band * v / 1e6}

    ts = np.linspace(lo, hi, 9)
    bad = row(ts[4], value=0.9 * truth(ts[4]), band=0.6)  # 10 % low, and the FE says +-60 %
    rows = [row(t) for t in ts[:4]] + [bad] + [row(t) for t in ts[5:]]
    probe = np.array([[0.5]])
    kept = ReducedModel.fit(r, rows)
    assert kept.info["left_out_wide_band"] == {"max_von_mises_Pa": 1}
    assert abs(kept.predict(probe)["value"]["max_von_mises_Pa"][0] / truth(ts[4]) - 1) < 1e-3
    # the same row with a narrow band is fitted: the model goes through its 10 % dip
    fitted = ReducedModel.fit(r, rows[:4] + [row(ts[4], value=0.9 * truth(ts[4]))] + rows[5:])
    assert abs(fitted.predict(probe)["value"]["max_von_mises_Pa"][0] / truth(ts[4]) - 1) > 0.05
    held = [row(t) for t in (ts[1] + ts[2]) / 2 + 0 * ts[:2]] + [row(ts[6] + 1e-6, value=0.95 * truth(ts[6]), band=0.3)]
    acc = kept.measure(held)["max_von_mises_Pa"]
    assert MAX_FE_BAND < 0.3 and acc["n_wide_fe_band"] == 1
    assert acc["max_rel_narrow_fe_band"] < 1e-3 < 0.04 < acc["max_rel"] and acc["within"] == 1.0


def test_the_engagement_with_ripple_is_derived_from_the_static_one_as_the_fe_derives_it():
    from clutchfem.clutch.ripple import effective_engagement_rpm
    from clutchfem.reduced.surrogate import RippleAnswer

    r = Region.around(live(), free=["flexure_thickness"])
    lo, hi = r.bounds("flexure_thickness")

    def row(t, ripple):
        s = 3e3 * (t / lo) ** 1.5
        return {"status": "ok", "point_json": json.dumps({"flexure_thickness": t}), "engagement_rpm": s,
                "engagement_ripple_rpm": ripple(s)}

    ts = np.linspace(lo, hi, 7)
    m = ReducedModel.fit(r, [row(t, lambda s: effective_engagement_rpm(s, k_sigma=3.0)) for t in ts])
    assert isinstance(m.models["engagement_rpm_with_ripple"], RippleAnswer)
    v = m.predict(np.array([[0.37]]))["value"]
    assert v["engagement_rpm_with_ripple"][0] == pytest.approx(
        effective_engagement_rpm(v["engagement_rpm"][0], k_sigma=3.0), rel=1e-12)
    # rows whose ripple answer is something else (another ripple model): a model of its own
    other = ReducedModel.fit(r, [row(t, lambda s: 0.9 * s) for t in ts])
    assert isinstance(other.models["engagement_rpm_with_ripple"], AnswerModel)
    assert other.predict(np.array([[0.37]]))["value"]["engagement_rpm_with_ripple"][0] == pytest.approx(
        0.9 * other.predict(np.array([[0.37]]))["value"]["engagement_rpm"][0], rel=1e-6)


def test_the_adaptive_designs_go_where_the_fit_knows_least_and_a_resumed_build_solves_the_same(tmp_path):
    from clutchfem.reduced.build import POOL, _adaptive

    r = Region.around(live(), free=["flexure_thickness", "clearance"])
    (t0, t1), (c0, c1) = r.bounds("flexure_thickness"), r.bounds("clearance")

    def row(u):  # an engagement of the kind the FE gives, known only on the box's lower-left quarter
        t, c = t0 + u[0] * (t1 - t0), c0 + u[1] * (c1 - c0)
        return {"status": "ok", "point_json": json.dumps({"flexure_thickness": t, "clearance": c}),
                "engagement_rpm": 3e3 * (t / t0) ** 1.5 * (c / c0) ** 0.5}

    grid = [(a, b) for a in np.linspace(0, 0.5, 4) for b in np.linspace(0, 0.5, 4)]
    first = ReducedModel.fit(r, [row(u) for u in grid])
    pool = np.random.default_rng(1).random((500, 2))
    picks = first.most_uncertain(pool, 6)
    assert len(set(picks)) == 6 and all(pool[i].max() > 0.6 for i in picks)  # none in the known quarter
    # the model is of log(y): its variance is a relative error squared, weighted by the answer's aim
    assert first.most_uncertain(pool, 6, aims={"engagement_rpm": 1.0}) == picks
    assert first.most_uncertain(pool, 6, aims={"torque_at_max_engine_torque_Nm": 0.005}) == []  # no such model
    # a pick that makes no part is passed over, the next best taken
    got = first.most_uncertain(pool, 2, admissible=lambda i: i != picks[0])
    assert len(got) == 2 and picks[0] not in got
    # the build's picks are written before they are solved; a resumed build reads them back even
    # where a refit would pick others
    points = _adaptive(first, tmp_path, 5, seed=0)
    assert len(points) == 5 and all(r.contains(p) for p in points)
    saved = json.loads((tmp_path / "adaptive.json").read_text())
    assert saved["key"] == {"n_fill": 16, "k": 5, "seed": 0, "pool": POOL} and saved["points"] == points
    (tmp_path / "fresh").mkdir()
    assert _adaptive(first, tmp_path / "fresh", 5, seed=0) == points  # the same fit picks the same
    other = ReducedModel.fit(r, [row((a, b)) for a in np.linspace(0, 0.3, 4) for b in np.linspace(0.2, 1, 4)])
    assert _adaptive(other, tmp_path / "fresh", 5, seed=0) == points  # resumed: read back, not re-picked
    (tmp_path / "other").mkdir()
    assert _adaptive(other, tmp_path / "other", 5, seed=0) != points  # (a refit there picks others)
    assert len(_adaptive(other, tmp_path, 4, seed=0)) == 4  # another build's file is not read


def test_a_build_solves_its_adaptive_designs_after_the_first_fit_and_fits_them_all(tmp_path, monkeypatch):
    """The build's order, its designs' FE replaced by hand-made rows (no FE; the doctest of
    :func:`clutchfem.reduce` builds a region of the FE itself): the space-filling and held-out
    designs first, then the designs the first fit knows least (written before they are solved),
    the error measured on the held-out ones, the final model fitted to every design, cached."""
    from clutchfem.reduced import build
    from clutchfem.reduced.build import _adaptive

    monkeypatch.setenv("CLUTCHFEM_CACHE", str(tmp_path / "cache"))  # the fitted model is not the FE's: kept apart
    d = live()
    r = Region.around(d, free=["flexure_thickness"])
    t0 = r.bounds("flexure_thickness")[0]
    row = lambda p: {"status": "ok", "point_json": json.dumps(p),  # noqa: E731
                     "engagement_rpm": 3e3 * (p["flexure_thickness"] / t0) ** 1.5}
    calls = []

    class Rows:  # the build's runner of designs, with rows of a known answer
        def __init__(self, region, folder, *a):
            self.compute_s, self.workers = 0.0, 0

        def __call__(self, points, desc):
            calls.append((desc, points))
            return [row(p) for p in points]

    monkeypatch.setattr(build, "_Runner", Rows)
    m = cf.reduce(d, free=["flexure_thickness"], n=9, held_out=2, adaptive=1 / 3, workers=0, progress=False)
    assert [(desc, len(p)) for desc, p in calls] == [("reduce", 8), ("reduce, adaptive", 3)]
    fill, held = calls[0][1][:6], calls[0][1][6:]
    assert fill == r.sample(6, seed=0) and held == r.sample(2, seed=1)
    first = ReducedModel.fit(r, [row(p) for p in fill])
    (tmp_path / "again").mkdir()
    assert calls[1][1] == _adaptive(first, tmp_path / "again", 3, seed=0)  # where the first fit knows least
    assert m.info["n_adaptive"] == 3 and m.info["n_train"] == 9 and m.info["fe_designs"] == len(m.rows) == 11
    assert [json.loads(x["point_json"]) for x in m.rows] == fill + calls[1][1] + held  # the final fit: every design
    assert m.accuracy["engagement_rpm"]["n"] == 2 and m.accuracy["engagement_rpm"]["max_rel"] < 1e-3
    assert cf.reduce(d, free=["flexure_thickness"], n=9, held_out=2, adaptive=1 / 3, workers=0,
                     progress=False).info == m.info and len(calls) == 2  # cached: loaded, no design solved


# -- the build and the live answers ---------------------------------------------------------
def fe_design():
    """The live design of flexure thickness 2.15 mm's best-path twin (what the region is built
    from, what the app's FE check solves)."""
    return cf.Design.from_concept("concept1", mesh=MESH, fidelity="best", flexure_thickness="2.15mm")


@pytest.fixture(scope="module")
def fe_215():
    """The full FE of :func:`fe_design` (best path, error step): one analysis the live
    answers of 2.15 mm are held against in the analyze test and the app's test."""
    return cf.analyze(fe_design())


@pytest.mark.slow
def test_reduce_builds_the_region_and_measures_its_error_on_held_out_designs(built):
    assert built["region"]["free"]["flexure_thickness"] == [pytest.approx(2.09e-3), pytest.approx(2.31e-3)]
    assert built["info"]["n_train"] == 3 and built["info"]["n_held_out"] == 2 and built["info"]["fe_designs"] == 5
    acc = built["accuracy"]
    for a in ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "max_von_mises_Pa"):
        assert acc[a]["n"] == 2 and 0 <= acc[a]["p95_rel"] < 0.01, (a, acc[a])  # 1-D, +-5 %: well below 1 %
    assert acc["mass_kg"]["p95_rel"] < 1e-4
    # again: loaded, not built (no FE: the same answer at once)
    again = json.loads(cli_in_process("reduce", "concept1", "--mesh-size", "3mm", "--free", "flexure_thickness",
                                      "--n", "3", "--held-out", "2", "--workers", "0", "--json", ok=True).stdout)
    assert again["info"] == built["info"]


@pytest.mark.slow
def test_live_analyze_answers_from_the_reduced_model_without_a_mesh_and_its_band_holds_the_fe(built, fe_215,
                                                                                               monkeypatch):
    d = live(flexure_thickness="2.15mm")
    a = cf.analyze(d)
    assert a.answered_by == "reduced model" and not d.meshed and a.region_key == built["region"]["key"]
    fe = fe_215
    for q, got, want in (("engagement_rpm", a.engagement_rpm, fe.engagement_rpm), ("slip_rpm", a.slip_rpm, fe.slip_rpm),
                         ("torque_at_max_engine_torque_Nm", a.torque_at_max_engine_torque_Nm,
                          fe.torque_at_max_engine_torque_Nm), ("max_von_mises_Pa", a.max_von_mises_Pa, fe.max_von_mises_Pa)):
        band = a.errors[q]["total"]
        assert abs(got - want) <= band, (q, got, want, band)
        assert band >= fe.errors[q]["total"] * 0.5  # the best path's band is in it (of its neighbours)
    assert a.safety_factor == pytest.approx(a.yield_strength_Pa / a.max_von_mises_Pa)
    assert "reduced model" in a.notes[0] and "measured on" in a.notes[0]
    # the command line: the same answer, said to be live
    doc = json.loads(cli_in_process("analyze", "concept1", "--mesh-size", "3mm", "--set", "flexure_thickness=2.15mm",
                                    "--fidelity", "live", "--json", ok=True).stdout)
    assert doc["answered_by"] == "reduced model" and doc["engagement_rpm"] == pytest.approx(a.engagement_rpm)
    # the table: each band said to be live, with the reduced model's own error (it once raised)
    from clutchfem.cli import common

    monkeypatch.setattr(common.console, "_width", 200)  # each row on one line
    text = cli_in_process("analyze", "concept1", "--mesh-size", "3mm", "--set", "flexure_thickness=2.15mm",
                          "--fidelity", "live", ok=True).stdout
    assert f"{a.engagement_rpm:.0f} rpm +- {a.errors['engagement_rpm']['total']:.0f} rpm (live:" in text
    assert "reduced model's own" in text


#: what a live answer from a cached reduced model must not load: the mesh (gmsh's meshing,
#: meshio), the FE model (scikit-fem), the contact and load cases, the FE steps, the reports' pages
#: and plots (the table's rows are clutchfem.report.answer_rows), the fit, scipy and pandas (gmsh
#: itself is loaded: a concept's geometry module imports its OCC helpers, ~20 ms)
FE_STACK = ("skfem", "meshio", "clutchfem.mesh", "clutchfem.fe", "clutchfem.contact", "clutchfem.softening",
            "clutchfem.loadcase.case", "clutchfem.analysis.pipeline", "clutchfem.report.design",
            "clutchfem.report.pages", "sklearn", "matplotlib", "scipy", "pandas")


@pytest.mark.slow
@pytest.mark.parametrize("json_out", [True, False], ids=["json", "table"])
def test_a_live_analyze_from_a_cached_region_loads_none_of_the_fe_stack(built, json_out):
    """The start-up of ``analyze --fidelity live``, its JSON and its table: a real process (what
    it imports is the process's), the region cached by the fixture."""
    argv = ["clutchfem", "analyze", "concept1", "--mesh-size", "3mm", "--set", "flexure_thickness=2.15mm",
            "--fidelity", "live"] + (["--json"] if json_out else [])
    code = textwrap.dedent(f"""
        import json, sys
        from clutchfem.cli import main
        sys.argv = {argv!r}
        try:
            main()
        except SystemExit as exc:
            assert not exc.code, exc.code
        print(json.dumps([m for m in {FE_STACK!r} if m in sys.modules]), file=sys.stderr)
        """)
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[1] / "src"), "COLUMNS": "200"}
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    # (a fallback to the FE loads it, rightly)
    if json_out:
        assert json.loads(r.stdout)["answered_by"] == "reduced model"
    else:
        assert "live: answered by the reduced model" in r.stdout and "engagement" in r.stdout
    assert json.loads(r.stderr.strip().splitlines()[-1]) == []


@pytest.mark.slow
def test_outside_every_region_live_falls_back_to_the_fe_and_says_so(built):
    d = live(flexure_thickness="2.6mm")
    a = live_analysis(d, build=False)
    assert a.answered_by == "FE (fallback)" and any("no reduced model holds this design" in n for n in a.notes)
    assert a.engagement_rpm > 0 and a.errors["engagement_rpm"]["discretisation"] is not None


@pytest.mark.slow
def test_the_app_answers_live_then_checks_with_the_fe_and_refuses_to_build(built, fe_215, tmp_path, monkeypatch):
    import copy

    from clutchfem.analysis import Requirements
    from clutchfem.app import session as app_session
    from clutchfem.app.figures import torque_chart
    from clutchfem.app.session import DesignSession

    s = DesignSession("concept1")
    s.mesh = MESH
    assert s.set_value("fidelity", "live") is None and s.set_value("flexure_thickness", 2.15) is None
    out = s.run()
    assert out.live and not out.design.meshed and out.seconds < 1.0
    same = cf.analyze(live(flexure_thickness="2.15mm"))
    assert out.analysis.engagement_rpm == same.engagement_rpm and out.analysis.slip_rpm == same.slip_rpm
    arc = next(r for r in out.rows if r[0].startswith("contact arc"))  # never "nan deg"
    given = out.analysis.contact_arc_at_max_engine_torque_deg is not None and np.isfinite(
        out.analysis.contact_arc_at_max_engine_torque_deg)
    assert arc[1:] == ((f"{out.analysis.contact_arc_at_max_engine_torque_deg:.3g} deg", "") if given
                       else ("-", "not given live (the FE gives it)"))
    chart = torque_chart(out.analysis)  # the engine curve and the live torque point (no FE curve)
    assert [x["name"].split()[0] for x in chart["series"]] == ["engine", "clutch"]
    # the app's FE check: the best path with its error step (what the region was built from) of
    # the 2.15 mm design, with the session's engine and requirements -- the very analysis of the
    # module's fe_215 (the same design, the same defaults): that one, not a second solve of it
    want = fe_design()
    real, checked = app_session.analyze, []

    def analyze(design, **kw):
        same = ((design.params, design.op, design._mesh_settings) == (want.params, want.op, MESH)
                and kw == {"engine": cf.EngineCurve.default(), "requirements": Requirements()})
        checked.append(same)
        return copy.deepcopy(fe_215) if same else real(design, **kw)

    monkeypatch.setattr(app_session, "analyze", analyze)
    shown, off = s.verify(out)
    monkeypatch.setattr(app_session, "analyze", real)
    assert checked == [True]  # one FE analysis, of that design with the defaults
    assert (out.fe_design.params, out.fe_design.op, out.fe_design._mesh_settings) == (want.params, want.op, MESH)
    fe = fe_215
    band = out.analysis.errors["engagement_rpm"]["total"]
    assert (abs(fe.engagement_rpm - out.analysis.engagement_rpm) > band) == any("engagement" in o for o in off)
    assert (shown is out) == (not off)
    # outside every region: the FE answers at once (no build of minutes), saying why
    assert s.set_value("flexure_thickness", 2.6) is None
    out = s.run()
    assert not out.live and out.analysis.answered_by == "FE (fallback)" and "no reduced model holds" in out.analysis.notes[-1]
    # an uploaded part has no parameters to reduce over: refused, naming the model
    s.set_part(out.design.cm.write_msh(tmp_path / "part.msh"))
    s.set_value("drum_radius", 34.4)
    with pytest.raises(cf.ParameterError, match="fidelity.*best or fast for an uploaded part"):
        s.run()


@pytest.mark.slow
def test_the_reduced_models_derivatives_match_the_morphed_finite_differences(built):
    """Measured on this region: engagement 0.7 %, slip 0.1 %, torque 1.1 % apart; the peak
    stress has a contact event inside the FE step (a kink the FE sees and the smooth model
    does not), so it is compared by its sign only."""
    from clutchfem.reduced import find

    d = live(flexure_thickness="2.2mm")
    s = find(d).sensitivities(d)
    assert s.methods["flexure_thickness"] == "central, reduced model" and "own error" in s.notes[0]
    fd = cf.sensitivities(d.with_fidelity("best"), ["flexure_thickness"], workers=0)
    assert fd.methods["flexure_thickness"].endswith("morphed")
    for a in ("engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm"):
        got, want = s.derivatives["flexure_thickness"][a], fd.derivatives["flexure_thickness"][a]
        assert got == pytest.approx(want, rel=0.03), a
    assert np.sign(s.derivatives["flexure_thickness"]["max_von_mises_Pa"]) == np.sign(
        fd.derivatives["flexure_thickness"]["max_von_mises_Pa"])
    assert s.derivatives["flexure_thickness"]["safety_factor"] > 0  # a thicker flexure: a lower peak
    with pytest.raises(cf.ParameterError, match="in the region"):
        find(d).sensitivities(live(flexure_thickness="2.6mm"))
    for kw, name in (({"names": ["clearance"]}, "names"), ({"h": 0.0}, "h"), ({"h": float("nan")}, "h"),
                     ({"h": True}, "h")):
        with pytest.raises(cf.ParameterError) as e:
            find(d).sensitivities(d, **kw)
        assert e.value.name == name


@pytest.mark.slow
def test_a_live_answer_writes_its_answers_and_a_live_design_report_is_refused(built, tmp_path):
    """``analyze --fidelity live --out``: the answers (JSON) and the engine's curve (CSV), no
    charts (the live answer has no clutch curves against rpm; it raised a KeyError before); the
    one-page report of a live design is refused, saying what gives it."""
    r = cli_in_process("analyze", "concept1", "--mesh-size", "3mm", "--set", "flexure_thickness=2.15mm",
                       "--fidelity", "live", "--out", str(tmp_path / "a"), ok=True)
    assert "Traceback" not in r.stderr
    names = sorted(p.suffix for p in (tmp_path / "a").iterdir())
    assert names == [".csv", ".json"]
    doc = json.loads(next((tmp_path / "a").glob("*_analysis.json")).read_text())
    assert doc["answered_by"] == "reduced model" and doc["curves"][0]["rpm"] > 0
    assert {"rpm", "engine_torque_Nm"} == set(doc["curves"][0])
    with pytest.raises(cf.ClutchfemError, match="answered by the reduced model.*fidelity 'best'"):
        cf.write_report(live(flexure_thickness="2.15mm"), tmp_path / "b")
