"""Checks of the picture rule (:mod:`clutchfem.core.figures`) on a written PNG.

* :func:`rule` -- the PNG carries its record; no legend covers a data point; no text leaves
  the figure and no annotation its axes; every axes that
  shows numbers on an axis names its quantity with a unit ``[...]`` (in the axis label or
  the title) or is a plain count or index;
* :func:`number` -- the number a picture shows after a label (a regular expression), with the
  digits it shows;
* :func:`agrees` -- that number equals the JSON value rounded to those digits.
"""

from __future__ import annotations

import math
import re

from clutchfem.core import figure_record

__all__ = ["agrees", "number", "rule", "texts"]

NUM = r"([-+]?\d[\d,]*(?:\.\d+)?)"


def texts(rec: dict) -> list[str]:
    """Every text of a record: the figure's, then each axes' title, labels, texts, legend."""
    out = list(rec["figure"])
    for lg in rec.get("figure_legends", []):
        out += lg
    for ax in rec["axes"]:
        out += [ax["title"], ax["xlabel"], ax["ylabel"], *ax["texts"], *ax["legend"]]
    return [t for t in out if t]


def rule(png, *, units_exempt: tuple[str, ...] = ()) -> dict:
    """The record of ``png``, after checking the rule (module docstring); ``units_exempt``:
    axis labels that need no unit (a count: 'parts', 'design evaluated (#)')."""
    rec = figure_record(png)
    assert rec is not None, f"{png}: no clutchfem record (drawn without core.figures.save_figure)"
    assert all(n == 0 for n in rec["legend_covers"]), f"{png}: a legend covers data points {rec['legend_covers']}"
    assert not rec.get("clipped", []), f"{png}: texts a reader sees cut: {rec['clipped']}"
    for ax in rec["axes"]:
        for tick, label in (("xticks", "xlabel"), ("yticks", "ylabel")):
            if not ax[tick] or not ax[label] or any(e in ax[label] for e in units_exempt):
                continue
            assert re.search(r"\[[^\]]+\]", ax[label]) or re.search(r"\[[^\]]+\]", ax["title"]), \
                f"{png}: axis '{ax[label]}' (title '{ax['title']}') states no unit"
    return rec


def number(rec: dict, label: str) -> tuple[float, int]:
    """(value, decimals shown) of the first number after the regular expression ``label`` in
    any text of the record."""
    for t in texts(rec):
        m = re.search(label + r"\s*" + NUM, t)
        if m:
            s = m.group(1).replace(",", "")
            return float(s), len(s.split(".")[1]) if "." in s else 0
    raise AssertionError(f"no number after {label!r} in {texts(rec)}")


def agrees(rec: dict, label: str, value: float, scale: float = 1.0) -> float:
    """The picture shows ``value * scale`` after ``label`` to the digits it shows; returns it."""
    shown, dec = number(rec, label)
    want = round(value * scale, dec)
    assert math.isclose(shown, want, abs_tol=0.51 * 10 ** -dec), \
        f"picture shows {shown} after {label!r}, the JSON says {value * scale} ({want} at {dec} decimals)"
    return shown
