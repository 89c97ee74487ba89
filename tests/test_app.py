"""The live design app in a real headless browser (Debian's Chromium, driven by Playwright):
open the page, move the flexure thickness, the engagement speed shown becomes the one
``cf.analyze`` gives for that design; a value out of range shows its refusal at the
parameter and the last valid design stays; pin and compare; a screenshot is kept as a test
artefact (``test-artifacts/app.png``).  And the session logic without a browser."""

from __future__ import annotations

import contextlib
import re
import zipfile
from pathlib import Path
from types import SimpleNamespace

import pytest

import clutchfem as cf
from clutchfem.app import DesignSession
from support.browser import CHROMIUM, ROOT, app_server, launch_chromium

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
    assert s.set_value("drum_wall", 0.0) is None and s.op.drum_wall == 0.0 and s.op.drum_wall_m is None  # rigid


@pytest.mark.slow
def test_session_fidelity_control_and_the_drum_it_shows(monkeypatch):
    """The app's model control: the shipped default (best) shows its 2 mm drum (not 0, which
    reads as rigid), and switching to fast gives the rigid drum and the fast mesh."""
    monkeypatch.delenv("CLUTCHFEM_FIDELITY", raising=False)
    s = DesignSession("concept4")
    shown = {c.name: c.value for c in s.controls()}
    assert shown["fidelity"] == "best" and shown["drum_wall"] == pytest.approx(2.0)
    assert s.set_value("fidelity", "fast") is None
    shown = {c.name: c.value for c in s.controls()}
    assert shown["drum_wall"] == 0.0 and s.design().op.model_formulation == "plane-stress"
    assert s.design().cm.mesh_settings == cf.MeshSettings.preset("fast").model_dump()
    assert "fidelity" in (s.set_value("fidelity", "medium") or "") and s.op.fidelity == "fast"


@pytest.fixture(scope="module")
def c4_19():
    """Concept 4 at 1.9 mm on the fast path and ``cf.analyze``'s answers for it, computed
    once for the module's tests that compare a page with them."""
    d = cf.Design.from_concept("concept4", flexure_thickness="1.9mm", fidelity="fast")
    return d, cf.analyze(d)


@pytest.mark.slow
def test_session_ends_on_the_answers_of_analyze(monkeypatch, c4_19):
    """One answer set (issue 37): the first pass is marked on its values, and the page ends on
    exactly the answers ``cf.analyze`` gives for the design (corrected, with bands), every main
    answer to the digits shown; a report downloaded meanwhile is of those answers."""
    monkeypatch.setenv("CLUTCHFEM_FIDELITY", "fast")
    s = DesignSession("concept4")
    assert s.set_value("flexure_thickness", 1.9) is None
    first = s.run()
    shown = dict((q, v) for q, v, _ in first.rows)
    assert shown["engagement speed (static)"].endswith("(first pass)")
    done = s.complete(first)
    assert s.last is done and done.analysis.errors
    design, want = c4_19
    assert s.design().hash == design.hash  # the session's design is the one analysed
    from clutchfem.app.session import answer_rows

    assert done.rows == answer_rows(want)
    assert not any("first pass" in v for _, v, _ in done.rows)
    assert any(" +- " in v and "MPa" in v for _, v, _ in done.rows)


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """One app server for the browser tests that need a server as it starts (each opens its
    own tab: a tab's session is its own); the tests about the server's own state (its pages
    and memory, its tab limit) start theirs.  Yields the URL and the server's --out folder."""
    out = tmp_path_factory.mktemp("app")
    try:
        with app_server(out) as url:
            yield SimpleNamespace(url=url, out=out)
    except RuntimeError as e:
        pytest.fail(str(e))


