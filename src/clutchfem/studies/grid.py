"""A grid study without a TOML file (:func:`run_grid`): every combination of some
parameter values around a design, on the study engine, as a table."""

from __future__ import annotations

import itertools
import json
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from ..core import InputError, clean
from ..evaluation import COLUMNS, EvalSettings, ResultStore, RunResult, design_hash, run_points

__all__ = ["GridResult", "run_grid"]


@dataclass(frozen=True)
class GridResult:
    """A grid study's rows (:func:`run_grid`).

    Attributes
    ----------
    frame : pandas.DataFrame
        One row per grid point in grid order: the varied values in columns named as the
        parameters (their own SI units), then the answers (engagement, slip, torque,
        stress, masses, status and message).
    vary : dict
        ``name -> values`` as given.
    run : RunResult
        What the study engine did (points, ok, refused, failed, the store).

    Examples
    --------
    >>> import pandas as pd
    >>> from clutchfem.studies import GridResult
    >>> g = GridResult(frame=pd.DataFrame({"flexure_thickness": [2e-3], "status": ["ok"]}),
    ...                vary={"flexure_thickness": [2e-3]}, run=None)
    >>> len(g), g.ok["flexure_thickness"].tolist()
    (1, [0.002])
    """

    frame: pd.DataFrame = field(repr=False)
    vary: dict
    run: RunResult | None

    def __len__(self) -> int:
        return len(self.frame)

    @property
    def ok(self) -> pd.DataFrame:
        """The rows with an answer (status ``ok``)."""
        return self.frame[self.frame["status"] == "ok"]

    def to_json(self) -> dict:
        """The varied values, the run's counts and the rows (JSON-ready)."""
        return clean({"vary": self.vary, "run": self.run.to_json() if self.run is not None else None,
                      "rows": self.frame.to_dict("records")})


def run_grid(design, vary: dict, *, store: str | Path, engine=None, requirements=None,
             min_safety_factor: float = 1.0, workers: int | None = None, scheduler: str | None = None,
             progress: bool = False) -> GridResult:
    """A grid study without a TOML file: every combination of ``vary`` around ``design``, on
    the study engine, stored (and resumable) in ``store``.

    Parameters
    ----------
    design : Design
        The base design (a concept's :class:`~clutchfem.Design`): its parameters, operating
        point and mesh settings hold for every point but the varied parameters.
    vary : dict
        ``name -> values`` in the parameters' own units (SI lengths, degrees).
    store : path
        The SQLite store.
    engine : EngineCurve, optional
        The engine's full-throttle curve (default: the built-in ASSUMED curve).
    requirements : Requirements, optional
        The requirement factors a and b (default: 1.3 and 1.0, ASSUMED).
    min_safety_factor : float
        The yield safety factor a row's ``feasible`` flag asks for.
    workers, scheduler, progress
        Study engine controls (``workers=0``: in this process).

    Returns
    -------
    GridResult
        One row per point in grid order (``.frame``), the run's counts (``.run``).

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> d = cf.Design.from_concept("concept1", mesh=cf.MeshSettings(size="3mm"))
    >>> g = cf.run_grid(d, {"flexure_thickness": [2.0e-3, 2.4e-3]},
    ...                 store=pathlib.Path(tempfile.mkdtemp()) / "s.sqlite", workers=0)
    >>> list(g.frame["status"]), bool(g.frame["engagement_rpm"].is_monotonic_increasing)
    (['ok', 'ok'], True)"""
    es = EvalSettings.from_design(design, engine=engine, requirements=requirements,
                                  min_safety_factor=min_safety_factor)
    settings = es.study()
    P = type(design.params)
    if not isinstance(vary, dict) or not vary or not all(isinstance(v, (list, tuple)) and v for v in vary.values()):
        raise InputError(f"vary: a dict of parameter name -> list of values (e.g. {{'flexure_thickness': [2.0e-3, "
                         f"2.4e-3]}}), not {type(vary).__name__} {vary!r:.80}")
    for name in vary:
        if name not in P.model_fields:
            raise InputError(f"vary: {name!r} is not a parameter of {design.name}; its parameters: "
                             + ", ".join(P.model_fields))
    names = list(vary)
    points = [dict(zip(names, combo)) for combo in itertools.product(*(list(vary[n]) for n in names))]
    res = run_points(points, settings, store, workers=workers, scheduler=scheduler, progress=progress,
                     source=f"run_grid {design.name}")
    with ResultStore(store, COLUMNS, context=res.context_hash) as st:
        df = st.frame(res.model_version, res.keys)
    keyed = [design_hash(p, settings) for p in points]
    df = df.set_index("design_hash").loc[keyed].reset_index()
    front = pd.DataFrame([{n: json.loads(pj).get(n) for n in names} for pj in df["point_json"]])
    return GridResult(frame=pd.concat([front, df], axis=1), vary=dict(vary), run=res)
