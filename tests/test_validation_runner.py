"""Validation runner: lazy module loading, warnings, Markdown report, rich table (its run time: benchmarks/bench_validation.py)."""

from __future__ import annotations

import json
import re
import sys
import types
import warnings
from pathlib import Path

import pytest
from rich.console import Console

from clutchfem.validation import runner
from clutchfem.validation.records import ValidationRecord

MINE = ("chain", "shaft")


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """One report of chain + shaft + a module that does not exist (written once)."""
    root = tmp_path_factory.mktemp("val")
    with pytest.warns(runner.ValidationModuleWarning, match="no_such_module"):
        md = runner.write_report(root / "out", root / "docs" / "validation.md",
                                 modules=MINE + ("no_such_module",))
    return root, md


def test_default_modules():
    """Discovered, not listed: the four paper modules in their ORDER, with their SOURCE
    headings; the package's helpers (records, runner) are not validation modules."""
    names = runner.module_names()
    assert [n for n in names if n in ("wiesik", "thesis", "chain", "shaft")] == [
        "wiesik", "thesis", "chain", "shaft"]
    assert "records" not in names and "runner" not in names
    assert runner.source_of("shaft").startswith("seed 004: circular-saw shaft")
    assert runner.source_of("wiesik").startswith("seed 000: spring-and-shoe clutch")
    assert runner.discover()[1] == []  # every module has a SOURCE and a valid ORDER


DROPPED = '''
from clutchfem.validation.records import ValidationRecord

SOURCE = "test: a module dropped into the package"
{order}

def records():
    return [ValidationRecord("{name}.x", "{name}", "q", 2.0, 2.0, "-")]
'''


@pytest.fixture
def dropped(tmp_path, monkeypatch):
    """Files dropped into the validation package (a temporary folder appended to its
    ``__path__``): ``zz_dropped`` (ORDER 25), ``aa_late`` (no ORDER), a helper without
    records(), a private ``_hidden`` module and one that fails to import."""
    import clutchfem.validation as pkg

    d = tmp_path / "validation_extra"
    d.mkdir()
    (d / "zz_dropped.py").write_text(DROPPED.format(name="zz_dropped", order="ORDER = 25"))
    (d / "aa_late.py").write_text(DROPPED.format(name="aa_late", order=""))
    (d / "helper_only.py").write_text("X = 1\n")
    (d / "_hidden.py").write_text(DROPPED.format(name="_hidden", order="ORDER = 1"))
    (d / "broken_mod.py").write_text("raise RuntimeError('kaputt')\n")
    monkeypatch.setattr(pkg, "__path__", [*pkg.__path__, str(d)])
    for n in ("zz_dropped", "aa_late", "helper_only", "_hidden", "broken_mod"):
        monkeypatch.delitem(sys.modules, f"clutchfem.validation.{n}", raising=False)
    yield d
    for n in ("zz_dropped", "aa_late", "helper_only", "_hidden", "broken_mod"):
        sys.modules.pop(f"clutchfem.validation.{n}", None)


def test_a_dropped_module_is_discovered_and_run(dropped, monkeypatch):
    names, notes = runner.discover()
    # ORDER 25 sits between thesis (20) and chain (30); no ORDER comes last
    assert names.index("thesis") < names.index("zz_dropped") < names.index("chain")
    assert names[-1] == "aa_late"
    assert "helper_only" not in names and "_hidden" not in names
    assert any("broken_mod" in w and "kaputt" in w for w in notes)
    with pytest.raises(RuntimeError, match="kaputt"):
        runner.discover(strict=True)
    # a full run (the paper modules stubbed out: only discovery is under test here)
    for n in ("wiesik", "thesis", "chain", "shaft"):
        monkeypatch.setattr(sys.modules[f"clutchfem.validation.{n}"], "records", lambda: [])
    run = runner.collect()
    assert [r.id for r in run.records] == ["zz_dropped.x", "aa_late.x"]
    assert any("broken_mod" in w for w in run.warnings)
    md = runner.render_markdown(run, {}, dropped / "v.md")
    assert "## zz_dropped\n\nSource: test: a module dropped into the package." in md
    assert md.index("## zz_dropped") < md.index("## aa_late")


def test_order_and_source_are_checked(tmp_path, monkeypatch):
    import clutchfem.validation as pkg

    d = tmp_path / "v2"
    d.mkdir()
    (d / "no_source.py").write_text(DROPPED.format(name="no_source", order="ORDER = 'first'")
                                    .replace("SOURCE =", "NOT_SOURCE ="))
    monkeypatch.setattr(pkg, "__path__", [*pkg.__path__, str(d)])
    monkeypatch.delitem(sys.modules, "clutchfem.validation.no_source", raising=False)
    try:
        names, notes = runner.discover()
        assert names[-1] == "no_source"  # an invalid ORDER counts as none
        assert any("no_source" in w and "ORDER" in w for w in notes)
        assert any("no_source" in w and "SOURCE" in w for w in notes)
        assert runner.source_of("no_source") == "no_source"
    finally:
        sys.modules.pop("clutchfem.validation.no_source", None)


def test_missing_module_is_skipped_with_a_warning():
    run = runner.collect(("no_such_module", "chain"))
    assert any("no_such_module" in w and "skipped" in w for w in run.warnings)
    assert {r.module for r in run.records} == {"chain"}
    with pytest.warns(runner.ValidationModuleWarning):
        recs = runner.run_all(("no_such_module", "chain"))
    assert len(recs) == len(run.records)
    with pytest.raises(ModuleNotFoundError):
        runner.collect(("no_such_module",), strict=True)


