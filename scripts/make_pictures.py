"""Regenerate the README's and docs' study, target, field and report pictures with the tool itself.

Every picture is the PNG a ``clutchfem`` command writes (run as a subprocess, exactly as a
user runs it), copied to ``docs/img/`` under the name the README and docs show; the report
screenshot is headless Chromium's rendering of the ``report.html`` the tool writes, at
1280 x 800 px (the first screen).  Nothing is drawn here: a picture cannot drift from what
the tool draws.  The commands, their times, the machine and its load (the times are wall clock on a shared
machine) go to ``docs/img/pictures.json``.

    make pictures     # every group, default meshes (34 min on 2 cores under a load of 8-21)
    OPENBLAS_NUM_THREADS=1 .venv/bin/python scripts/make_pictures.py [--only study,fields]
        [--out docs/img] [--work out/pictures] [--mesh-size 2mm]

Groups (``--only``): ``study`` (the example spec: answers vs flexure thickness, parallel
coordinates), ``guidelines`` (concept 4: elasticities, one at a time), ``optimize``
(concept 4 from its defaults), ``compensate`` (concept 4 at 8000 rpm), ``report`` (the optimum's page and its screenshot), ``fields`` (von Mises of concept 4's
default design at 14000 rpm, the ParaView series beside it), ``export`` (concept 1's drawing
sheet for wire EDM, with its as-cut variants).  ``--mesh-size`` is passed to
the guideline, target and field commands (default: the tool's own default mesh); the study
uses the example spec's own mesh (2 mm).  Other pictures have their own scripts:
``make_concept_docs.py`` (concept drawings), ``make_clutch_docs.py`` (clutch model),
``make_durability_docs.py`` (slip heat, fatigue), ``clutchfem validate --docs``.  The
tolerance pictures of ``docs/design_to_targets.md`` belong to the two runs its text
describes (six toleranced dimensions of two optimised designs) and are not redrawn here.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import shutil
import subprocess
import sys
import time
from pathlib import Path

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

ROOT = Path(__file__).resolve().parents[1]
GROUPS = ("study", "guidelines", "optimize", "compensate", "report", "fields", "export")
CLI = [sys.executable, "-m", "clutchfem.cli"]
LOG: list[dict] = []


def run(args: list[str], **kw) -> subprocess.CompletedProcess:
    """Run one clutchfem command, stop the script with its stderr if it fails; log its time."""
    t0 = time.perf_counter()
    print("$ clutchfem " + " ".join(args), flush=True)
    p = subprocess.run(CLI + args, cwd=ROOT, capture_output=True, text=True, **kw)
    dt = time.perf_counter() - t0
    LOG.append({"command": ("clutchfem " + " ".join(args)).replace(f"{ROOT}/", ""), "seconds": round(dt, 1),
                "exit": p.returncode, "load_average_1min": round(os.getloadavg()[0], 1)})
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}) after {dt:.0f} s: clutchfem {' '.join(args)}\n{p.stderr[-3000:]}")
    print(f"  {dt:.0f} s", flush=True)
    return p


def one(folder: Path, pattern: str) -> Path:
    """The single file matching ``pattern`` in ``folder`` (the tool's names carry the design label)."""
    hits = sorted(folder.glob(pattern))
    if len(hits) != 1:
        sys.exit(f"expected one {pattern} in {folder}, found {[h.name for h in hits]}")
    return hits[0]


def copy(src: Path, out: Path, name: str) -> None:
    shutil.copyfile(src, out / name)
    print(f"  wrote {out / name}", flush=True)


def screenshot(html: Path, png: Path, size: str = "1280,800") -> None:
    """Headless Chromium's first screen of ``html``."""
    exe = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
    if exe is None:
        sys.exit("the report screenshot needs chromium (apt-get install chromium)")
    t0 = time.perf_counter()
    cmd = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", f"--window-size={size}",
           f"--screenshot={png}", html.resolve().as_uri()]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    LOG.append({"command": "chromium --headless --window-size=" + size + " --screenshot " + html.name,
                "seconds": round(time.perf_counter() - t0, 1), "exit": p.returncode,
                "load_average_1min": round(os.getloadavg()[0], 1)})
    if p.returncode != 0 or not png.exists():
        sys.exit(f"chromium failed: {p.stderr[-2000:]}")
    print(f"  wrote {png}", flush=True)


