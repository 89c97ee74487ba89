"""The documentation site (issue 35): ``make docs`` builds it with every warning an error, and
this builds it the same way (``mkdocs build --strict``, into a temporary folder) and reads
what came out:

* every public name (``clutchfem.__all__``) has its page under ``api/``, and the page shows
  the code of its docstring's Examples section (the doctests ``make test`` runs);
* the CLI reference names every command of the typer app, subcommands too, and every option
  of each;
* README.md stays a front page: at most 150 lines, still with the two commands.

The build takes ~20 s (it imports every public name and renders ~45 pages), hence ``slow``;
it runs in ``make test``.
"""

from __future__ import annotations

import html
import inspect
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

import clutchfem

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.slow


def _text(page: Path) -> str:
    """A built page as text: tags dropped, entities decoded, whitespace runs made one space."""
    raw = page.read_text(encoding="utf-8")
    raw = re.sub(r"<(script|style)\b.*?</\1>", " ", raw, flags=re.S)
    return " ".join(html.unescape(re.sub(r"<[^>]+>", "", raw)).split())


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("site")
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1", "DISABLE_MKDOCS_2_WARNING": "true",
           "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT / "src"), os.environ.get("PYTHONPATH")]))}
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(out)],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=600)
    print(f"mkdocs build --strict: {time.perf_counter() - t0:.1f} s")
    warnings = [line for line in (p.stdout + p.stderr).splitlines() if "WARNING" in line and " -  " in line]
    assert p.returncode == 0 and not warnings, "the site does not build without warnings:\n" + "\n".join(
        warnings or (p.stdout + p.stderr).splitlines()[-30:])
    return out


def _examples(obj: object) -> list[str]:
    """The code lines (after ``>>>``) of a numpydoc Examples section."""
    doc = inspect.getdoc(obj) or ""
    m = re.search(r"^Examples\n-{3,}\n", doc, re.M)
    if not m:
        return []
    section = re.split(r"^\S.*\n-{3,}\n", doc[m.end():], maxsplit=1, flags=re.M)[0]
    code = [line.strip()[4:] for line in section.splitlines() if line.strip().startswith(">>> ")]
    return [re.sub(r"\s*#\s*doctest:.*$", "", line) for line in code]  # the site trims doctest flags


def test_every_public_name_has_a_page_with_its_example(site):
    names = [n for n in clutchfem.__all__ if n != "__version__"]
    assert len(names) >= 30
    index = _text(site / "api" / "index.html")
    missing = []
    for name in names:
        page = site / "api" / f"{name}.html"
        assert page.is_file(), f"no API page for cf.{name}"
        assert name in index, f"the API overview does not list cf.{name}"
        code = _examples(getattr(clutchfem, name))
        assert code, f"cf.{name}'s docstring has no Examples section with a >>> line"
        text = _text(page)
        missing += [f"cf.{name}: {line}" for line in code if " ".join(line.split()) not in text]
    assert not missing, "example code not on its page:\n" + "\n".join(missing)


def _commands(group, prefix: str = "clutchfem"):
    import click

    for name, command in sorted(group.commands.items()):
        if command.hidden:
            continue
        yield f"{prefix} {name}", command
        if isinstance(command, click.Group):
            yield from _commands(command, f"{prefix} {name}")


def test_cli_reference_lists_every_command_and_option(site):
    import typer.main

    from clutchfem.cli import app

    text = _text(site / "cli.html")
    commands = list(_commands(typer.main.get_command(app)))
    assert len(commands) >= 10
    for path, command in commands:
        assert path in text, f"the CLI reference does not show {path}"
        for param in command.params:
            if getattr(param, "hidden", False):
                continue
            for opt in param.opts:
                if opt.startswith("-"):
                    assert opt in text, f"the CLI reference does not show {path} {opt}"


def test_user_guide_pages_and_pictures_are_in_the_site(site):
    for page in (ROOT / "docs").glob("*.md"):
        assert (site / page.with_suffix(".html").name).is_file(), f"docs/{page.name} is not in the site"
    for img in ["app.png", "fields_von_mises.png", "concept4.png"]:
        assert (site / "img" / img).is_file()
    assert "Benchmarks and verification figures" in _text(site / "benchmarks.html")  # BENCHMARKS.md


def test_readme_is_a_front_page():
    readme = (ROOT / "README.md").read_text()
    assert len(readme.splitlines()) <= 150
    for command in ["make demo", "make test"]:
        assert command in readme
    for page in re.findall(r"\]\((docs/[^)#\s]+\.md)", readme):
        assert (ROOT / page).is_file(), f"README links {page}, which does not exist"