@pytest.fixture(scope="module")
def chromium():
    """One headless Chromium for the module's browser tests (a launch is ~1 s of CPU); each
    test opens its pages in a context of its own and closes it."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = launch_chromium(p)
        yield browser
        browser.close()


def _engagement(page) -> str:
    row = page.locator("[data-testid=answers] tr", has_text="engagement speed (static)")
    return row.locator("td").nth(1).inner_text().split(" +-")[0].strip()


@pytest.mark.slow
def test_live_design_in_a_real_browser(server, chromium, c4_19):
    from playwright.sync_api import expect

    assert Path(CHROMIUM).exists(), "Debian's chromium is installed by make setup (APT_PKGS)"
    want = cf.analyze(cf.Design.from_concept("concept4", flexure_thickness="2mm"))  # the answers of record
    with _context(chromium, viewport={"width": 1500, "height": 1300}) as browser:
        page = browser.new_page()
        page.goto(server.url)
        status = page.locator("[data-testid=status]")
        expect(status).to_contain_text("first pass in", timeout=90_000)
        before = _engagement(page)
        # move the flexure thickness: the engagement shown becomes cf.analyze's
        box = page.locator("input[data-testid=num-flexure_thickness]")
        box.fill("2")
        box.press("Enter")
        expect(status).to_contain_text("the answers of analyze, with error bands", timeout=90_000)
        expect(page.locator("[data-testid=answers] tr", has_text="engagement speed (static)")).to_contain_text(
            f"{want.engagement_rpm:.0f} rpm +- ", timeout=60_000)
        expect(page.locator("[data-testid=answers] tr", has_text="peak von Mises")).to_contain_text(
            f"{want.max_von_mises_Pa / 1e6:.0f} MPa +- ")
        assert _engagement(page) != before
        # the slider spans what the concept's rules allow with the others as they are
        P = cf.get_concept("concept4").Params
        lo, hi = P.feasible_range(P(flexure_thickness="2mm").model_dump(), "flexure_thickness")
        expect(page.locator("[data-testid=range-flexure_thickness]")).to_contain_text(
            f"with the others now {lo * 1e3:.4g}..{hi * 1e3:.4g} mm", timeout=30_000)
        # out of range: the refusal at the parameter, the last valid design stays, greyed and said
        box.fill("9")
        box.press("Enter")
        expect(page.locator("[data-testid=msg-flexure_thickness]")).to_contain_text("[0.5 mm, 4 mm]", timeout=20_000)
        assert _engagement(page) == f"{want.engagement_rpm:.0f} rpm"
        expect(status).to_contain_text("answers of the last valid design (greyed); flexure_thickness = 9 mm refused")
        expect(page.locator("[data-testid=answers]")).to_have_class(re.compile("opacity-50"))
        # pin and compare: a pinned column with the difference
        page.locator("[data-testid=pin]").click()
        d19 = cf.Design.from_concept("concept4", flexure_thickness="1.9mm")  # the session's fidelity
        other = c4_19[1] if d19.hash == c4_19[0].hash else cf.analyze(d19)
        box.fill("1.9")
        box.press("Enter")
        expect(page.locator("[data-testid=answers] th", has_text="pinned")).to_be_visible(timeout=60_000)
        row = page.locator("[data-testid=answers] tr", has_text="engagement speed (static)")
        diff = round(other.engagement_rpm) - round(want.engagement_rpm)  # of the values shown
        expect(row).to_contain_text(f"{other.engagement_rpm:.0f} rpm +- ", timeout=90_000)
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
        # the model control: best gives the thick model's answer and shows its 2 mm drum wall
        best = cf.analyze(cf.Design.from_concept("concept4", flexure_thickness="1.9mm", fidelity="best"),
                          errors=False)
        page.locator("[data-testid=choice-fidelity]").click()
        page.get_by_role("option", name="best").click()
        expect(row).to_contain_text(f"{best.engagement_rpm:.0f} rpm (first pass)", timeout=90_000)
        expect(page.locator("input[data-testid=num-drum_wall]")).to_have_value("2")
        ARTIFACTS.mkdir(exist_ok=True)
        page.screenshot(path=str(ARTIFACTS / "app.png"), full_page=True)
    assert (ARTIFACTS / "app.png").stat().st_size > 50_000


@contextlib.contextmanager
def _context(chromium, **kw):
    """A browser context of the shared Chromium (its own pages, cookies and downloads),
    closed after: its tabs go away as a closed browser's do."""
    ctx = chromium.new_context(**kw)
    try:
        yield ctx
    finally:
        ctx.close()


def _rss_mb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmRSS:"):
            return int(line.split()[1]) / 1024
    raise AssertionError("no VmRSS")


