"""Write docs/concepts.md and docs/img/<concept>.png for every registered concept.

For each concept: its labelled drawing at the default parameters, what the thesis says, how
the text was turned into parameters (the concept file's docstring), the parameter table
(``ParamSet.describe()``), and facts at the defaults (shoe mass, R_Tp, part mass, elements
of the default sector mesh and, when the FE solver is available, the engagement speed).

    .venv/bin/python scripts/make_concept_docs.py [--out docs] [--no-fe]
"""

from __future__ import annotations

import argparse
import inspect
import math
import os
import sys
import tempfile
import textwrap
import time
from pathlib import Path

# the figures this records (BENCHMARKS.md, docs/) are the fast 2-D path's unless a model asks for
# "best": the shipped default is the best estimate since issue 20
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

RHO_STEEL = 7850.0
PNG_LIMIT = 200_000


def _fmt_default(P, row) -> str:
    v, unit = row["default"], row["unit"]
    if isinstance(v, str):
        return f"`{v}`"
    if unit == "m":
        return f"{v * 1e3:g} mm"
    return f"{v:g}" + ("" if unit in ("-", "") else f" {unit}")


def _table(P) -> str:
    lines = ["| parameter | default | allowed | meaning |", "|---|---|---|---|"]
    for row in P.describe():
        desc = row["description"].replace("|", "/")
        lines.append(f"| `{row['name']}` | {_fmt_default(P, row)} | {row['allowed']} | {desc} |")
    return "\n".join(lines)


IDLE_RPM, FACTOR_A = 2700.0, 1.3  # engagement window: > a x idle (domain.md; a assumed) ...
RPM_MAX_TORQUE, RPM_MAX = 8000.0, 14000.0  # ... and below the engine's max-torque speed; governed max


def _engagement(cm, p) -> float | None:
    """FE engagement speed [rpm]: 51CrV4, mu = 0.165, modal spin softening (the solver's
    defaults); None if the shoe never reaches the drum below its first natural frequency."""
    from clutchfem.loadcase import Design

    w, _ = Design(cm, params=p).case().engagement
    return None if w is None else w * 60 / (2 * math.pi)


