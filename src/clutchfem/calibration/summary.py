"""The summaries of a calibration's posterior (:func:`clutchfem.calibrate`): per input its
mean, 95 % interval, how much the data narrowed it and what it trades off against
(:func:`summarise`); the calibrated answers with bands (:func:`answers_of`); the ranked
explanations in words (:func:`explanations_of`)."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["IDENTIFIED", "REPORTED", "TRADE_OFF", "answers_of", "explanations_of", "show", "summarise"]

#: an input whose 95 % interval the data narrowed by less than this share is not identified
IDENTIFIED = 0.25
#: a posterior correlation at least this strong is named as a trade-off
TRADE_OFF = 0.5
#: the answers reported for the calibrated part: answer -> (label, unit shown, scale to it)
REPORTED = {"engagement_rpm": ("engagement speed (static)", "rpm", 1.0),
            "engagement_rpm_with_ripple": ("engagement speed with ripple", "rpm", 1.0),
            "slip_rpm": ("slip speed (drum held)", "rpm", 1.0),
            "torque_at_max_engine_torque_Nm": ("torque at the rpm of max engine torque", "N m", 1.0),
            "max_von_mises_Pa": ("peak von Mises at engine max", "MPa", 1e-6),
            "mass_kg": ("part mass", "g", 1e3)}


def show(v: float, unit: str, digits: int = 4) -> str:
    """A value in the unit a designer reads (mm, GPa, rpm, N m)."""
    sc, u = {"m": (1e3, "mm"), "Pa": (1e-9, "GPa"), "-": (1.0, "")}.get(unit, (1.0, unit))
    return f"{v * sc:.{digits}g} {u}".rstrip()


def summarise(U, S, prior_S) -> tuple[dict, np.ndarray]:
    k = len(U)
    corr = np.corrcoef(S.T) if k > 1 else np.ones((1, 1))
    corr = np.atleast_2d(np.nan_to_num(corr))
    out = {}
    for j, u in enumerate(U):
        x = S[:, j]
        lo, hi = (float(v) for v in np.quantile(x, [0.025, 0.975]))
        plo, phi = u.prior_ci95()
        narrowed = 1.0 - (hi - lo) / (phi - plo)
        partner = None
        if k > 1:
            c = corr[j].copy()
            c[j] = 0.0
            i = int(np.argmax(np.abs(c)))
            if abs(c[i]) >= TRADE_OFF:
                partner = {"name": U[i].name, "correlation": float(c[i])}
        w = u.hi - u.lo
        edge = None
        if u.kind == "uniform":  # a posterior whose 95 % interval reaches the support's bound from inside
            if lo - u.lo < 0.01 * w and np.mean(x < u.lo + 0.05 * w) > 0.1:
                edge = "lo"
            elif u.hi - hi < 0.01 * w and np.mean(x > u.hi - 0.05 * w) > 0.1:
                edge = "hi"
        else:
            if np.mean(x < u.lo + 0.05 * w) > 0.1:
                edge = "lo"
            elif np.mean(x > u.hi - 0.05 * w) > 0.1:
                edge = "hi"
        out[u.name] = {"mean": float(x.mean()), "sd": float(x.std()), "ci95": [lo, hi], "unit": u.unit,
                       "drawn": u.drawn, "deviation_mean": float(x.mean() - u.drawn), "prior": u.to_json(),
                       "narrowed": float(narrowed), "identified": bool(narrowed >= IDENTIFIED),
                       "trades_off_with": partner, "at_edge": edge, "moved_sigmas": float((x.mean() - u.mean) / u.sd)}
    return out, corr


def answers_of(fw, S, M, design, model) -> dict:
    """The calibrated part's answers: over the posterior samples, each with the model's
    band drawn as a normal of +-2 sigma; the drawn design's (the base of the region)."""
    ans, ok = fw(S, [a for a in REPORTED if a in fw.answers])
    base = {u.name: u.drawn for u in fw.uncertain}
    nom, _ = fw(np.array([[base[u.name] for u in fw.uncertain]]), [a for a in REPORTED if a in fw.answers])
    rng = np.random.default_rng(7)
    out = {}
    for a, v in ans.items():
        v = v[ok & np.isfinite(v)]
        if not len(v):
            continue
        rep = v + rng.normal(0.0, 1.0, len(v)) * fw.sigma_model(a, v)
        mean = float(v.mean())
        label, unit, sc = REPORTED[a]
        meas = [m.value for m in M if m.answer == a and not m.is_dimension]
        out[a] = {"label": label, "mean": mean, "ci95": [float(q) for q in np.quantile(rep, [0.025, 0.975])],
                  "band": float(fw.rel_band[a] * abs(mean)), "unit": {"max_von_mises_Pa": "Pa", "mass_kg": "kg"}.get(
                      a, unit), "measured": meas[0] if meas else None,
                  "nominal": float(nom[a][0]) if math.isfinite(nom[a][0]) else None}
    return out


def explanations_of(U, posterior, consistent) -> list[str]:
    """The inputs ranked by how far the data moved them from their prior, in words."""
    order = sorted(U, key=lambda u: -abs(posterior[u.name]["moved_sigmas"]))
    out = []
    for u in order:
        p = posterior[u.name]
        lo, hi = p["ci95"]
        txt = f"{u.name} {show(p['mean'], u.unit)} (95 % {show(lo, u.unit)} .. {show(hi, u.unit)}"
        if u.kind == "normal" and u.name not in ("mu",):
            dev = p["mean"] - u.drawn
            txt += f"; {show(abs(dev), u.unit, 2)} {'above' if dev > 0 else 'below'} the drawn {show(u.drawn, u.unit)}"
        txt += f"; narrowed {100 * p['narrowed']:.0f} % from its prior"
        if not p["identified"]:
            txt += "; NOT IDENTIFIED by these data"
            if p["trades_off_with"]:
                t = p["trades_off_with"]
                txt += f": it trades off against {t['name']} (correlation {t['correlation']:+.2f})"
        elif p["trades_off_with"]:
            t = p["trades_off_with"]
            txt += f"; correlated with {t['name']} ({t['correlation']:+.2f})"
        out.append(txt + ")")
    if not consistent:
        out.insert(0, "no combination of the inputs within their priors explains every measurement (see the checks)")
    return out