#: what 200 page requests without a browser may add to the server's memory [MB] (docs/app.md:
#: at most MAX_PENDING = 32 pages wait for their browser, each ~1 MB of widgets, no session)
UNCONNECTED_BOUND_MB = 64


@pytest.mark.slow
def test_the_app_as_a_server_without_a_browser(tmp_path, monkeypatch):
    """200 plain page requests (/ and random paths) start no session and no analysis: no tab
    folder, no mesh written, memory under the stated bound; at most MAX_PENDING pages wait
    for their browser (a further request gets a 503); other paths are a plain 404; an
    upload larger than its limit is refused by the server (413) before it is read, declared
    or chunked, and a small one to a page that never connected writes nothing."""
    import random

    import httpx

    from clutchfem.app.limits import MAX_CSV_BYTES, MAX_PART_BYTES, MAX_PENDING

    out, cache = tmp_path / "app", tmp_path / "cache"
    monkeypatch.setenv("CLUTCHFEM_CACHE", str(cache))  # the server's mesh cache: an analysis would write there
    with app_server(out) as url, httpx.Client(base_url=url, timeout=30) as http:
        pid = int(next(p.name for p in Path("/proc").iterdir() if p.name.isdigit()
                       and (p / "cmdline").exists() and str(out).encode() in (p / "cmdline").read_bytes()))
        before = _rss_mb(pid)
        rng = random.Random(37)
        html, codes = "", {}
        for i in range(200):
            if i % 2:
                r = http.get(f"/{''.join(rng.choices('abcxyz/', k=8)).strip('/') or 'x'}")
                assert r.status_code == 404 and "no page of this app" in r.text, (r.status_code, r.text[:200])
            else:
                r = http.get("/")
                codes[r.status_code] = codes.get(r.status_code, 0) + 1
                if r.status_code == 200:
                    html = html or r.text
                else:  # more pages wait for their browser than the server holds: refused, nothing built
                    assert r.status_code == 503 and "waiting for their browser" in r.text, (r.status_code, r.text)
        after = _rss_mb(pid)
        assert codes == {200: MAX_PENDING, 503: 100 - MAX_PENDING}, codes
        uploads = sorted(set(re.findall(r"/_nicegui/client/[0-9a-f-]+/upload/\d+", html)),
                         key=lambda u: int(u.rsplit("/", 1)[1]))  # the engine CSV's comes first
        assert len(uploads) == 2, uploads  # the engine CSV's and the part's
        csv_url, part_url = uploads
        big = b"rpm,torque\n" + b"5000,10\n" * (5 * (1 << 20) // 8)  # 5 MB
        r = http.post(csv_url, files={"file": ("engine.csv", big, "text/csv")})
        assert r.status_code == 413 and f"{MAX_CSV_BYTES / 1024:.0f} kB" in r.text
        r = http.post(part_url, files={"file": ("part.msh", b"x" * (MAX_PART_BYTES + (64 << 10)), "text/plain")})
        assert r.status_code == 413 and f"{MAX_PART_BYTES / 1024:.0f} kB" in r.text

        def chunks():  # a well-formed multipart body without a declared length: counted as it arrives
            yield b'--xx\r\nContent-Disposition: form-data; name="file"; filename="e.csv"\r\n\r\nrpm,torque\n'
            for _ in range(40):
                yield b"5000,10\n" * 16384
            yield b"\r\n--xx--\r\n"

        r = http.post(csv_url, content=chunks(), headers={"content-type": "multipart/form-data; boundary=xx"})
        assert r.status_code == 413
        r = http.post(csv_url, files={"file": ("engine.csv", b"rpm,torque\n3000,5\n9000,10\n", "text/csv")})
        assert r.status_code == 200
        r = http.post("/_nicegui/client/nobody/upload/1", files={"file": ("a.csv", b"1,2\n", "text/csv")})
        assert r.status_code == 404
    written = [p for p in out.rglob("*") if p.name != "app.log"]
    assert written == [], written  # no tab folder, no mesh, no upload written
    assert [p for p in cache.rglob("*") if p.is_file()] == []  # no design meshed
    assert "Traceback" not in (out / "app.log").read_text()
    print(f"server RSS: {before:.0f} MB before, {after:.0f} MB after 200 page requests")
    assert after - before < UNCONNECTED_BOUND_MB, (before, after)


@pytest.mark.slow
def test_a_tab_is_live_only_while_its_page_is_open_and_tabs_are_bounded(tmp_path, chromium):
    """A page in a browser gets its folder and its analysis; over --max-tabs a further tab
    gets the refusal page and no folder; a closed tab's folder is dropped (its session
    reclaimed) and its place taken by the next tab."""
    import time

    from playwright.sync_api import expect

    LIVE = re.compile("computing|first pass|answers of analyze")  # the tab analyses
    out = tmp_path / "app"
    tabs = lambda: sorted(p for p in out.glob("tab-*"))  # noqa: E731
    with app_server(out, args=("--max-tabs", "1")) as url, _context(chromium) as browser:
        first = browser.new_page()
        first.goto(url)
        expect(first.locator("[data-testid=status]")).to_have_text(LIVE, timeout=60_000)
        assert len(tabs()) == 1
        expect(first.locator("[data-testid=status]")).to_contain_text("with error bands", timeout=120_000)
        pid = int(next(p.name for p in Path("/proc").iterdir() if p.name.isdigit()
                       and (p / "cmdline").exists() and str(out).encode() in (p / "cmdline").read_bytes()))
        print(f"server RSS with one tab analysed: {_rss_mb(pid):.0f} MB")
        second = browser.new_page()
        second.goto(url)
        expect(second.locator("[data-testid=refused]")).to_contain_text("1 tabs of this app are open already")
        assert len(tabs()) == 1
        first.close()
        t0 = time.time()
        while tabs() and time.time() - t0 < 20:  # the reconnect grace (3 s), then the tab is reclaimed
            time.sleep(0.25)
        assert tabs() == [], "a closed tab's folder is dropped"
        second.reload()
        expect(second.locator("[data-testid=status]")).to_have_text(LIVE, timeout=60_000)
        assert len(tabs()) == 1
    log = (out / "app.log").read_text()
    assert "Traceback" not in log and "deleted but is still being used" not in log, log[-2000:]


def _optimum(feasible: bool, values: dict, searched: dict | None = None, ratios: dict | None = None,
             texts: dict | None = None):
    from clutchfem.targets import OptimizationResult

    t = cf.Targets(3510.0, None, 8000.0, 1.5)
    row = {"status": "ok", "mass_kg": 0.05, "torque_margin_Nm": 1.0, **values}
    best = {"params": {}, "mass_kg": 0.05, "assessment": t.assess(row)}
    r = OptimizationResult("concept4", t, ["flexure_thickness"], {"flexure_thickness": "2mm"}, best, feasible,
                           texts or {}, [], [], {"ok": 12, "refused": 1}, 30.0, 4, "poll 8: incumbent ...")
    r.best_estimate = {"targets_searched": {**{"engage_rpm_lo": 3510.0, "engage_rpm_hi": None,
                                               "slip_rpm_max": 8000.0, "safety_factor_min": 1.5,
                                               "fatigue_min": None}, **(searched or {})},
                       "ratios": ratios or {}}
    return r


def test_the_optimum_in_the_designers_words():
    """The optimiser's result as the page states its targets: met or missed by how much, the
    shifted target it searched said with its reason, and apply only for a design that meets
    every target (analyze's answers)."""
    from clutchfem.app.studies_panel import optimum_summary

    ok = _optimum(True, {"engagement_rpm_with_ripple": 3620.0, "slip_rpm": 7600.0, "safety_factor": 1.52},
                  searched={"safety_factor_min": 1.54}, ratios={"safety_factor": 0.974},
                  texts={"flexure_thickness": "1.85mm"})
    lines, can_apply = optimum_summary(ok)
    text = "\n".join(lines)
    assert can_apply and lines[0].startswith("A design meets every target (3)")
    assert "engagement with 2-stroke ripple >= 3510 rpm: met with 110 rpm to spare (3620 rpm)" in text
    assert "slip speed <= 8000 rpm: met with 400 rpm to spare (7600 rpm)" in text
    assert "safety factor (yield) at the engine's top speed >= 1.50: met with 0.02 to spare (1.52)" in text
    assert "aimed at safety factor (yield) at the engine's top speed >= 1.54, not 1.50" in text
    assert "-2.6 %" in text and "flexure_thickness 2mm -> 1.85mm" in text
    assert "poll" not in text and "incumbent" not in text and "h = " not in text  # no search jargon
    # no design meets the targets: what is missed and by how much, and nothing to apply
    bad = _optimum(False, {"engagement_rpm_with_ripple": 3400.0, "slip_rpm": 7600.0, "safety_factor": 1.2},
                   texts={"flexure_thickness": "1.6mm"})
    lines, can_apply = optimum_summary(bad)
    text = "\n".join(lines)
    assert not can_apply and "misses 2 of 3" in lines[0] and "nothing to apply" in lines[0]
    assert "engagement with 2-stroke ripple >= 3510 rpm: MISSED by 110 rpm (3400 rpm)" in text
    assert "safety factor (yield) at the engine's top speed >= 1.50: MISSED by 0.30 (1.20)" in text
    assert "aimed at" not in text  # it searched the page's own targets
    # the search met its targets but analyze's answers miss one: not offered either
    unconfirmed = _optimum(False, {"engagement_rpm_with_ripple": 3620.0, "slip_rpm": 8100.0, "safety_factor": 1.6},
                           texts={"flexure_thickness": "1.7mm"})
    lines, can_apply = optimum_summary(unconfirmed)
    assert not can_apply and "slip speed <= 8000 rpm: MISSED by 100 rpm (8100 rpm)" in lines
    # a slip that never comes: said in words
    never = _optimum(False, {"engagement_rpm_with_ripple": 3620.0, "slip_rpm": None, "safety_factor": 1.6})
    assert any("never slips to a hold" in x for x in optimum_summary(never)[0])


def test_study_progress_and_time_left():
    from clutchfem.app.studies_panel import StudyProgress

    p = StudyProgress(33, 1.0)  # by time: 33 designs of ~1 s
    p.t0 -= 11.0
    assert p.share() == pytest.approx(11 / 33, rel=1e-3) and p.left_text() == "about 22 s left"
    p.t0 -= 100.0  # longer than foreseen: never done before it ends
    assert p.share() == 0.99 and p.left_text() == "finishing"
    q = StudyProgress(40, 5.0)  # the study's own count wins
    q.t0 -= 60.0
    q.saw("sample of 8: best: feasible, mass 51.20 g [10 of at most 40 evaluations, 60 s, at most ~180 s left]")
    assert q.share() == pytest.approx(0.25) and q.left_text() == "about 3 min left"
    q.saw("no count here")
    assert q.share() == pytest.approx(0.25)


def test_upload_limit_refuses_before_the_body_is_read():
    """The middleware alone (no server): over the limit on the declared length or on the
    bytes as they arrive -> 413 and the route never reads the body; an unknown upload route
    -> 404; within the limit the route gets every byte."""
    import asyncio
    import concurrent.futures

    import httpx
    from starlette.applications import Starlette
    from starlette.responses import PlainTextResponse
    from starlette.routing import Route

    from clutchfem.app.limits import UploadLimit, upload_limits

    got = []

    async def route(request):
        got.append(len(await request.body()))
        return PlainTextResponse("ok")

    url = "/_nicegui/client/abc/upload/7"
    app = UploadLimit(Starlette(routes=[Route(url, route, methods=["POST"])]))
    upload_limits[url] = 1000

    async def go():
        async with httpx.AsyncClient(transport=httpx.ASGITransport(app=app), base_url="http://t") as c:
            big = await c.post(url, content=b"x" * 40_000)

            async def chunks():
                for _ in range(10):
                    yield b"x" * 4096

            chunked = await c.post(url, content=chunks())
            small = await c.post(url, content=b"x" * 900)
            unknown = await c.post("/_nicegui/client/abc/upload/8", content=b"x")
        return big, chunked, small, unknown

    try:  # in a thread of its own: the module's browser (Playwright's sync API) may hold this thread's loop
        with concurrent.futures.ThreadPoolExecutor(1) as pool:
            big, chunked, small, unknown = pool.submit(asyncio.run, go()).result()
    finally:
        upload_limits.pop(url, None)
    assert big.status_code == 413 and "1 kB" in big.text
    assert chunked.status_code == 413
    assert small.status_code == 200 and unknown.status_code == 404
    assert got == [900]  # the refused bodies never reached the route


@pytest.mark.slow
def test_a_cancelled_optimisation_stops_at_its_next_step():
    """The app's cancel: the optimiser's log is its cancellation point; a cancel raised there
    ends the search (no further design evaluated) instead of being taken for a bad design."""
    from clutchfem.app.studies_panel import StudyCancelled, StudyProgress

    d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="3mm"), fidelity="fast")
    prog, seen = StudyProgress(40, 1.0), []

    def log(m: str) -> None:  # as the page's: cancelled after the first step
        seen.append(m)
        prog.saw(m)
        prog.cancelled = True
        raise StudyCancelled("optimisation: cancelled")

    with pytest.raises(StudyCancelled):
        cf.optimize(d, free=["flexure_thickness"], sample=4, max_evals=12, workers=0, check=False,
                    method="pattern", log=log)
    assert len(seen) == 1 and "[1 of at most 12 evaluations" in seen[0], seen
    assert prog.share() == pytest.approx(1 / 12)


