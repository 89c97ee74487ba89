"""Repeated readings of one answer on one part: combined into one measurement, so that the
model's error (one and the same for all of them) enters once; readings that disagree beyond
their uncertainties said to."""

from __future__ import annotations

import numpy as np

from .inputs import Measurement

__all__ = ["READINGS_P", "combine_readings"]

#: repeated readings whose chi-square about their mean has a p-value below this disagree
READINGS_P = 0.01


def combine_readings(measured: list[Measurement]) -> tuple[list[Measurement], list[str]]:
    """The repeated readings of one answer on one part combined into one measurement.

    The readings y_i (standard uncertainties u_i) of one answer f of one part, whose model
    error e is common to all of them, have the joint likelihood N(y | f + e, diag(u^2)); its
    dependence on f + e is that of their weighted mean ybar = sum(y_i/u_i^2)/sum(1/u_i^2)
    with uncertainty (sum 1/u_i^2)^-1/2 -- so the posterior is the same with the one combined
    measurement, and the model's error enters once (counting it once per reading would
    narrow the posterior as if the model erred anew each time).  Readings whose scatter about
    their mean exceeds their uncertainties (a chi-square p-value below :data:`READINGS_P`)
    are said to disagree.

    Parameters
    ----------
    measured : list of Measurement

    Returns
    -------
    (list of Measurement, list of str)
        The measurements, one per answer (or dimension) and part, in the order first given;
        and the notes on readings that disagree.

    Examples
    --------
    >>> import clutchfem as cf
    >>> from clutchfem.calibration import combine_readings
    >>> ms, notes = combine_readings([cf.parse_measured(t) for t in ("slip=7500rpm+-40rpm", "slip=7540rpm+-40rpm")])
    >>> [(m.value, round(m.sd, 3), m.readings) for m in ms], notes
    ([(7520.0, 28.284, 2)], [])
    """
    from scipy.stats import chi2

    groups: dict = {}
    for m in measured:
        groups.setdefault((m.part, m.name, m.at_rpm), []).append(m)
    out, notes = [], []
    for ms in groups.values():
        if len(ms) == 1:
            out.append(ms[0])
            continue
        y = np.array([m.value for m in ms])
        w = 1.0 / np.array([m.sd for m in ms]) ** 2
        mean = float((w * y).sum() / w.sum())
        sd = float(w.sum() ** -0.5)
        q = float((w * (y - mean) ** 2).sum())
        p = float(chi2.sf(q, len(ms) - 1))
        text = "; ".join(m.text for m in ms)
        if p < READINGS_P:
            notes.append(f"the {len(ms)} readings {text} disagree beyond their uncertainties (chi-square "
                         f"{q:.1f} on {len(ms) - 1} degrees of freedom, p = {p:.2g}): the uncertainties are too "
                         "small or the part changed between them; their weighted mean is used")
        out.append(Measurement(ms[0].name, mean, sd, ms[0].unit, ms[0].at_rpm, text, ms[0].part, len(ms)))
    return out, notes
