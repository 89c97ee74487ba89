"""Coupled limits (issue 37): a cross-parameter rule that the user's change breaks at another
parameter names both and a way out at the parameter changed; the feasible range of a parameter
given the others is the set the parameter set accepts (checked against probes, not numbers
written here); the app's sliders get those ranges."""

from __future__ import annotations

import re

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.app import DesignSession
from clutchfem.core import ParameterError

P4 = cf.get_concept("concept4").Params


def _accepts(P, values, name, x) -> bool:
    try:
        P(**{**values, name: x})
        return True
    except ParameterError:
        return False


@pytest.mark.parametrize("concept", ["concept1", "concept4", "concept5"])
def test_feasible_range_is_what_the_rules_accept(concept):
    """Inside the range every probe is accepted; just outside a cut end it is refused; a
    declared end that the rules do not cut is the end."""
    P = cf.get_concept(concept).Params
    values = P().model_dump()
    for name in [n for n in P.model_fields if P._numeric(n) and not n.startswith("table_c")][:12]:
        lo, hi = P.feasible_range(values, name)
        dlo, dhi = cf.core.param_bounds(P, name)
        assert lo is not None and dlo <= lo <= values[name] <= hi <= dhi, (name, lo, hi)
        integer = P.model_fields[name].annotation is int
        probes = np.unique(np.round(np.linspace(lo, hi, 7))) if integer else np.linspace(lo, hi, 7)
        assert all(_accepts(P, values, name, int(x) if integer else float(x)) for x in probes), name
        step = 1 if integer else 4 * cf.core.resolution(P, name)
        if hi < dhi:
            assert not _accepts(P, values, name, hi + step), (name, hi)
        if lo > dlo:
            assert not _accepts(P, values, name, lo - step), (name, lo)


def test_refusal_names_both_parameters_and_a_way_out():
    """flexure_thickness 2.4 mm breaks the beam-end rule of flexure_length (the user did not
    touch it): the refusal names flexure_length's limit and flexure_thickness's feasible range,
    from the API, the parameter set's replace and the CLI's --set alike."""
    lo, hi = P4.feasible_range(P4().model_dump(), "flexure_thickness")
    for make in (lambda: cf.Design.from_concept("concept4", flexure_thickness="2.4mm"),
                 lambda: P4().replace(flexure_thickness=2.4e-3),
                 lambda: P4(**P4.parse_assignments(["flexure_thickness=2.4mm"]))):
        with pytest.raises(ParameterError) as e:
            make()
        msg = str(e.value)
        assert e.value.name == "flexure_length" and "flexure_length' = 19 mm" in msg
        m = re.search(r"flexure_thickness \(now 2\.4 mm\) within \[([\d.]+) mm, ([\d.]+) mm\]", msg)
        assert m, msg  # the limit found by bisection to the parameter's resolution (0.01 mm)
        assert float(m[1]) == pytest.approx(lo * 1e3, abs=0.01) and float(m[2]) == pytest.approx(hi * 1e3, abs=0.01)
    assert _accepts(P4, P4().model_dump(), "flexure_thickness", hi)
    assert not _accepts(P4, P4().model_dump(), "flexure_thickness", 2.4e-3)


def test_a_refusal_at_the_parameter_given_is_unchanged():
    """Out of the declared range: the plain refusal (no advice about other parameters)."""
    with pytest.raises(ParameterError) as e:
        cf.Design.from_concept("concept4", flexure_thickness="9mm")
    assert e.value.name == "flexure_thickness" and "with the others" not in str(e.value)


def test_session_sliders_get_the_feasible_ranges():
    s = DesignSession("concept4")
    feas = s.feasible()
    lo, hi = P4.feasible_range(s.params.model_dump(), "flexure_thickness")
    assert feas["flexure_thickness"] == pytest.approx((lo * 1e3, hi * 1e3))
    c = next(c for c in s.controls() if c.name == "flexure_thickness")
    assert feas["flexure_thickness"][1] < c.hi  # the rule cuts the declared 4 mm
    assert s.set_value("hub_radius", 10.0) is None
    assert s.feasible()["flexure_thickness"] != feas["flexure_thickness"]  # it follows the others
