"""The table shoe profile (geometry/concept.py, geometry/profile.py) and --set texts that round-trip exactly."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchfem.core import ParameterError
from clutchfem.core import values as V
from clutchfem.geometry import TABLE_FIELDS, TABLE_N, MeshSettings, get_concept
from clutchfem.loadcase import Design
from clutchfem.mesh import cache_key

COARSE = MeshSettings(size=2.4e-3)


def test_inert_table_values_leave_dump_and_cache_key_unchanged():
    """For every other profile the table values are left out of model_dump: the cache key and the
    recorded inputs of existing designs do not change when the table profile is added."""
    c = get_concept("concept4")
    p = c.params()
    q = c.params(table_c3=1.1e-3)  # inert: the profile is concentric
    assert not any(n in p.model_dump() for n in TABLE_FIELDS)
    assert cache_key(c, p, COARSE) == cache_key(c, q, COARSE)
    t = c.params(profile="table")
    assert all(n in t.model_dump() for n in TABLE_FIELDS)
    assert cache_key(c, t, COARSE) != cache_key(c, p, COARSE)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["concept1", "concept4"])
def test_uniform_table_is_the_concentric_shoe(name):
    """A table of equal clearances is the concentric circle: same engagement speed (closed form,
    FE) to the spline's representation error."""
    c = get_concept(name)
    e0 = Design.from_concept(c, c.params(), None, COARSE).case().engagement_rpm
    e1 = Design.from_concept(c, c.params(profile="table"), None, COARSE).case().engagement_rpm
    assert abs(e1 - e0) / e0 < 1e-4, (e0, e1)


@pytest.mark.slow
def test_table_profile_follows_the_spline_at_the_contact_nodes():
    """The meshed contact nodes sit on the tabulated clearance c(s): rest gap = spline value."""
    c = get_concept("concept4")
    vals = np.linspace(0.3e-3, 1.1e-3, TABLE_N) + 0.1e-3 * np.sin(np.linspace(0, 3, TABLE_N))
    p = c.params(profile="table", **dict(zip(TABLE_FIELDS, vals)))
    d = Design.from_concept(c, p, None, COARSE)
    nd = d.nodes
    root, tip = d.cm.contact_arcs[0]
    s = (nd.angle - root) / (tip - root)
    err = np.abs(nd.gap0 - p.table_clearance(s))
    assert err.max() < 1e-7, err.max()  # 0.1 um on a 0.3-1.2 mm clearance


def test_table_that_dips_to_the_drum_is_refused_naming_a_control_value():
    """A C2 spline overshoots next to a spike: small control values beside a large one dip below
    the 0.02 mm the profile must keep; the refusal names the control value nearest the dip."""
    from clutchfem.geometry import table_spline as _table_spline

    c = get_concept("concept4")
    vals = [0.06e-3] * TABLE_N
    vals[8] = 2.0e-3
    assert _table_spline(tuple(vals))(np.linspace(0, 1, 2001)).min() < 0.02e-3  # the premise
    with pytest.raises(ParameterError) as e:
        c.params(profile="table", **dict(zip(TABLE_FIELDS, vals)))
    assert e.value.name in ("table_c6", "table_c7", "table_c9", "table_c10") and "0.02 mm" in str(e.value)
    with pytest.raises(ParameterError) as e:
        c.params(profile="table", table_c4=0.01e-3)  # below the declared range
    assert e.value.name == "table_c4"


@settings(max_examples=60, deadline=None, derandomize=True, database=None)
@given(v=st.floats(0.3e-3, 6e-3, allow_nan=False), name=st.sampled_from(
    ["flexure_thickness", "shoe_thickness", "clearance", "table_c5"]))
def test_set_texts_round_trip_exactly(v, name):
    """What the tools print for --set is read back as the very value that was evaluated."""
    P = get_concept("concept4").Params
    val, txt = V.snap(P, name, v)
    assert V.from_text(P, name, txt) == val
    assert abs(val - v) <= V.resolution(P, name)
    assert V.from_text(P, name, V.exact_text(P, name, v)) == v
    assert txt.endswith("mm")


def test_angle_and_plain_texts():
    P = get_concept("concept4").Params
    assert V.snap(P, "shoe_arc", 91.26)[1] == "91.3deg"
    assert V.snap(P, "flexure_taper", 1.2999)[1] == "1.3"
    assert math.isclose(V.from_text(P, "shoe_arc", "91.3deg"), 91.3)