def mesh_args(a) -> list[str]:
    return ["--mesh-size", a.mesh_size] if a.mesh_size else []


def study(a, out: Path, work: Path) -> None:
    spec = work / "study.toml"
    spec.write_text(run(["study", "--example"]).stdout)
    run(["study", str(spec), "--out", str(work / "study")])
    copy(work / "study" / "charts" / "answers_vs_clearance.png", out, "study_sweep_answers.png")
    copy(work / "study" / "charts" / "parallel_coordinates.png", out, "study_parallel_coordinates.png")


def guidelines(a, out: Path, work: Path) -> None:
    run(["guidelines", "concept4", *mesh_args(a), "--out", str(work / "guidelines")])
    copy(work / "guidelines" / "elasticities.png", out, "study_guidelines_elasticities.png")
    copy(work / "guidelines" / "one_at_a_time.png", out, "study_guidelines_one_at_a_time.png")


def optimize(a, out: Path, work: Path) -> None:
    run(["optimize", "concept4", *mesh_args(a), "--out", str(work / "opt")])
    copy(work / "opt" / "optimization_path.png", out, "targets_optimization_path.png")


def optimum(a, work: Path) -> list[str]:
    """The optimum's ``--set`` arguments (base + final) from the optimize run, run first if missing."""
    doc = work / "opt" / "optimization.json"
    if not doc.exists():
        optimize(a, Path(a.out), work)
    return [x for kv in json.loads(doc.read_text())["set"] for x in ("--set", kv)]


def compensate(a, out: Path, work: Path) -> None:
    run(["compensate", "concept4", *mesh_args(a), "--rpm", "8000rpm", "--out", str(work / "comp")])
    copy(work / "comp" / "compensation_profile.png", out, "targets_compensation_profile.png")
    copy(work / "comp" / "compensation_torque.png", out, "targets_compensation_torque.png")


def report(a, out: Path, work: Path) -> None:
    run(["report", "concept4", *optimum(a, work), *mesh_args(a), "--out", str(work / "report")])
    screenshot(work / "report" / "report.html", out / "targets_report.png")


def fields(a, out: Path, work: Path) -> None:
    run(["solve", "concept4", *mesh_args(a), "--rpm", "0:14000:250", "--vtk", "--vtk-rpm", "2000:14000:2000",
         "--out", str(work / "fields")])
    copy(one(work / "fields", "*fields_14000rpm.png"), out, "fields_von_mises.png")


def export(a, out: Path, work: Path) -> None:
    run(["export", "concept4", *mesh_args(a), "--process", "wire-edm", "--tol", "flexure_thickness=+-0.02mm",
         "--out", str(work / "export")])
    copy(one(work / "export", "*_drawing.png"), out, "export_workshop_drawing.png")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=",".join(GROUPS), help=f"comma separated groups of {GROUPS}")
    ap.add_argument("--out", default=str(ROOT / "docs" / "img"))
    ap.add_argument("--work", default=str(ROOT / "out" / "pictures"))
    ap.add_argument("--mesh-size", default="", help="e.g. 2mm (default: the tool's default mesh)")
    a = ap.parse_args(argv)
    groups = [g.strip() for g in a.only.split(",") if g.strip()]
    bad = [g for g in groups if g not in GROUPS]
    if bad:
        ap.error(f"--only: unknown group(s) {bad}; allowed: {', '.join(GROUPS)}")
    out, work = Path(a.out), Path(a.work)
    out.mkdir(parents=True, exist_ok=True)
    work.mkdir(parents=True, exist_ok=True)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    for g in groups:
        globals()[g](a, out, work)
    log = out / "pictures.json"
    old = json.loads(log.read_text()) if log.exists() else {}
    for g in groups:
        old[g] = {"date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
                  "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
                  "mesh_size": a.mesh_size or "default",
                  "commands": [x for x in LOG if _group_of(x["command"]) == g]}
    log.write_text(json.dumps(old, indent=1) + "\n")
    print(f"wrote {log}")
    return 0


def _group_of(cmd: str) -> str:
    if cmd.startswith("chromium"):
        return "report"
    return {"solve": "fields"}.get(cmd.split()[1], cmd.split()[1])


if __name__ == "__main__":
    sys.exit(main())
