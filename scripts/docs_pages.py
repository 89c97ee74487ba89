"""The generated pages of the documentation site (run by mkdocs-gen-files in ``make docs``).

* ``api/``: one page per public name, taken from ``clutchfem.__all__`` at build time (never a
  hand-written list), grouped as the package docstring groups them, plus an overview and the
  section's navigation (``api/SUMMARY.md``, read by mkdocs-literate-nav); the groups are
  ``clutchfem._GROUPS``, the one table the public names come from.  A page documents
  the object where it is *defined* (its ``__module__`` and ``__qualname__``): the package's
  names are imported lazily (PEP 562), which griffe, reading the source statically, cannot
* ``cli.md``: every command of the typer app with its arguments and options, from typer's
  own Markdown of the click command tree (what ``typer clutchfem.cli utils docs`` prints).
* ``benchmarks.md``: ``BENCHMARKS.md`` of the repository root, included as it is.

Run alone (``python scripts/docs_pages.py``) it prints the public names with their group and
the object each page documents.
"""

from __future__ import annotations

import inspect
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT / "src") not in sys.path:
    sys.path.insert(0, str(ROOT / "src"))  # the checkout's source, as mkdocstrings reads it

def public_names() -> list[str]:
    import clutchfem

    return [n for n in clutchfem.__all__ if not n.startswith("__")]


def target(name: str) -> tuple[object, str]:
    """The object of a public name and the dotted path where it is defined."""
    import clutchfem

    obj = getattr(clutchfem, name)
    module, qualname = getattr(obj, "__module__", None), getattr(obj, "__qualname__", None)
    if isinstance(module, str) and isinstance(qualname, str) and "<" not in qualname:
        return obj, f"{module}.{qualname}"
    return obj, f"clutchfem.{name}"  # a plain value: griffe finds it in the package itself


ROLE = re.compile(r":(?:py:)?[a-z]+:`~?([^`]+)`")


def summary(obj: object, limit: int = 160) -> str:
    """The docstring's first sentence (Sphinx roles as code), for the overview's table."""
    doc = inspect.getdoc(obj) or ""
    text = " ".join(doc.strip().split("\n\n")[0].split())
    text = ROLE.sub(lambda m: f"`{m[1].lstrip('.')}`", text)
    end = re.search(r"\.(\s|$)", text)
    text = text[:end.start() + 1] if end else text
    if len(text) > limit:
        text = text[:limit].rsplit(" ", 1)[0] + " ..."
    return text.replace("|", "\\|")


def api_pages() -> dict[str, list[tuple[str, object, str]]]:
    """group -> [(public name, object, defining path)]: the groups of ``clutchfem._GROUPS`` (the
    public API by job, where ``clutchfem.__all__`` comes from), in order, names as listed; a
    public name in no group (none today: a test holds them equal) goes to "Other"."""
    import clutchfem

    pages: dict[str, list[tuple[str, object, str]]] = {g: [] for g in [*clutchfem._GROUPS, "Other"]}
    where = {n: g for g, names in clutchfem._GROUPS.items() for n in names}
    for name in public_names():
        obj, path = target(name)
        pages[where.get(name, "Other")].append((name, obj, path))
    return {g: entries for g, entries in pages.items() if entries}


def api_page(name: str, grp: str, path: str) -> str:
    defined = path.rsplit(".", 1)
    where = f"`{defined[0]}`" if len(defined) == 2 else "`clutchfem`"
    renamed = "" if path.rsplit(".", 1)[-1] == name else f" as `{path.rsplit('.', 1)[-1]}`"
    return (f"# clutchfem.{name}\n\n"
            f"*{grp}* · `import clutchfem as cf; cf.{name}` · defined in {where}{renamed}\n\n"
            f"::: {path}\n")


def api_index(pages: dict[str, list[tuple[str, object, str]]]) -> str:
    lines = ["# API reference", "",
             "`import clutchfem as cf` loads no numerical library: each public name is imported on first",
             "use. These are the names of `cf.__all__`, one page each, generated from their numpydoc",
             "docstrings at build time; every example on them runs as a doctest in `make test`.",
             "Quantities take unit strings (`\"2.4mm\"`, `\"200GPa\"`) or SI floats everywhere.", ""]
    for grp, entries in pages.items():
        lines += [f"## {grp}", "", "| name | what it is |", "| --- | --- |"]
        lines += [f"| [`{name}`]({name}.md) | {summary(obj)} |" for name, obj, _ in entries]
        lines.append("")
    return "\n".join(lines)


def api_summary(pages: dict[str, list[tuple[str, object, str]]]) -> str:
    lines = ["* [Overview](index.md)"]
    for grp, entries in pages.items():
        lines.append(f"* {grp}")
        lines += [f"    * [{name}]({name}.md)" for name, _, _ in entries]
    return "\n".join(lines) + "\n"


def cli_page() -> str:
    import click
    import typer.cli
    import typer.main

    from clutchfem.cli import app

    command = typer.main.get_command(app)
    docs = typer.cli.get_docs_for_click(obj=command, ctx=click.Context(command), name="clutchfem",
                                        title="CLI reference")
    # each command's example (its epilog) as a shell block, the command list linked to the sections
    docs = re.sub(r"^Example: (clutchfem .*?)(?:  \((.*)\))?$",
                  lambda m: "**Example**:\n\n```sh\n" + m[1] + (f"   # {m[2]}" if m[2] else "") + "\n```",
                  docs, flags=re.M)
    docs = re.sub(r"^\* `([a-z][a-z0-9-]*)`: ", lambda m: f"* [`{m[1]}`](#clutchfem-{m[1]}): ", docs, flags=re.M)
    head, _, rest = docs.partition("\n")
    note = ("\n\nGenerated at build time from the typer app `clutchfem.cli:app` (typer's own Markdown of "
            "the click command tree, as `clutchfem COMMAND --help` shows it): every command with its "
            "arguments and options.")
    return head + note + "\n" + rest


def main() -> None:
    import mkdocs_gen_files

    pages = api_pages()
    for grp, entries in pages.items():
        for name, _, path in entries:
            with mkdocs_gen_files.open(f"api/{name}.md", "w") as f:
                f.write(api_page(name, grp, path))
            mkdocs_gen_files.set_edit_path(f"api/{name}.md", None)
    with mkdocs_gen_files.open("api/index.md", "w") as f:
        f.write(api_index(pages))
    with mkdocs_gen_files.open("api/SUMMARY.md", "w") as f:
        f.write(api_summary(pages))
    with mkdocs_gen_files.open("cli.md", "w") as f:
        f.write(cli_page())
    with mkdocs_gen_files.open("benchmarks.md", "w") as f:
        f.write((ROOT / "BENCHMARKS.md").read_text())


if __name__ == "__main__":
    for grp, entries in api_pages().items():
        for name, _, path in entries:
            print(f"{grp:18s} {name:20s} {path}")
elif __name__ == "<run_path>":  # mkdocs-gen-files runs it so (runpy.run_path), in a build
    main()