@pytest.mark.slow
def test_a_study_in_the_browser_shows_its_time_left_and_cancels(server, chromium):
    """The optimisation from the page: a bar with its share done and the time left, a cancel
    button that stops it (said on the page), no apply button without a result.  On the
    module's server (its own tab: the fast path, the suite's default, as the server's)."""
    from playwright.sync_api import expect

    with _context(chromium, viewport={"width": 1500, "height": 1300}) as browser:
        page = browser.new_page()
        page.goto(server.url)
        expect(page.locator("[data-testid=status]")).to_contain_text("first pass in", timeout=90_000)
        page.get_by_text("studies of this design").click()
        page.locator("[data-testid=study-optimize]").click()
        log = page.locator("[data-testid=study-log]")
        expect(log).to_contain_text(re.compile(r"optimisation \(least mass, at most 40 designs\): \d+ %, "
                                               r"(about \d+ (s|min) left|finishing)"), timeout=30_000)
        expect(page.locator("[data-testid=study-apply]")).to_be_hidden()
        page.locator("[data-testid=study-cancel]").click()
        expect(log).to_contain_text(re.compile(r"cancelled after \d+ s"), timeout=120_000)
        expect(page.locator("[data-testid=study-cancel]")).to_be_hidden()
        expect(page.locator("[data-testid=study-apply]")).to_be_hidden()
    assert "Traceback" not in (server.out / "app.log").read_text()


