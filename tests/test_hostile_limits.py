"""Issue 24: physical limits the slip-heat answer passed without a word (the shoe face at
1873 C, above steel's melting point; the flexure at 955 C). Each level where the model stops
holding is flagged with its time; past a phase change the answer is cut there; a clearance
closed by thermal growth is flagged."""

from __future__ import annotations

import numpy as np
import pytest

from clutchfem.thermal import EXPANSION_PER_K, MELTING_C, PHASE_CHANGE_C, slip_heat_validity


def _doc(part_max, part_mean=None, flexure=None, seconds=10.0, pause=0.0, cycles=None, time_to_limit=None):
    n = len(part_max)
    t = list(np.linspace(0.0, seconds, n))
    return {"series": {"times_s": t, "part_max_C": list(part_max),
                       "part_mean_C": list(part_mean if part_mean is not None else [25.0] * n),
                       "flexure_C": None if flexure is None else list(flexure), "hub_C": [25.0] * n,
                       "shoe_face_C": list(part_max)},
            "ambient_temperature_C": 25.0, "seconds": seconds, "pause_s": pause, "cycles_table": cycles or [],
            "time_to_limit_s": time_to_limit, "peak_temperature_C": max(part_max), "peak_time_s": 0.0}


def test_an_answer_in_range_carries_no_flag_and_is_not_cut():
    v = slip_heat_validity(_doc([25, 100, 300, 390]), limit_C=400.0)
    assert v == {"valid": True, "validity": []}


def test_past_tempering_the_answer_stands_flagged_with_the_crossing_time():
    v = slip_heat_validity(_doc([25.0, 300.0, 500.0, 600.0], seconds=3.0), limit_C=400.0)
    assert v["valid"] and [f["flag"] for f in v["validity"]] == ["tempering"]
    assert v["validity"][0]["time_s"] == pytest.approx(1.5)  # 300 -> 500 C between 1 and 2 s
    assert "estimates" in v["validity"][0]["meaning"]


def test_past_the_phase_change_the_transient_is_cut_there_and_melting_is_only_a_warning():
    pm = [25.0, 500.0, 900.0, 1500.0, 1873.0]
    fl = [25.0, 100.0, 400.0, 955.0, 955.0]
    cyc = [{"cycle": 1, "end_of_slip_part_max_C": 1873.0}]
    v = slip_heat_validity(_doc(pm, flexure=fl, seconds=4.0, cycles=cyc, time_to_limit=2.0), limit_C=400.0)
    flags = {f["flag"]: f for f in v["validity"]}
    assert list(flags) == ["tempering", "phase change", "melting"] and not v["valid"]
    stop = 1.0 + (PHASE_CHANGE_C - 500.0) / 400.0
    assert v["stopped_at_s"] == pytest.approx(stop) and flags["phase change"]["time_s"] == pytest.approx(stop)
    assert "stopped there" in flags["phase change"]["meaning"] and "not an answer" in flags["melting"]["meaning"]
    assert flags["melting"]["time_s"] == pytest.approx(2.0 + (MELTING_C - 900.0) / 600.0)
    # every reported number is from before the cut: no 1873 C, no 955 C, no late limit crossing
    assert v["series"]["times_s"] == [0.0, 1.0, pytest.approx(stop)]
    assert v["peak_temperature_C"] == pytest.approx(PHASE_CHANGE_C) and v["peak_time_s"] == pytest.approx(stop)
    assert v["flexure_temperature_C"] == pytest.approx(100.0 + (stop - 1.0) * 300.0)
    assert v["time_to_limit_s"] is None and v["cycles_table"] == []


def test_a_clearance_closed_by_thermal_growth_is_flagged():
    gap, r = 0.3e-3, 34e-3
    T_close = 25.0 + gap / (EXPANSION_PER_K * r)  # ~760 C mean: only a very hot part
    mean = [25.0, 0.5 * T_close, 1.5 * T_close]
    v = slip_heat_validity(_doc([25.0, 300.0, 390.0], part_mean=mean, seconds=2.0), limit_C=400.0,
                           clearance_m=gap, contact_radius_m=r)
    (f,) = v["validity"]
    assert f["flag"] == "clearance closed" and f["level_C"] == pytest.approx(T_close)
    assert f["time_s"] == pytest.approx(1.5) and "drags at idle" in f["meaning"] and v["valid"]
    tight = slip_heat_validity(_doc([25.0, 30.0], part_mean=[25.0, 30.0]), limit_C=400.0, clearance_m=1e-6,
                               contact_radius_m=r)
    assert [x["flag"] for x in tight["validity"]] == ["clearance closed"]


def test_another_materials_phase_change_and_melting_are_its_own():
    """An aluminium part melts near 600 C: the steel defaults would have let 700 C pass."""
    from clutchfem.thermal import ThermalMaterial

    al = ThermalMaterial(limit_temperature=150.0, phase_change_temperature=580.0, melting_temperature=600.0)
    v = slip_heat_validity(_doc([25.0, 500.0, 700.0], seconds=2.0), limit_C=al.limit_temperature,
                           phase_change_C=al.phase_change_temperature, melting_C=al.melting_temperature)
    assert [f["flag"] for f in v["validity"]] == ["tempering", "phase change", "melting"]
    assert v["stopped_at_s"] == pytest.approx(1.4) and v["peak_temperature_C"] == pytest.approx(580.0)
    with pytest.raises(Exception, match="phase_change_temperature"):
        ThermalMaterial(phase_change_temperature=5000.0)
