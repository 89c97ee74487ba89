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
import logging
import re
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
    """The site as ``mkdocs build --strict --site-dir OUT`` builds it from the checkout, run in
    this process (mkdocs' own build with its strict count of warnings; every warning it logs is
    collected and named): a process of its own paid its start and every public name's imports
    again, ~5 s of its ~15 s."""
    from mkdocs.commands.build import build
    from mkdocs.config import load_config

    out = tmp_path_factory.mktemp("site")
    warnings: list[str] = []

    class Warnings(logging.Handler):
        def emit(self, record):
            warnings.append(f"{record.levelname} -  {record.getMessage()}")

    catch = Warnings(level=logging.WARNING)
    logging.getLogger("mkdocs").addHandler(catch)
    t0 = time.perf_counter()
    try:
        with pytest.MonkeyPatch.context() as mp:
            mp.chdir(ROOT)
            mp.setenv("NO_MKDOCS_2_WARNING", "1")
            mp.setenv("DISABLE_MKDOCS_2_WARNING", "true")
            mp.setattr(sys, "path", [str(ROOT / "src"), *sys.path])
            try:
                build(load_config(config_file=str(ROOT / "mkdocs.yml"), strict=True, site_dir=str(out)))
            except (Exception, SystemExit) as exc:  # mkdocs' Abort (strict: warnings), a plugin's error
                warnings.append(f"the build stopped: {type(exc).__name__}: {exc}")
    finally:
        logging.getLogger("mkdocs").removeHandler(catch)
    print(f"mkdocs build --strict: {time.perf_counter() - t0:.1f} s")
    assert not warnings, "the site does not build without warnings:\n" + "\n".join(warnings)
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
