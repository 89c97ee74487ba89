"""Hostile inputs, round 4 (issue 37) and the options of this round's features: each class
answered by a refusal that names the option, its value and what is allowed, before any work."""

from __future__ import annotations

import socket

import pytest

from clutchfem.studies import load_study
from support.cli import cli_in_process


def refused(*args) -> str:
    r = cli_in_process(*args)
    assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
    return r.stderr


@pytest.mark.parametrize("opt", [("--yield", "1.5"), ("--rounds", "11"), ("--no-model-error",), ("--check", "20"),
                                 ("--dist", "uniform")])
def test_robust_design_options_without_tolerances_are_refused_not_dropped(opt):
    err = refused("optimize", "concept4", *opt)
    assert f"option {opt[0]}" in err and "--tol" in err


@pytest.mark.parametrize("cmd", [("optimize", "concept4"), ("solve", "concept4"), ("compensate", "concept4", "--rpm",
                                                                                  "8000"),
                                 ("guidelines", "concept4"), ("slip-heat", "concept4")])
def test_live_fidelity_is_refused_by_the_commands_that_need_the_fe(cmd):
    err = refused(*cmd, "--fidelity", "live")
    assert "--fidelity" in err and "analyze and tolerance" in err


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
