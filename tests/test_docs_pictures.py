"""The README's pictures are drawn by the code, never by hand (issue 25): every image the
README shows, and the site pages that took the README's long content (issue 35: home,
getting started, the tour), exists and is named by a script in ``scripts/`` that writes it
(``scripts/make_pictures.py``, run by ``make pictures``, for the study, guideline, target,
field, report and cutting pictures)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


#: the README and the site pages that show the README's former pictures, with the folder their
#: image paths are relative to
PAGES = {"README.md": ROOT, "docs/index.md": ROOT / "docs", "docs/getting_started.md": ROOT / "docs",
         "docs/guide.md": ROOT / "docs"}


def test_every_readme_picture_is_made_by_a_script():
    images = []
    for page, base in PAGES.items():
        shown = re.findall(r"!\[[^\]]*\]\(((?:docs/)?img/[^)\s]+\.png)\)", (ROOT / page).read_text())
        assert shown, f"{page} shows no picture"
        images += [(page, (base / img).relative_to(ROOT).as_posix()) for img in shown]
    assert len({img for _, img in images}) >= 5
    scripts = {p.name: p.read_text() for p in (ROOT / "scripts").glob("*.py")}
    for page, img in images:
        assert (ROOT / img).is_file(), f"{page} shows {img}, which does not exist"
        name = Path(img).name
        makers = [s for s, text in scripts.items() if name in text]
        assert makers, f"{page} shows {img}, but no script in scripts/ writes it"


def test_make_pictures_refuses_an_unknown_group(tmp_path):
    p = subprocess.run([sys.executable, str(ROOT / "scripts" / "make_pictures.py"), "--only", "study,bogus",
                        "--out", str(tmp_path), "--work", str(tmp_path)], capture_output=True, text=True)
    assert p.returncode == 2 and "bogus" in p.stderr and "fields" in p.stderr  # names the value and the allowed
    assert not any(tmp_path.iterdir())  # nothing run, nothing written
