"""evaluate_many: one process per design, refusals without a process, crashes and timeouts
cost one row, rows in the order of the points."""

import os
import time

import pytest

from clutchfem.errors import ParameterError
from clutchfem.targets import evaluate as E


def _fake(point, settings):
    kind = point.get("kind_")
    if kind == "crash":
        os._exit(3)  # what a gmsh abort looks like to the parent
    if kind == "sleep":
        time.sleep(30)
    return {"params": dict(point), "status": "ok", "message": "", "pid": os.getpid(), "x": point.get("x")}


class _Settings(E.EvalSettings):
    def params(self, point=None):  # no concept: refuse one marked point, accept the rest
        if point and point.get("kind_") == "refuse":
            raise ParameterError("x", point.get("x"), "anything but this")
        return None


def test_statuses_and_order(monkeypatch):
    monkeypatch.setattr(E, "evaluate_one", _fake)  # forked children inherit the patch
    s = _Settings(concept="none", timeout_s=2.0)
    pts = [{"x": "1"}, {"x": "2", "kind_": "crash"}, {"x": "3", "kind_": "refuse"}, {"x": "4", "kind_": "sleep"},
           {"x": "5"}]
    seen = []
    t0 = time.perf_counter()
    rows = E.evaluate_many(pts, s, workers=2, on_row=seen.append)
    assert time.perf_counter() - t0 < 15
    assert [r["i"] for r in rows] == [0, 1, 2, 3, 4]
    assert [r["status"] for r in rows] == ["ok", "crashed", "refused", "timeout", "ok"]
    assert rows[0]["pid"] != os.getpid() and rows[0]["pid"] != rows[4]["pid"]  # a process per design
    assert "exit code 3" in rows[1]["message"]
    assert rows[2]["refused_parameter"] == "x" and rows[2]["seconds"] == 0.0
    assert len(seen) == 5


def test_workers_are_checked():
    with pytest.raises(ParameterError):
        E.evaluate_many([], _Settings(concept="none"), workers=0)
