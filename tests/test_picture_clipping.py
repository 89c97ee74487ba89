"""Issue 37, pictures: a marked point cut by its axes' edge is recorded as clipped (the
arc-stress plot's peak at the engine's maximum speed drawn half outside), every axes records
its view limits (a colour bar's range: it must reach the marked peak), and the app's field
picture's colour bar reaches its marked peak with no text cut."""

from __future__ import annotations

import numpy as np
import pytest

import clutchfem as cf
from clutchfem.core import figure, figure_record, save_figure
from clutchfem.core.figures import RPM_MARGIN, clipped_markers


def _marked(xmax: float):
    fig, ax = figure(figsize=(4, 3), layout="constrained")
    rpm = np.linspace(0, 14000, 15)
    ax.plot(rpm, rpm / 10, "r-")
    ax.plot([14000], [1400], "ko", mfc="none", ms=8, mew=2, label="peak at 14000 rpm")
    ax.set_xlim(0, xmax)
    ax.set_ylim(0, 1600)
    ax.set_xlabel("engine speed [rpm]")
    ax.set_ylabel("stress [MPa]")
    return fig


def test_a_marker_on_the_axes_edge_is_recorded_as_cut(tmp_path):
    rec = figure_record(save_figure(_marked(14000), tmp_path / "cut.png"))
    assert any("peak at 14000 rpm" in c and "cut by its axes" in c for c in rec["clipped"]), rec["clipped"]
    assert rec["axes"][0]["xlim"] == [0.0, 14000.0]


def test_the_report_margin_keeps_the_marker_whole(tmp_path):
    fig = _marked(RPM_MARGIN * 14000)  # the arc-stress plot's rpm axis
    fig.canvas.draw()
    assert clipped_markers(fig) == []
    assert figure_record(save_figure(fig, tmp_path / "whole.png"))["clipped"] == []


def test_a_colour_bar_records_its_range(tmp_path):
    fig, ax = figure(figsize=(4, 3), layout="constrained")
    im = ax.imshow(np.arange(12.0).reshape(3, 4), vmin=0, vmax=20)
    fig.colorbar(im, ax=ax, label="von Mises [MPa]")
    rec = figure_record(save_figure(fig, tmp_path / "cb.png"))
    cb = next(a for a in rec["axes"] if a["ylabel"] == "von Mises [MPa]")
    assert max(cb["ylim"]) == pytest.approx(20.0)


@pytest.mark.slow
def test_the_app_field_picture_reaches_its_peak_and_cuts_no_text():
    """The marked peak (the raw vertex maximum, above the averaged colours) is inside the
    colour bar's range; the peak label and the ticks stay in the picture."""
    from clutchfem.app.figures import field_png

    d = cf.Design.from_concept("concept4", mesh=cf.MeshSettings(size="2.5mm"))
    res = d.sweep("14000")
    png, info = field_png(d, res, 14000)
    assert png[:4] == b"\x89PNG"
    assert info["colour_bar_MPa"][1] >= info["peak_MPa"]
    assert info["peak_MPa"] == pytest.approx(float(res.curve["max_von_mises_Pa"].iloc[0]) / 1e6, rel=0.02)
    assert info["clipped"] == []
