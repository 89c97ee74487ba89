"""A concept's rules learned as linear constraints of a gradient step: where a step's design
is refused by a rule (e.g. concept 4's beam that must end below its shoe), the refused
parameter's admissible end is found by bisection of the rule check alone -- no analysis, no
design counted -- and linearised in the other parameters, so that the step's subproblem can
keep inside the rules (:mod:`.gradient`).

The evaluator ``ev`` given to these functions answers ``ev.refused(x)`` (the name of the
parameter a rule refuses at normalised x, or None), ``ev.grid_x(x)`` (x on the value grid),
``ev.space.names`` and counts its rule checks in ``ev.rule_checks``.
"""

from __future__ import annotations

import numpy as np

from .sqp import subproblem

#: margin kept from a linearised rule of the concept (share of the range)
RULE_MARGIN = 2e-3


def admissible_step(ev, g, J, c, B, x, delta, rho, rules: dict) -> tuple[np.ndarray, np.ndarray]:
    """The subproblem's step, kept inside the concept's rules (module docstring).  Where the
    step's design is refused on a free parameter k, the rule is linearised -- the admissible
    end of x_k at x and at x + h e_j for the others, by bisection of the rule check alone (no
    analysis) -- and enters the subproblem as x_k + d_k <= end(x) + grad end . d (or >=),
    which is solved again; ``rules`` keeps the learned rules (re-linearised at each iterate).
    A refusal this does not resolve shortens the step to the rules' admissible share."""
    for _ in range(4):  # the trust box, halved while the rules refuse what the cuts let through
        lo, hi = np.maximum(-delta, -x), np.minimum(delta, 1.0 - x)
        for _ in range(len(x) + 2):
            d, lam = subproblem(g, J, c, B, lo, hi, rho, list(rules.values()))
            xt = ev.grid_x(np.clip(x + d, 0.0, 1.0))
            name = ev.refused(xt)
            if name is None:
                return d, lam
            k = ev.space.names.index(name) if name in ev.space.names else None
            sign = None if k is None else side(ev, xt, k)
            if sign is None:  # not one free parameter's own limit: a smaller box
                break
            key = (k, sign)
            if key in rules:  # the rule is curved: a cut linearised where the step crosses it
                a_ = bisect(lambda t: ev.refused(x + t * d) is None, 0.0, 1.0, 30)
                ev.rule_checks += 30
                rules[key] = rule(ev, x, *key, at=x + a_ * d)
            else:
                rules[key] = rule(ev, x, *key)
        delta *= 0.5
    a_ = bisect(lambda t: ev.refused(x + t * d) is None, 0.0, 1.0, 30)  # the share of the last step admitted
    ev.rule_checks += 30
    return 0.98 * a_ * d, lam


def side(ev, xt: np.ndarray, k: int) -> float | None:
    """Which end of parameter k refuses the design ``xt``: +1 an upper end (a smaller x_k is
    admitted), -1 a lower end, None: no value of x_k nearby is admitted."""
    for h in (0.005, 0.02, 0.05, 0.1, 0.2):
        for sign in (1.0, -1.0):
            probe = xt.copy()
            probe[k] = xt[k] - sign * h
            ev.rule_checks += 1
            if 0.0 <= probe[k] <= 1.0 and ev.refused(probe) is None:
                return sign
    return None


def rule(ev, x: np.ndarray, k: int, sign: float, at: np.ndarray | None = None) -> tuple[np.ndarray, float]:
    """A rule of parameter k (``sign`` +1: an upper end, -1: a lower end), its end linearised
    at ``at`` (default x): the row a and bound b of a . d >= b for the step d from x
    (:func:`admissible_step`)."""
    p = x if at is None else np.asarray(at, dtype=float)
    n, h = len(x), 1e-3
    end0 = end(ev, p, k, sign)
    end0 = p[k] if end0 is None else end0
    grad = np.zeros(n)
    for j in range(n):
        if j == k:
            continue
        step = h if p[j] + h <= 1.0 else -h
        pj = p.copy()
        pj[j] += step
        end_j = end(ev, pj, k, sign)
        if end_j is not None:
            grad[j] = (end_j - end0) / step
    # sign * (end0 + grad . (x + d - p) - x_k - d_k) >= margin
    row = sign * (grad - np.eye(n)[k])
    return row, RULE_MARGIN - sign * (end0 + grad @ (x - p) - x[k])


def end(ev, p: np.ndarray, k: int, sign: float) -> float | None:
    """How far x_k may go (towards 1 for ``sign`` +1, towards 0 for -1) with the others at p:
    outwards from p_k where p is admitted, else back inwards to the first admitted value
    (None: none within 0.4 of the range)."""
    far = 1.0 if sign > 0 else 0.0
    probe = p.copy()

    def admitted(v: float) -> bool:
        probe[k] = v
        ev.rule_checks += 1
        return ev.refused(probe) is None

    if admitted(p[k]):
        if admitted(far):
            return far
        a, b = p[k], far
    else:
        a = next((v for v in (p[k] - sign * h for h in (0.005, 0.02, 0.05, 0.1, 0.2, 0.4))
                  if 0.0 <= v <= 1.0 and admitted(v)), None)
        if a is None:
            return None
        b = p[k]
    return bisect(admitted, a, b, 25)


def bisect(admitted, ok: float, bad: float, steps: int) -> float:
    """The admitted end of [ok, bad] after ``steps`` halvings, ``admitted(ok)`` true and
    ``admitted(bad)`` false (a rule check of the concept: no analysis)."""
    for _ in range(steps):
        m = 0.5 * (ok + bad)
        ok, bad = (m, bad) if admitted(m) else (ok, m)
    return ok
