"""Issue 37: CLI tables fit an 80-column terminal without cutting a number (rich wraps or
folds every cell; a table too wide even so is drawn compact, else transposed).  The cheap
tests print the tables through the CLI's console; the slow ones run the main commands at 80
columns in this process."""

from __future__ import annotations

import re

import pytest
from rich.table import Table

from clutchfem.cli import common
from clutchfem.guidelines import ANSWERS, GuidelineResult
from clutchfem.report.guideline_charts import guideline_table
from support.cli import cli_in_process

PARAMS = ("flexure_thickness", "clearance", "shoe_arc", "eccentric_angle")


@pytest.fixture
def terminal80(monkeypatch):
    """The CLI's consoles as an 80-column terminal (messages wrapped, not one line)."""
    for c in (common.console, common.err):
        monkeypatch.setattr(c, "soft_wrap", False)
        monkeypatch.setattr(c, "_width", 80)
    return common.console


def assert_fits(text: str, numbers=()) -> None:
    """No line over 80 columns (but a command to copy, kept on one line: 'verify: clutchfem
    analyze ... --set ...'), no ellipsis, each of ``numbers`` whole."""
    long = [ln for ln in text.splitlines() if len(ln) > 80 and "--set " not in ln]
    assert not long, f"{len(long)} lines over 80 columns: {long[:3]}"
    assert "\u2026" not in text and "..." not in text, text
    for n in numbers:  # each number shown whole (not folded across lines)
        assert re.search(r"(?<![\d.])" + re.escape(n) + r"(?![\d])", text), (n, text)


def test_guidelines_table_fits_80_columns(terminal80, capsys):
    rows = [{"parameter": n, "answer": a, "unit": "m", "x0": 0.0022 + 1e-4 * j, "E": 1.2345 + 0.01 * j,
             "verdict": "unstable", "method": "one-sided central difference on morphed meshes", "kink": 1}
            for j, n in enumerate(PARAMS) for a, _ in ANSWERS]
    res = GuidelineResult("concept4", {}, 0.02, rows, list(PARAMS), oat=None)
    res.methods.update({n: "central difference, meshed from scratch" for n in PARAMS})
    terminal80.print(guideline_table(res))
    out = capsys.readouterr().out
    assert_fits(out, numbers=[f"~+{1.2345 + 0.01 * j:.2f}1k" for j in range(4)] + list(PARAMS))


def test_a_table_too_wide_for_80_columns_is_transposed_whole(terminal80, capsys):
    t = Table(title="sixteen answers")
    t.add_column("design")
    for k in range(16):
        t.add_column(f"answer {k} [MPa]", justify="right")
    t.add_row("concept4", *[f"{1234.5678 + k:.4f}" for k in range(16)])
    terminal80.print(t)
    out = capsys.readouterr().out
    assert_fits(out, numbers=[f"{1234.5678 + k:.4f}" for k in range(16)])
    assert "answer 15 [MPa]" in out


def test_a_long_word_is_folded_not_cut(terminal80, capsys):
    t = Table(title="files")
    t.add_column("file")
    t.add_column("size", justify="right")
    path = "/" + "/".join(f"folder{k:02d}" for k in range(12)) + "/concept4-fcd4d4c9cee8_arc_stress_rpm.png"
    t.add_row(path, "123456 bytes")
    terminal80.print(t)
    out = capsys.readouterr().out
    assert_fits(out, numbers=["123456"])
    assert "".join(ln.strip(" │┃|") for ln in out.splitlines()).count("fcd4d4c9cee8") == 1


COMMANDS = {
    "analyze": ("analyze", "concept4", "--mesh-size", "3mm", "--fidelity", "fast", "--rpm", "0:14000:2000"),
    # one operating input (its row of the table is laid out as the idle speed's would be: the
    # idle speed's four more designs were a quarter of the command's time)
    "guidelines": ("guidelines", "concept4", "--params", "flexure_thickness", "--mesh-size", "3mm", "--workers", "0",
                   "--points", "3", "--fidelity", "fast", "--inputs", "mu"),
    "tolerance": ("tolerance", "concept4", "--mesh-size", "3mm", "--fidelity", "fast", "--tol", "clearance=+-0.02mm",
                  "--n", "8", "--workers", "0", "--no-shifts"),
    "optimize": ("optimize", "concept4", "--mesh-size", "3mm", "--workers", "0", "--fidelity", "fast", "--free",
                 "flexure_thickness", "--max-evals", "3"),
    "export": ("export", "concept4", "--no-analysis"),
    "calibrate": ("calibrate", "concept1", "--fidelity", "fast", "--mesh-size", "3mm", "--n", "6", "--held-out", "2",
                  "--workers", "0", "--measured", "engagement=4000rpm+-30rpm", "--measured", "slip=7500rpm+-60rpm",
                  "--uncertain", "mu=0.15:0.2", "--uncertain", "flexure_thickness=+-0.05mm",
                  # the sampler's shortest chain (default 5000 steps, ~3.5 s): the same tables, their
                  # numbers rougher, and one note more (a short chain) that must fit too
                  "--steps", "1000"),
}


@pytest.mark.slow
@pytest.mark.parametrize("name", list(COMMANDS))
def test_main_commands_fit_80_columns(name, terminal80, tmp_path):
    r = cli_in_process(*COMMANDS[name], "--out", str(tmp_path / name), env={"COLUMNS": "80"})
    assert r.returncode == 0, r.stderr[-3000:]
    assert r.stdout.strip(), "no table printed"
    assert_fits(r.stdout)
