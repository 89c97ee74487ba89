"""Hostile inputs, round 4 (issue 37) and the options of this round's features: each class
answered by a refusal that names the option, its value and what is allowed, before any work."""

from __future__ import annotations

import socket

import pytest

from clutchfem.studies import load_study
from support.cli import cli_in_process


def refused(*args, env: dict | None = None) -> str:
    r = cli_in_process(*args, env=env)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    return r.stderr


@pytest.mark.parametrize("opt", [("--yield", "1.5"), ("--rounds", "11"), ("--no-model-error",), ("--check", "20"),
                                 ("--dist", "uniform")])
def test_robust_design_options_without_tolerances_are_refused_not_dropped(opt):
    err = refused("optimize", "concept4", *opt)
    assert f"option {opt[0]}" in err and "--tol" in err


@pytest.mark.parametrize("cmd", [("export", "concept4"), ("solve", "concept4"), ("compensate", "concept4", "--rpm",
                                                                                  "8000"),
                                 ("life", "concept4"), ("slip-heat", "concept4")])
def test_live_fidelity_is_refused_by_the_commands_that_need_the_fe(cmd):
    err = refused(*cmd, "--fidelity", "live")
    assert "--fidelity" in err and "analyze and tolerance" in err


def test_a_live_optimisation_no_cached_region_holds_is_refused_before_any_work(tmp_path, monkeypatch):
    monkeypatch.setenv("CLUTCHFEM_CACHE", str(tmp_path))  # an empty cache: no region holds the start
    err = refused("optimize", "concept4", "--fidelity", "live")
    assert "clutchfem reduce concept4" in err and "--fidelity best" in err


@pytest.mark.parametrize("args, what", [(("--span", "0"), "span"), (("--span", "2"), "(0, 0.5]"),
                                        (("--n", "2"), "[3, 5000]"), (("--held-out", "0"), "[2, 5000]"),
                                        (("--free", "profile"), "continuous parameter"),
                                        (("--range", "flexure_thickness=3mm:1mm"), "lo < hi"),
                                        (("--range", "flexure_thickness=1mm"), "name=LO:HI"),
                                        (("--workers", "-1"), "--workers")])
def test_reduce_refuses_a_bad_region_or_build_before_any_design(args, what):
    assert what in refused("reduce", "concept4", *args)


def test_tolerance_check_is_an_option_of_the_live_fidelity():
    err = refused("tolerance", "concept4", "--tol", "flexure_thickness=+-0.05mm", "--check", "5")
    assert "option --check" in err and "--fidelity live" in err


def test_a_study_spec_with_a_byte_order_mark_reads_as_without(tmp_path):
    plain = cli_in_process("study", "--example", ok=True).stdout
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + plain.encode())
    assert len(load_study(path).points()) == 12


def test_the_app_refuses_a_port_in_use_and_an_out_that_is_a_file(tmp_path):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        err = refused("app", "--port", str(port), "--no-browser")
    assert f"127.0.0.1:{port} is in use" in err and "--port" in err and "clutchfem app on" not in err
    f = tmp_path / "afile"
    f.write_text("x")
    with socket.socket() as s:  # a port free now (closed again before the app asks for it)
        s.bind(("127.0.0.1", 0))
        free = s.getsockname()[1]
    assert "is a file, not a folder" in refused("app", "--no-browser", "--port", str(free), "--out", str(f))


def test_a_coupled_limit_names_the_parameter_the_user_changed():
    """Concept 4's beam-end rule is on flexure_length but a thicker flexure breaks it: the
    refusal names the thickness (and the other inputs of the limit) with their values."""
    import clutchfem as cf

    with pytest.raises(cf.ParameterError) as e:
        cf.Design.from_concept("concept4", flexure_thickness="2.4mm")
    msg = str(e.value)
    assert e.value.name == "flexure_length" and "flexure_thickness 2.4 mm" in msg
    assert "hub_radius 12 mm" in msg and "flexure_angle 30 deg" in msg and "<= 18.50 mm" in msg


# -- lost data: the mesh cache deletes only what it wrote ------------------------------------
ENTRY = "concept4-0123456789abcdef01234567"


def _cache_with(root, *names):
    d = root / "meshes"
    d.mkdir(parents=True)
    for n in names:
        (d / n).write_text("x" * 100)
    return d


def test_a_cache_folder_holding_files_it_did_not_write_is_refused_and_left_whole(tmp_path):
    d = _cache_with(tmp_path, f"{ENTRY}.msh", f"{ENTRY}.json", "my part.msh", "notes.txt")
    err = refused("cache", "--clear", env={"CLUTCHFEM_CACHE": str(tmp_path)})
    assert "2 file(s) the mesh cache did not write" in err and "my part.msh" in err and "CLUTCHFEM_CACHE" in err
    assert sorted(p.name for p in d.iterdir()) == sorted([f"{ENTRY}.msh", f"{ENTRY}.json", "my part.msh", "notes.txt"])


def test_clear_and_eviction_delete_the_cache_entries_only(tmp_path):
    import os
    import time

    import clutchfem as cf
    from clutchfem.mesh.cache import evict

    d = _cache_with(tmp_path, f"{ENTRY}.msh", f"{ENTRY}.json", f"{ENTRY}.groups.msh")
    with mock_env(CLUTCHFEM_CACHE=str(tmp_path)):
        assert cf.cache_dir() == d  # a folder of entries only: the cache's (its marker written)
    (d / "mine.msh").write_text("y" * 10_000)  # the user's file, put there afterwards
    old = time.time() - 3600
    for p in d.iterdir():
        os.utime(p, (old, old))
    assert evict(limit=50, d=d) == (1, 300)  # over the bound: the entry goes, the user's larger file stays
    assert (d / "mine.msh").read_text() == "y" * 10_000
    (d / f"{ENTRY}.json").write_text("{}")
    r = cli_in_process("cache", "--clear", env={"CLUTCHFEM_CACHE": str(tmp_path)}, ok=True)
    assert "deleted 1 cached meshes" in r.stderr and "kept 1 file(s)" in r.stderr and (d / "mine.msh").exists()


