"""The live design app in a real headless browser (Debian's Chromium, driven by Playwright):
open the page, move the flexure thickness, the engagement speed shown becomes the one
``cf.analyze`` gives for that design; a value out of range shows its refusal at the
parameter and the last valid design stays; pin and compare; a screenshot is kept as a test
artefact (``test-artifacts/app.png``).  And the session logic without a browser."""

from __future__ import annotations

import os
import shutil
import socket
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import pytest

import clutchfem as cf
from clutchfem.app import DesignSession

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
ARTIFACTS = ROOT / "test-artifacts"


def test_session_refuses_at_the_parameter_and_keeps_the_last_design():
    s = DesignSession("concept1")
    assert {c.name for c in s.controls()} >= {"flexure_thickness", "mu", "drum_wall"}
    assert not any(c.name.startswith("table_c") for c in s.controls())  # inactive profile controls hidden
    msg = s.set_value("flexure_thickness", 9.0)  # mm, out of range
    assert msg and "flexure_thickness" in msg and "9 mm" in msg and "6 mm" in msg
    assert s.params.flexure_thickness == pytest.approx(2.2e-3)  # unchanged
    assert s.set_value("flexure_thickness", 2.4) is None and s.params.flexure_thickness == pytest.approx(2.4e-3)
    assert s.set_value("drum_wall", 2.0) is None and s.op.drum_wall == pytest.approx(2e-3)
    assert s.set_value("drum_wall", 0.0) is None and s.op.drum_wall is None


def _free_port() -> int:
    with socket.socket() as so:
        so.bind(("127.0.0.1", 0))
        return so.getsockname()[1]


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    port = _free_port()
    out = tmp_path_factory.mktemp("app")
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTEST")}  # NiceGUI's own test mode keys on it
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")])
    proc = subprocess.Popen([sys.executable, "-m", "clutchfem.cli", "app", "--port", str(port), "--no-browser",
                             "--out", str(out)], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    t0 = time.time()
    while time.time() - t0 < 60 and proc.poll() is None:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1).close()
            break
        except OSError:
            time.sleep(0.3)
    else:
        proc.kill()
        pytest.fail("the app did not start: " + proc.stdout.read().decode()[-2000:])
    yield f"http://127.0.0.1:{port}/"
    proc.terminate()
    proc.wait(timeout=20)


def _engagement(page) -> str:
    row = page.locator("[data-testid=answers] tr", has_text="engagement speed (static)")
    return row.locator("td").nth(1).inner_text().split(" +-")[0].strip()


def test_live_design_in_a_real_browser(server):
    from playwright.sync_api import expect, sync_playwright

    assert Path(CHROMIUM).exists(), "Debian's chromium is installed by make setup (APT_PKGS)"
    want = cf.analyze(cf.Design.from_concept("concept4", flexure_thickness="2mm"), errors=False)
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=[
            "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
            "--disable-sync", "--no-first-run"])
        page = browser.new_page(viewport={"width": 1500, "height": 1300})
        page.goto(server)
        status = page.locator("[data-testid=status]")
        expect(status).to_contain_text("answers in", timeout=90_000)
        before = _engagement(page)
        # move the flexure thickness: the engagement shown becomes cf.analyze's
        box = page.locator("input[data-testid=num-flexure_thickness]")
        box.fill("2")
        box.press("Enter")
        expect(page.locator("[data-testid=answers] tr", has_text="engagement speed (static)")).to_contain_text(
            f"{want.engagement_rpm:.0f} rpm", timeout=60_000)
        assert _engagement(page) != before
        # out of range: the refusal at the parameter, the last valid design stays
        box.fill("9")
        box.press("Enter")
        expect(page.locator("[data-testid=msg-flexure_thickness]")).to_contain_text("[0.5 mm, 4 mm]", timeout=20_000)
        assert _engagement(page) == f"{want.engagement_rpm:.0f} rpm"
        # pin and compare: a pinned column with the difference
        expect(status).to_contain_text("with error bands", timeout=60_000)
        page.locator("[data-testid=pin]").click()
        other = cf.analyze(cf.Design.from_concept("concept4", flexure_thickness="1.9mm"), errors=False)
        box.fill("1.9")
        box.press("Enter")
        expect(page.locator("[data-testid=answers] th", has_text="pinned")).to_be_visible(timeout=60_000)
        row = page.locator("[data-testid=answers] tr", has_text="engagement speed (static)")
        diff = round(other.engagement_rpm) - round(want.engagement_rpm)  # of the values shown
        expect(row).to_contain_text(f"{other.engagement_rpm:.0f} rpm", timeout=60_000)
        expect(row).to_contain_text(f"{want.engagement_rpm:.0f} rpm")  # the pinned design beside it
        expect(row).to_contain_text(f"{diff:+.4g} rpm")
        # the cutting files of the design on screen: DXF, STEP and drawing in one zip
        page.locator("[data-testid=files]").click()
        with page.expect_download(timeout=120_000) as dl:
            page.get_by_text("cutting files").click()
        with zipfile.ZipFile(dl.value.path()) as z:
            names = z.namelist()
        assert {Path(n).suffix for n in names} >= {".dxf", ".step", ".pdf"}, names
        assert all(n.startswith("concept4") or n.endswith(".json") for n in names), names
        ARTIFACTS.mkdir(exist_ok=True)
        page.screenshot(path=str(ARTIFACTS / "app.png"), full_page=True)
        browser.close()
    assert (ARTIFACTS / "app.png").stat().st_size > 50_000
