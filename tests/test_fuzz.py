"""Property-based fuzzing of the public API and the CLI (issue 12): whatever the input,
clutchfem raises only its documented errors (ClutchfemError subclasses, or exits with code 2
naming the problem), and every answer it does give passes the same invariants: torques and
contact forces >= 0, slip speed >= engagement speed, contact only above engagement, a
small equilibrium residual."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from clutchfem.analysis import analyze
from clutchfem.cli import app
from clutchfem.core import ClutchfemError
from clutchfem.geometry import MeshSettings, get_concept
from clutchfem.loadcase import Design, OperatingPoint
from clutchfem.mesh import mesh_concept

COARSE = MeshSettings(size=3e-3)
FUZZ = settings(max_examples=25, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])

weird_floats = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.floats(-2.0, 2.0),
                         st.sampled_from([0.0, -0.0, 1e-300, 1e300]))


@pytest.fixture(scope="module")
def c1():
    c = get_concept("concept1")
    p = c.params()
    return mesh_concept(c, p, COARSE), p


def check_answer(res) -> None:
    c = res.curve
    assert np.all(res.lam >= 0)
    assert np.all(c["torque_Nm"] >= 0) and np.all(c["normal_force_N"] >= 0)
    assert float(c["residual"].max()) < 1e-3
    touching = c["rpm"][c["normal_force_N"] > 0]
    if len(touching):
        assert touching.min() >= res.engagement_rpm * (1 - 1e-9)


@pytest.mark.slow
@FUZZ
@given(mu=st.one_of(weird_floats, st.sampled_from([0.0, 0.165, 0.5, 1.0])),
       rotation=st.sampled_from(["ccw", "cw", "CCW", "left", ""]),
       softening=st.sampled_from(["ritz", "modal", "off", "exact", "Ritz", "none"]),
       rpm=st.one_of(st.lists(weird_floats, min_size=0, max_size=4),
                     st.sampled_from(["0:14000:2000", "8000", "14000,0,7000", "1:2", "a:b:c", "0:1e9:1e3"])))
def test_api_operating_points(c1, mu, rotation, softening, rpm):
    cm, p = c1
    try:
        op = OperatingPoint(mu=mu, rotation=rotation, softening=softening if softening != "exact" else "off")
        res = Design(cm, op, params=p).sweep(rpm)
    except ClutchfemError:
        return
    check_answer(res)


@st.composite
def concept_params(draw):
    name = draw(st.sampled_from(["concept1", "concept4"]))
    P = get_concept(name).Params
    names = [n for n in ("flexure_thickness", "flexure_length", "clearance", "shoe_arc", "n_shoes") if n in P.model_fields]
    chosen = draw(st.lists(st.sampled_from(names), min_size=1, max_size=3, unique=True))
    vals = {}
    for n in chosen:
        f = P.model_fields[n]
        lo = next((m.ge for m in f.metadata if getattr(m, "ge", None) is not None), 0.0)
        hi = next((m.le for m in f.metadata if getattr(m, "le", None) is not None), 1.0)
        x = draw(st.floats(lo - 0.2 * (hi - lo), hi + 0.2 * (hi - lo), allow_nan=False))
        vals[n] = int(round(x)) if f.annotation is int else x
    return name, vals


@pytest.mark.slow
@FUZZ
@given(cp=concept_params(), mu=st.sampled_from([0.0, 0.165, 0.6]))
def test_api_concept_parameters_and_analysis(cp, mu):
    name, vals = cp
    try:
        d = Design.from_concept(name, get_concept(name).params(**vals), OperatingPoint(mu=mu), COARSE)
        an = analyze(d)
    except ClutchfemError:
        return
    assert an.torque_at_max_engine_torque_Nm >= 0
    if an.slip_rpm is not None and an.engagement_rpm is not None:
        assert an.slip_rpm >= an.engagement_rpm * (1 - 1e-9)
    assert an.slip_status in ("slips", "holds at start", "never holds", "never engages")
    if an.slip_status == "never engages":
        assert an.slip_rpm is None and an.torque_at_max_engine_torque_Nm == 0
    assert math.isfinite(an.max_von_mises_Pa) and an.max_von_mises_Pa >= 0


OPTIONS = {
    "--mu": ["0.2", "-1", "abc", "nan", "2"],
    "--rpm": ["0:14000:3500", "8000", "-5", "0:1:0", "1e9", ""],
    "--set": ["flexure_thickness=2mm", "n_shoes=3deg", "clearance=0", "bogus=1", "flexure_thickness"],
    "--mesh-size": ["3mm", "0.00001", "-1", "10 mm", "3"],
    "--rotation": ["cw", "up"],
    "--spin-softening": ["off", "magic"],
    "--material": ["titanium", "cheese"],
}


@pytest.mark.slow
@FUZZ
@given(cmd=st.sampled_from(["solve", "analyze"]),
       opts=st.dictionaries(st.sampled_from(sorted(OPTIONS)), st.integers(0, 5), max_size=3))
def test_cli_never_tracebacks(cmd, opts):
    args = [cmd, "concept1"]
    if "--mesh-size" not in opts:
        args += ["--mesh-size", "3mm"]
    for k, i in opts.items():
        args += [k, OPTIONS[k][i % len(OPTIONS[k])]]
    r = CliRunner().invoke(app, args)
    assert r.exit_code in (0, 2), (args, r.output)
    assert r.exception is None or isinstance(r.exception, SystemExit), (args, repr(r.exception))
    assert "Traceback" not in r.output