def mock_env(**env):
    from unittest import mock

    return mock.patch.dict("os.environ", env)


# -- options silently dropped or recorded wrong ---------------------------------------------
def test_kerf_error_without_as_cut_is_refused_not_dropped():
    err = refused("export", "concept4", "--process", "laser", "--kerf-error", "0.02mm", "--dxf", "x.dxf")
    assert "option --kerf-error 0.02mm applies to --as-cut" in err


def test_a_kerf_error_as_wide_as_the_kerf_is_refused_before_any_work():
    err = refused("export", "concept4", "--process", "wire-edm", "--as-cut", "--kerf-error", "0.9mm", "--dxf", "x.dxf")
    assert "option --kerf-error" in err and "0.9 mm" in err and "below the kerf 0.33 mm of wire-edm" in err


def test_a_web_limit_given_replaces_the_process_rule_thickness_included():
    import clutchfem as cf

    laser = cf.ProcessRules.of("laser")
    assert laser.limits(0.011)["min_web"] > 5e-3  # the laser's own rule: 0.7 x the plate thickness
    assert cf.ProcessRules.of("laser", min_web="0.5mm").limits(0.011)["min_web"] == 0.5e-3
    assert cf.ProcessRules.of("laser", min_slot="1mm").limits(0.011)["min_slot"] == 1e-3


@pytest.mark.slow  # (meshes the design)
def test_a_tolerance_wider_than_the_parameter_range_is_refused_before_the_search():
    err = refused("optimize", "concept4", "--tol", "flexure_thickness=+-5mm", "--fidelity", "fast", "--mesh-size",
                  "6mm")
    assert "option --tol" in err and "+-5 mm" in err and "half the parameter's range [0.5 mm, 4 mm]" in err


# -- tracebacks ------------------------------------------------------------------------------
@pytest.mark.slow  # (meshes the design)
def test_every_output_is_checked_before_any_is_written(tmp_path):
    err = refused("export", "concept4", "--fidelity", "fast", "--mesh-size", "6mm", "--no-analysis",
                  "--dxf", str(tmp_path / "part.dxf"), "--step", "/proc/clutchfem-part.step")
    assert "--step /proc/clutchfem-part.step: cannot be written" in err and "nothing was written" in err
    assert list(tmp_path.iterdir()) == []


def test_export_from_a_record_that_is_not_an_object_is_refused(tmp_path):
    (tmp_path / "inputs.json").write_text("[]")
    err = refused("export", "--from", str(tmp_path), "--dxf", str(tmp_path / "x.dxf"))
    assert "not a run's record" in err and "JSON list" in err


def test_a_concept_that_is_not_a_name_is_refused_naming_the_argument():
    import clutchfem as cf

    with pytest.raises(cf.ParameterError) as e:
        cf.Design.from_concept(4)
    assert e.value.name == "concept" and "'4' or 'concept4'" in str(e.value)
    c = cf.get_concept("concept4")  # the concept object itself is a concept
    assert cf.Design.from_concept(c, fidelity="live").concept is c


@pytest.mark.slow  # (meshes the design)
def test_geometry_without_out_writes_into_its_documented_folder(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cli_in_process("geometry", "concept1", "--no-drawing", "--mesh-size", "6mm", ok=True)
    assert sorted(p.suffix for p in (tmp_path / "out" / "geometry").iterdir()) == [".json", ".msh"]


# -- refusals that mislead -------------------------------------------------------------------
def test_the_typographic_minus_is_a_minus_and_a_decimal_comma_is_said_as_such():
    import clutchfem as cf

    P = cf.get_concept("concept4").Params
    assert P.parse_value("eccentric_angle", "\u221230deg") == -30.0
    with pytest.raises(cf.ParameterError) as e:
        P.parse_value("flexure_thickness", "2,4mm")
    assert "a number with a decimal point, not a decimal comma (2.4mm)" in str(e.value)
    assert "decimal comma (2.4mm)" in refused("geometry", "concept4", "--set", "flexure_thickness=2,4mm")


@pytest.mark.parametrize("row, said", [("10,000,3.0", "'10,000' reads as a number with thousands separators (10000)"),
                                       ('"10,000",3.0', "'10,000' is a number with thousands separators (10000)"),
                                       ("1e7,3.0", "row 4: speed 1e+07 rpm is above 60,000 rpm")])
def test_an_engine_row_with_thousands_separators_or_a_typo_speed_is_named(tmp_path, row, said):
    import clutchfem as cf

    f = tmp_path / "engine.csv"
    f.write_text(f"rpm,torque_Nm\n3000,2.0\n6000,3.5\n{row}\n")
    with pytest.raises(cf.InputError) as e:
        cf.EngineCurve.from_csv(f)
    assert said in str(e.value) and "decimal commas" not in str(e.value)
    f.write_text("rpm,torque_Nm\n3000,2.0\n6000,1,90\n")  # a torque split at its decimal comma stays said so
    with pytest.raises(cf.InputError, match="decimal commas with ',' as the separator"):
        cf.EngineCurve.from_csv(f)