def _png(concept, p, cm, path: Path) -> Path:
    from clutchfem.geometry import draw_concept

    for dpi in (100, 85, 72):
        with tempfile.TemporaryDirectory() as tmp:
            png, _svg = draw_concept(concept, p, Path(tmp) / "d", None, dpi=dpi)
            if png.stat().st_size <= PNG_LIMIT or dpi == 72:
                path.write_bytes(png.read_bytes())
                return path
    return path  # pragma: no cover


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path(__file__).resolve().parent.parent / "docs")
    ap.add_argument("--no-fe", action="store_true", help="skip the FE engagement column (faster)")
    args = ap.parse_args(argv)

    from clutchfem.geometry import MeshSettings, concepts
    from clutchfem.mesh import mesh_concept

    out: Path = args.out
    img = out / "img"
    img.mkdir(parents=True, exist_ok=True)
    ms = MeshSettings()
    summary = ["| concept | shoes | shoe mass | R_Tp | part mass | elements (sector, default mesh) | "
               "FE engagement |", "|---|---|---|---|---|---|---|"]
    sections = []
    for name, c in concepts().items():
        t0 = time.perf_counter()
        p = c.params()
        cm = mesh_concept(c, p, ms)
        sh = cm.mass["shoe_0"]
        m_shoe = sh["area"] * RHO_STEEL * p.thickness
        m_part = cm.mass["solid"]["area"] * RHO_STEEL * p.thickness * p.n_shoes
        rpm = None if args.no_fe else _engagement(cm, p)
        if args.no_fe:
            rpm_s = "-"
        elif rpm is None or rpm > RPM_MAX:
            rpm_s = f"does not engage below {RPM_MAX:,.0f} rpm" + ("" if rpm is None else f" ({rpm:,.0f} rpm)")
        else:
            ok = ("in window" if FACTOR_A * IDLE_RPM < rpm < RPM_MAX_TORQUE else
                  "below window" if rpm <= FACTOR_A * IDLE_RPM else "above window")
            rpm_s = f"{rpm:,.0f} rpm ({ok})"
        png = _png(c, p, cm, img / f"{name}.png")
        summary.append(f"| [{name}](#{name.replace('.', '')}) | {p.n_shoes} | {m_shoe * 1e3:.1f} g | "
                       f"{sh['radius'] * 1e3:.1f} mm | {m_part * 1e3:.0f} g | {cm.n_elements} | {rpm_s} |")
        doc = inspect.cleandoc(c.parametrisation or "")
        sections.append("\n".join([
            f"## {name}",
            "",
            f"**{c.title}**",
            "",
            f"![{name} at its default parameters](img/{png.name})",
            "",
            "*What the thesis says.* " + c.thesis,
            "",
            "### Parametrisation",
            "",
            doc,
            "",
            "### Parameters",
            "",
            _table(c.Params),
            "",
            f"At the defaults (steel): shoe mass {m_shoe * 1e3:.2f} g, R_Tp {sh['radius'] * 1e3:.2f} mm, part "
            f"mass {m_part * 1e3:.1f} g; default sector mesh {cm.n_elements} P2 elements"
            + ("" if rpm is None else f"; FE engagement {rpm:,.0f} rpm") + ".",
            "",
        ]))
        print(f"{name}: {png} ({png.stat().st_size / 1e3:.0f} kB), {time.perf_counter() - t0:.1f} s",
              file=sys.stderr)
    intro = textwrap.dedent("""\
        # Concept geometries

        *Generated by `scripts/make_concept_docs.py`; do not edit by hand.*

        The thesis (Chalmers 2020, section 4.2) describes five one-piece concepts in words only;
        no figure survives.  Each concept below is a parametric gmsh-OCC model in
        `geometries/<name>.py`, drawn in its final frame (the default **minus** arrangement is the
        mirror image of the canonical plus frame; rotation is counter-clockwise).  Red: contact
        surfaces; hatched: shoe and flexure zones (used for per-shoe mass properties and mesh
        refinement); circle-cross: shoe centroid (R_Tp); triangle: nominal pivot; dashed: drum.

        Conventions shared by all concepts: lengths in metres (shown in mm), angles in degrees;
        60 cc saw defaults (drum radius 34.4 mm, clearance 0.6 mm, axial thickness 11 mm *assumed*,
        bore radius 6.5 mm *assumed*); every parameter has a declared range and every concept has
        consistency rules that raise `ParameterError` naming the parameter and what is allowed
        *before* gmsh runs; the shoe profile can be concentric, eccentric or linear (clearance at
        the root vs the tip); any concept meshes as one cyclic sector (cut through hub material
        only) or the full part.  Concepts 3, 3.1, 4 and 5 are built as one analytic outline
        (lines, arcs and exact tangent fillets: `clutchfem.geometry.sketch`), concepts 1 and 2 by
        booleans of rounded annular sectors.  Concept 2 extends concept 1 and concept 3.1
        extends concept 3 (Python subclasses: shared parameters, checks and construction).
        The mesh is refined in the flexure zones for the thinnest flexure
        (`ConceptParams.flexure_thicknesses`), on the contact surfaces and at every fillet.

        FE engagement: P2 plane stress, 51CrV4, rigid drum, first node of the contact surface to
        close its clearance, modal spin softening on (leaving it out raises the speed by ~1 %);
        "in window" means above 1.3 x the 2700 rpm idle speed = 3510 rpm (the thesis keeps its
        factor a confidential; 1.3 is an assumption, `clutch.analyze.Requirements`) and below the
        8000 rpm of maximum engine torque; the saw's governed maximum is 14 000 rpm.  The
        analytical and solver modules give the full torque curves.

        """)
    text = intro + "\n".join(summary) + "\n\n" + "\n".join(sections)
    (out / "concepts.md").write_text(text)
    print(f"wrote {out / 'concepts.md'}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
