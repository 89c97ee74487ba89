"""``clutchfem life``: every bad input refused before any mesh, naming the option; the JSON of a
short life on a coarse mesh (arrays against the starts with units in the keys, the slip energy
per start, the energy balance), the options reaching the run, and the pictures in --out (slow)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from support.cli import cli_in_process
from support.pictures import rule

COARSE = ["--mesh-size", "3mm", "--rebuild-depth", "never"]
#: the starts of the short life: what is checked is the document, the options reaching the run
#: and the files, not the wear at the end (400 starts took 57 wear states, 100 take 16: the
#: run's cost is its wear steps, not the FE model)
STARTS = 100


def strict(text: str):
    def bad(c):
        raise ValueError(f"non-standard JSON constant {c}")
    return json.loads(text, parse_constant=bad)


@pytest.mark.parametrize("args, option", [
    (["--starts", "0"], "--starts"),
    (["--starts", "-5"], "--starts"),
    (["--engine-inertia", "-1e-3kg*m^2"], "--engine-inertia"),
    (["--driven-inertia", "0"], "--driven-inertia"),
    (["--drag-torque", "-0.1N*m"], "--drag-torque"),
    (["--cutting-torque", "3mm"], "--cutting-torque"),
    (["--throttle-ramp", "2mm"], "--throttle-ramp"),
    (["--wear-coefficient", "0"], "--wear-coefficient"),
    (["--drum-wear-coefficient", "-1e-5"], "--drum-wear-coefficient"),
    (["--hardness", "4mm"], "--hardness"),
    (["--drum-hardness", "0Pa"], "--drum-hardness"),
    (["--wear-regime", "wet"], "--wear-regime"),
    (["--max-wear-step", "2kg"], "--max-wear-step"),
    (["--wear-rate-change", "0"], "--wear-rate-change"),
    (["--rebuild-depth", "5"], "--rebuild-depth"),
])
def test_bad_values_are_refused_naming_the_option(args, option):
    r = cli_in_process("life", "concept4", *args)
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr
    assert f"option {option}" in r.stderr and "is not allowed" in r.stderr


def test_several_parameters_after_one_set_are_refused_saying_how():
    r = cli_in_process("life", "concept4", "--set", "hub_radius=9.04mm", "shoe_arc=100.8deg", "--starts", "10")
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "shoe_arc=100.8deg" in r.stderr and "each concept parameter takes its own --set" in r.stderr


def test_duty_file_in_wrong_units_or_missing_is_refused(tmp_path):
    f = tmp_path / "duty.toml"
    f.write_text('[duty]\nheld_slip_duration = "2 mm"\n')
    r = cli_in_process("life", "concept4", "--duty", str(f))
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert "option --duty" in r.stderr and "held_slip_duration" in r.stderr and "a time in s" in r.stderr
    r = cli_in_process("life", "concept4", "--duty", str(tmp_path / "none.toml"))
    assert r.returncode == 2 and "option --duty" in r.stderr and "not found" in r.stderr


@pytest.fixture(scope="module")
def short(tmp_path_factory):
    out = tmp_path_factory.mktemp("life")
    duty = out / "duty.toml"
    duty.write_text('[duty]\nstarts_per_hour = "30 1/h"\nheld_slips_per_hour = 1\nheld_slip_duration = "0.5 s"\n'
                    'cutting_share = 0.2\n')
    r = cli_in_process("life", "concept4", *COARSE, "--starts", str(STARTS), "--duty", str(duty), "--engine-inertia",
                       "1.1e-3kg*m^2", "--driven-inertia", "2.5e-4kg*m^2", "--drag-torque", "0.3N*m",
                       "--cutting-torque", "3N*m", "--throttle-ramp", "0.25s", "--wear-regime", "lubricated",
                       "--wear-coefficient", "2e-5", "--hardness", "4GPa", "--drum-wear-coefficient", "1e-5",
                       "--drum-hardness", "5GPa", "--max-wear-step", "8um", "--wear-rate-change", "0.3",
                       "--json", "--out", str(out))
    assert r.returncode == 0, r.stderr[-3000:]
    return strict(r.stdout), out, r.stderr


@pytest.mark.slow
def test_json_answers_against_starts_and_the_options_reached_the_run(short):
    d, _, _ = short
    arr = d["arrays"]
    n = len(arr["starts"])
    assert arr["starts"][0] == 0 and arr["starts"][-1] == STARTS and n >= 2
    for k in ("hours", "engagement_rpm", "slip_rpm", "torque_at_max_engine_torque_Nm", "contact_arc_deg",
              "slip_energy_per_start_J", "time_to_lockup_s", "drum_worn_m"):
        assert len(arr[k]) == n, k
    assert arr["hours"][-1] == pytest.approx(STARTS / 30)
    assert d["slip_energy_per_start_J"] == arr["slip_energy_per_start_J"][0] > 0
    assert 0 <= d["energy_balance"] < 1e-6
    a = d["assumptions"]
    dl, w, duty = a["drive_line"], a["wear"], a["duty_cycle"]
    assert (dl["engine_inertia"], dl["driven_inertia"], dl["drag_torque"], dl["cutting_torque"],
            dl["throttle_ramp"]) == (1.1e-3, 2.5e-4, 0.3, 3.0, 0.25)
    assert (w["regime"], w["k_used"], w["hardness"], w["drum_wear_coefficient"], w["drum_hardness"], w["max_step"],
            w["rate_change"]) == ("lubricated", 2e-5, 4e9, 1e-5, 5e9, 8e-6, 0.3)
    assert duty == {"starts_per_hour": 30.0, "held_slips_per_hour": 1.0, "held_slip_duration": 0.5,
                    "cutting_share": 0.2}
    # the given k with the lubricated band's ratios (1e-9..1e-7 around 1e-8)
    assert d["band"]["wear_coefficient_band"] == pytest.approx([2e-6, 2e-4])
    assert d["wear_steps"]["rebuild_depth_m"] is None and d["rebuilds_at_starts"] == []
    assert d["wear_steps"]["step_limit_m"]["max"] <= 8e-6


@pytest.mark.slow
def test_out_writes_the_json_and_pictures_that_keep_the_rule(short):
    d, out, stderr = short
    stem = d["label"] + "_life"
    files = {p.name for p in out.iterdir()}
    assert {f"{stem}.json", f"{stem}_answers.png", f"{stem}_pressure.png"} <= files
    for name in (f"{stem}.json", f"{stem}_answers.png", f"{stem}_pressure.png"):
        assert f"wrote {out / name}" in stderr
    assert strict((out / f"{stem}.json").read_text())["arrays"] == d["arrays"]
    rec = rule(out / f"{stem}_answers.png")
    labels = [ax["ylabel"] for ax in rec["axes"]]
    assert "engagement speed [rpm]" in labels and "slip speed [rpm]" in labels
    # the requirement limits are drawn and named with their value
    legend = " ".join(t for ax in rec["axes"] for t in ax["legend"])
    assert f"{d['limits']['engagement_min_rpm']:.0f} rpm" in legend and f"{d['limits']['slip_max_rpm']:.0f} rpm" in legend
    rec = rule(out / f"{stem}_pressure.png")
    assert any("new" in t for ax in rec["axes"] for t in ax["legend"])
    # the wearing part for ParaView: the collection indexes one .vtu per kept state by its starts
    import xml.etree.ElementTree as ET

    pvd = out / f"{stem}.pvd"
    assert f"wrote {pvd}" in stderr
    sets = ET.parse(pvd).getroot().find("Collection").findall("DataSet")
    steps = [float(e.get("timestep")) for e in sets]
    assert steps[0] == 0 and steps[-1] == STARTS and steps == sorted(steps) and len(steps) >= 2
    starts = np.asarray(d["arrays"]["starts"])
    assert all(np.min(np.abs(starts - n)) <= 1e-9 * max(n, 1.0) for n in steps)
    assert all((out / e.get("file")).is_file() for e in sets)