def test_failing_module_is_reported_not_hidden(monkeypatch):
    def broken():
        raise RuntimeError("boom")

    fake = types.ModuleType("clutchfem.validation._fake_broken")
    fake.records = broken
    monkeypatch.setitem(sys.modules, "clutchfem.validation._fake_broken", fake)
    run = runner.collect(("_fake_broken", "chain"))
    assert any("_fake_broken" in w and "boom" in w for w in run.warnings)
    assert run.records and all(r.module == "chain" for r in run.records)
    with pytest.raises(RuntimeError):
        runner.collect(("_fake_broken",), strict=True)


def test_unexplained_differs_and_duplicates_are_flagged(monkeypatch):
    fake = types.ModuleType("clutchfem.validation._fake_dup")
    fake.records = lambda: [ValidationRecord("x.a", "x", "q", 1.0, 2.0, "-"),
                            ValidationRecord("x.a", "x", "q", 1.0, 1.0, "-")]
    monkeypatch.setitem(sys.modules, "clutchfem.validation._fake_dup", fake)
    run = runner.collect(("_fake_dup",))
    assert any("without an explanation" in w for w in run.warnings)
    assert any("duplicate" in w for w in run.warnings)


@pytest.mark.slow
def test_report_contents(report):
    root, md = report
    text = md.read_text()
    data = json.loads((root / "out" / "validation.json").read_text())
    recs = [types.SimpleNamespace(**d) for d in data["records"]]
    assert {r.module for r in recs} == set(MINE)
    for r in recs:
        assert f"`{r.id}`" in text
    # every differs row is explained in its module's section
    for name in MINE:
        section = text.split(f"## {name}\n", 1)[1].split("\n## ", 1)[0]
        explained = section.split("### Differences explained", 1)[1]
        for r in recs:
            if r.module == name and r.status == "differs":
                assert f"- `{r.id}`:" in explained
    assert "## Warnings" in text and "no_such_module" in text
    # figures: relative links that resolve from the report's folder
    links = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", text)
    assert len(links) == 4
    for link in links:
        assert not Path(link).is_absolute()
        assert (md.parent / link).resolve().is_file()
    assert {"id", "paper", "computed", "status", "rel_diff", "note"} <= set(data["records"][0])
    assert len(recs) == len({r.id for r in recs}) > 90


def test_rich_table_reads_at_80_columns():
    recs = runner.collect(("chain",)).records
    console = Console(record=True, width=80)
    runner.print_table(recs, console=console)
    out = console.export_text()
    assert max(len(line.rstrip()) for line in out.splitlines()) <= 80
    assert "id (chain.*)" in out and "Nu2_min " in out and "differs" in out
    # every differs row is listed with its reason under the module's table
    why = out.split("Why chain rows differ:", 1)[1]
    for r in recs:
        if r.status == "differs":
            assert f"- {r.id}:" in why
    assert f"{len(recs)} records" in out
    # the table clutchfem validate prints (ValidationRun.table) is this one
    again = Console(record=True, width=80)
    again.print(runner.ValidationRun(records=recs).table())
    assert again.export_text() == out


def test_report_run_does_not_run_modules_again(monkeypatch, tmp_path):
    calls = []
    fake = types.ModuleType("clutchfem.validation._fake_once")
    fake.records = lambda: calls.append(1) or [ValidationRecord("y.a", "y", "q", 1.0, 1.0, "-")]
    fake.figures = lambda out: []
    monkeypatch.setitem(sys.modules, "clutchfem.validation._fake_once", fake)
    run = runner.collect(("_fake_once",))
    runner.report_run(run, tmp_path / "out", tmp_path / "v.md")
    assert calls == [1]
    assert "`y.a`" in (tmp_path / "v.md").read_text()


@pytest.mark.slow
def test_full_run_writes_the_report(tmp_path):
    """Everything that exists (all four modules when present) runs and is reported.  Its run
    time (well under 60 s) is measured in benchmarks/bench_validation.py, not asserted here."""
    with warnings.catch_warnings():  # other engineers' modules may be missing: not our test
        warnings.simplefilter("ignore", runner.ValidationModuleWarning)
        runner.write_report(tmp_path / "out", tmp_path / "validation.md")
    assert (tmp_path / "validation.md").stat().st_size > 1000


@pytest.mark.slow
def test_cli_validate_docs_collects_once(monkeypatch, tmp_path):
    from typer.testing import CliRunner

    from clutchfem.cli import app

    calls = []
    real = runner.collect

    def counting(modules=None, **kw):
        calls.append(kw)
        return real(("chain",), **kw)

    monkeypatch.setattr(runner, "collect", counting)
    res = CliRunner().invoke(app, ["validate", "--docs", str(tmp_path / "v.md"), "--out",
                                   str(tmp_path / "out")])
    assert res.exit_code == 0, res.output
    assert len(calls) == 1  # the modules ran once, for the table and the report
    assert (tmp_path / "v.md").is_file() and (tmp_path / "out" / "validation.json").is_file()
    res = CliRunner().invoke(app, ["validate", "--json"])
    data = json.loads(res.stdout)
    assert {"id", "paper", "computed", "unit", "status", "note"} <= set(data[0])
    # the crankshaft whirl left validation (clutch/whirl.py): --concept is gone, and an
    # unknown option is refused with a non-zero exit before any module runs
    calls.clear()
    for bad in (["concept1"], ["--no-such-option"]):
        res = CliRunner().invoke(app, ["validate", *bad])
        assert res.exit_code != 0 and calls == []