@pytest.mark.parametrize("bad", ["0", "65"])
def test_max_tabs_outside_its_range_is_refused_naming_it(bad):
    from typer.testing import CliRunner

    from clutchfem.cli import app

    r = CliRunner().invoke(app, ["app", "--max-tabs", bad, "--no-browser", "--port", "18999"])
    assert r.exit_code != 0 and "Traceback" not in r.output
    assert f"max_tabs {bad}: an integer in 1..64" in r.output


def test_meshing_leaves_sigpipe_ignored():
    """gmsh.initialize sets SIGPIPE to SIG_DFL process-wide: after a meshing run, a write to a
    closed socket killed the process (the app's server, when a browser went away); a gmsh
    session puts it back, from the main thread and from a worker thread."""
    import ctypes
    import signal
    import threading

    from clutchfem.geometry.session import gmsh_session

    libc = ctypes.CDLL(None)
    libc.signal.restype = ctypes.c_void_p
    libc.signal.argtypes = [ctypes.c_int, ctypes.c_void_p]

    def disposition():
        prev = libc.signal(int(signal.SIGPIPE), ctypes.c_void_p(1))
        libc.signal(int(signal.SIGPIPE), ctypes.c_void_p(prev))
        return prev

    assert disposition() == 1  # Python's default: ignored
    with gmsh_session("t1"):
        assert disposition() == 1
    assert disposition() == 1
    worker = threading.Thread(target=_mesh_in_thread, args=(gmsh_session,))
    worker.start()
    worker.join()
    assert disposition() == 1


def _mesh_in_thread(gmsh_session) -> None:
    with gmsh_session("t2"):
        pass
