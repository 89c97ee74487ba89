"""The README's screenshot of the live design app (docs/img/app.png): concept 4 at its
defaults pinned, then the flexure thickness moved to 1.9 mm, the answers side by side.

    .venv/bin/python scripts/make_app_screenshot.py [--out docs/img/app.png]

Needs Debian's chromium (installed by `make setup`)."""

from __future__ import annotations

import argparse
import re
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from support.browser import app_server, launch_chromium  # noqa: E402


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "img" / "app.png")
    args = ap.parse_args(argv)
    from playwright.sync_api import expect, sync_playwright

    if shutil.which("chromium") is None:
        sys.exit("scripts/make_app_screenshot.py: Debian's chromium is not installed (make setup installs it)")
    with app_server(Path(tempfile.mkdtemp())) as url, sync_playwright() as p:
        b = launch_chromium(p)
        page = b.new_page(viewport={"width": 1500, "height": 1250})
        page.goto(url)
        status = page.locator("[data-testid=status]")
        expect(status).to_contain_text("with error bands", timeout=120_000)
        page.locator("[data-testid=pin]").click()
        box = page.locator("input[data-testid=num-flexure_thickness]")
        box.fill("1.9")
        box.press("Enter")
        expect(page.locator("[data-testid=answers] th", has_text="pinned")).to_be_visible(timeout=60_000)
        expect(status).to_contain_text(re.compile(r"concept4-\w+: .*with error bands"), timeout=120_000)
        time.sleep(1.0)
        args.out.parent.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(args.out), full_page=False)
        b.close()
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
