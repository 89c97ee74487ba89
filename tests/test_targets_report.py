"""The one-page report: structure of the self-contained HTML and of its Markdown twin."""

import json
import re

import pytest

from support.cli import cli_in_process


@pytest.fixture(scope="module")
def write_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    # in this process (support/cli.py), as the tests below: the files are the point, not the process
    cli_in_process("report", "concept4", "--set", "flexure_thickness=1.8mm", "--mesh-size", "2.4mm",
                   "--no-errors", "--out", str(out), ok=True)
    return out


@pytest.mark.slow
def test_html_is_self_contained_with_answers_units_images_inputs(write_report):
    html = (write_report / "report.html").read_text()
    assert html.startswith("<!DOCTYPE html>")
    assert not re.search(r"""<(img|script|link)[^>]+(src|href)=['"](?!data:)""", html)  # nothing external
    assert html.count("data:image/png;base64,") >= 3  # torque chart, arc/stress chart, drawing
    for answer in ("engagement speed", "slip speed", "safety factor", "part mass", "max von Mises"):
        assert answer in html
    assert re.search(r"\d rpm", html) and re.search(r"\d MPa", html) and re.search(r"\d N m", html)
    assert "PASS" in html or "FAIL" in html
    assert "Young&#x27;s modulus" in html or "Young's modulus" in html
    assert "flexure_thickness" in html and "1.8 mm" in html
    inputs = json.loads((write_report / "inputs.json").read_text())
    assert inputs["params"]["flexure_thickness"] == pytest.approx(1.8e-3)
    assert inputs["concept"] == "concept4" and "mesh_settings" in inputs and "operating_point" in inputs


@pytest.mark.slow
def test_markdown_has_the_same_answers(write_report):
    md = (write_report / "report.md").read_text()
    html = (write_report / "report.html").read_text()
    rows = re.findall(r"^\| ([^|]+) \| ([^|]+) \|$", md, flags=re.M)
    answers = [(q.strip(), v.strip()) for q, v in rows if q.strip() not in ("answer", "---")]
    assert len(answers) >= 10
    import html as h

    for q, v in answers[:12]:
        assert h.escape(q) in html and h.escape(v) in html
    for img in re.findall(r"!\[[^]]*\]\(([^)]+)\)", md):
        assert (write_report / img).exists()


@pytest.mark.slow
def test_run_folder_renders_again(write_report, tmp_path):
    import pandas as pd

    pd.DataFrame({"rpm": [1000, 2000], "torque_Nm": [0.0, 1.5]}).to_csv(tmp_path / "sweep.csv", index=False)
    (tmp_path / "torque.png").write_bytes((write_report / "torque_rpm.png").read_bytes())
    cli_in_process("report", "--run", str(tmp_path), ok=True)
    html = (tmp_path / "report.html").read_text()
    assert "sweep.csv" in html and "data:image/png;base64," in html and "torque_Nm" in html
    out = tmp_path / "again"
    cli_in_process("report", "--run", str(write_report), "--out", str(out), ok=True)
    assert "engagement speed" in (out / "report.html").read_text()


def test_report_refuses_unclear_requests(tmp_path):
    run = cli_in_process  # in this process (support/cli.py): the refusals are the point
    r = run("report", "concept4")
    assert r.returncode == 2 and "--out" in r.stderr
    r = run("report", "concept4", "--run", str(tmp_path))
    assert r.returncode == 2 and "exactly one" in r.stderr


@pytest.mark.slow
def test_report_of_a_user_mesh(tmp_path):
    """`report --mesh`: the mesh picture instead of the drawing, the mesh file and its SHA-256 in
    the inputs."""
    cli_in_process("geometry", "concept4", "--out", str(tmp_path / "geo"), "--model", "full", "--mesh-size", "2.4mm",
                   "--no-drawing", ok=True)
    out = tmp_path / "rep"
    cli_in_process("report", "--mesh", str(next((tmp_path / "geo").glob("concept4-*.msh"))), "--drum-radius", "34.4mm",
                   "--thickness", "11mm", "--no-errors", "--out", str(out), ok=True)
    html = (out / "report.html").read_text()
    assert "the user mesh" in html and html.count("data:image/png;base64,") >= 3
    inputs = json.loads((out / "inputs.json").read_text())
    assert inputs["mesh_sha256"] and inputs["mesh_file"].endswith(".msh")
