"""A grid study without a TOML file (:func:`run_grid`): every combination of some
parameter values of one concept, on the study engine, as a table."""

from __future__ import annotations

import itertools
import json
from pathlib import Path

import pandas as pd

from ..core import InputError
from ..geometry import MeshSettings, get_concept
from ..loadcase import OperatingPoint
from .hashing import design_hash
from .point import COLUMNS, Settings
from .runner import run_points
from .store import ResultStore

__all__ = ["run_grid"]


def run_grid(concept: str, vary: dict, *, fixed: dict | None = None, mesh_size: float | None = None, op=None,
             store: str | Path, workers: int | None = None, scheduler: str | None = None, progress: bool = False,
             engine=None, a: float = 1.3, b: float = 1.0, min_safety_factor: float = 1.0):
    """A grid study without a TOML file: every combination of ``vary`` of ``concept`` around
    ``fixed``, on the study engine, stored (and resumable) in ``store``.

    Parameters
    ----------
    concept : str
    vary : dict
        ``name -> values`` in the parameters' own units (SI lengths, degrees).
    fixed : dict, optional
        Other parameters of the design.
    mesh_size : float, optional
    op : OperatingPoint, optional
    store : path
        The SQLite store.
    workers, scheduler, progress
        Study engine controls (``workers=0``: in this process).
    engine, a, b, min_safety_factor
        Engine curve and requirement factors.

    Returns
    -------
    pandas.DataFrame
        One row per point in grid order, the varied values in columns named as the
        parameters (their own units) before the answers (engagement, slip, torque, stress,
        masses, status and message).

    Examples
    --------
    >>> import clutchfem as cf, tempfile, pathlib
    >>> df = cf.run_grid("concept1", {"flexure_thickness": [2.0e-3, 2.4e-3]}, mesh_size=3e-3,
    ...                  store=pathlib.Path(tempfile.mkdtemp()) / "s.sqlite", workers=0)
    >>> list(df["status"]), bool(df["engagement_rpm"].is_monotonic_increasing)
    (['ok', 'ok'], True)"""
    c = get_concept(concept)
    P = c.Params
    for name, value in (fixed or {}).items():
        if name not in P.model_fields:
            raise InputError(f"fixed parameter {name!r} is not a parameter of {c.name}")
    settings = Settings(concept=c.name, fixed=tuple(sorted((fixed or {}).items())), op=op or OperatingPoint(),
                        mesh=MeshSettings() if mesh_size is None else MeshSettings(size=mesh_size), engine=engine,
                        a=a, b=b, min_safety_factor=min_safety_factor)
    if not isinstance(vary, dict) or not vary or not all(isinstance(v, (list, tuple)) and v for v in vary.values()):
        raise InputError(f"vary: a dict of parameter name -> list of values (e.g. {{'flexure_thickness': [2.0e-3, "
                         f"2.4e-3]}}), not {type(vary).__name__} {vary!r:.80}")
    names = list(vary)
    points = [dict(zip(names, combo)) for combo in itertools.product(*(list(vary[n]) for n in names))]
    res = run_points(points, settings, store, workers=workers, scheduler=scheduler, progress=progress,
                     source=f"run_grid {c.name}")
    with ResultStore(store, COLUMNS) as st:
        df = st.frame(res.model_version, res.keys)
    keyed = [design_hash(p, settings) for p in points]
    df = df.set_index("design_hash").loc[keyed].reset_index()
    front = pd.DataFrame([{n: json.loads(pj).get(n) for n in names} for pj in df["point_json"]])
    return pd.concat([front, df], axis=1)
