"""ValidationRecord: status rules, relative difference, JSON form."""

from __future__ import annotations

import math

import pytest

from clutchfem.validation.records import ValidationRecord


def test_status_follows_tolerance_on_either_side():
    assert ValidationRecord("m.a", "m", "q", 10.0, 10.19, "N m", tol=0.02).status == "reproduced"
    assert ValidationRecord("m.a", "m", "q", 10.0, 9.81, "N m", tol=0.02).status == "reproduced"
    assert ValidationRecord("m.a", "m", "q", 10.0, 10.21, "N m", tol=0.02).status == "differs"
    assert ValidationRecord("m.a", "m", "q", -10.0, -10.5, "%", tol=0.02).status == "differs"
    r = ValidationRecord("m.a", "m", "q", None, 3.0, "rpm")
    assert r.status == "computed" and math.isnan(r.rel_diff)


def test_rel_diff_is_relative_to_the_paper_magnitude():
    assert ValidationRecord("m.a", "m", "q", -6.0, -5.4, "%").rel_diff == pytest.approx(0.1)
    assert ValidationRecord("m.a", "m", "q", 4.0, 3.0, "-").rel_diff == pytest.approx(-0.25)


def test_status_cannot_be_set_and_json_has_the_issue_keys():
    with pytest.raises(TypeError):
        ValidationRecord("m.a", "m", "q", 1.0, 1.0, "-", status="reproduced")  # type: ignore[call-arg]
    d = ValidationRecord("m.a", "m", "q", None, 2.0, "kg", note="n").to_json()
    assert {"id", "paper", "computed", "unit", "status", "note"} <= set(d)
    assert d["rel_diff"] is None and d["status"] == "computed"
