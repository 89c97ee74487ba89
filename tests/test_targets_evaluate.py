"""evaluate_many on the study engine: refusals found here without sending anything, rows in
the order of the points, the design evaluated is the one `--set` builds from the texts."""

import pytest

from clutchfem.core import ParameterError
from clutchfem.evaluation import EvalSettings, context_hash, evaluate_many
from clutchfem.evaluation.batch import shared_cluster

SIZE = 2.4e-3


@pytest.mark.slow
def test_rows_in_order_with_refusals_in_process(tmp_path):
    s = EvalSettings("concept4", mesh_size=SIZE, store=str(tmp_path / "results.sqlite"))
    pts = [{"flexure_thickness": "1.7mm"}, {"flexure_thickness": "9mm"}, {"flexure_thickness": "1.7mm"},
           {"flexure_length": "30mm"}]
    rows = evaluate_many(pts, s, workers=0)
    assert [r["i"] for r in rows] == [0, 1, 2, 3]
    assert [r["status"] for r in rows] == ["ok", "refused", "ok", "refused"]
    assert rows[1]["refused_parameter"] == "flexure_thickness" and rows[1]["seconds"] == 0.0
    assert rows[3]["refused_parameter"] == "flexure_length" and "mm" in rows[3]["message"]
    assert rows[0]["design_hash"] == rows[2]["design_hash"] and rows[0]["slip_rpm"] == rows[2]["slip_rpm"]
    r = rows[0]
    assert r["params"] == {"flexure_thickness": "1.7mm"}
    assert 0.05 < r["mass_kg"] < 0.5 and 100e6 < r["max_von_mises_Pa"] < 1e10  # SI units
    assert r["safety_factor"] == pytest.approx(r["yield_strength_Pa"] / r["max_von_mises_Pa"], rel=1e-9)
    # the same design through analyze: identical answers (same values, same mesh)
    from clutchfem.analysis import analyze
    from clutchfem.geometry import MeshSettings, get_concept
    from clutchfem.loadcase import Design

    c = get_concept("concept4")
    an = analyze(Design.from_concept(c, c.Params.from_assignments(["flexure_thickness=1.7mm"]), None,
                                     MeshSettings(size=SIZE)), errors=False)
    assert an.slip_rpm == pytest.approx(r["slip_rpm"], rel=1e-12)
    assert an.max_von_mises_Pa == pytest.approx(r["max_von_mises_Pa"], rel=1e-9)
    assert (tmp_path / "results.sqlite").exists()  # every design kept with its inputs (study store)


@pytest.mark.slow
def test_on_a_local_dask_cluster():
    s = EvalSettings("concept4", mesh_size=SIZE)
    with shared_cluster(1) as address:
        assert str(address).startswith("tcp://")
        rows = evaluate_many([{"hub_radius": "12.5mm"}, {"hub_radius": "11.5mm"}], s)
    assert [r["status"] for r in rows] == ["ok", "ok"]
    assert rows[0]["worker"] and rows[0]["engagement_rpm"] > rows[1]["engagement_rpm"]


def test_workers_are_checked():
    with pytest.raises(ParameterError):
        evaluate_many([], EvalSettings("concept4"), workers=-1)
    with pytest.raises(ParameterError):
        with shared_cluster(2, "tcp://127.0.0.1:1"):
            pass


@pytest.mark.slow
def test_a_design_asked_for_again_in_this_process_is_not_solved_again(tmp_path, monkeypatch):
    """Without a store of the caller's, a design this process already evaluated (same hash:
    design, settings, model version) is served from its recent rows; with a store the design
    is evaluated into it, as the caller asked."""
    import clutchfem.evaluation.batch as batch

    s = EvalSettings("concept4", mesh_size=6e-3)
    pt = {"flexure_thickness": "1.72mm"}
    first = evaluate_many([pt], s, workers=0)[0]
    assert first["status"] == "ok" and (first["design_hash"], context_hash(s.study())) in batch.RECENT_ROWS

    def no_solve(*a, **k):
        raise AssertionError("solved again")

    monkeypatch.setattr(batch, "run_points", no_solve)
    again = evaluate_many([pt, {"flexure_thickness": "9mm"}], s, workers=0)
    assert [r["status"] for r in again] == ["ok", "refused"]
    assert {k: v for k, v in again[0].items() if k != "i"} == {k: v for k, v in first.items() if k != "i"}
    with pytest.raises(AssertionError, match="solved again"):  # a store of the caller's: into it
        evaluate_many([pt], EvalSettings("concept4", mesh_size=6e-3, store=str(tmp_path / "r.sqlite")), workers=0)
