"""Strict JSON out: every document clutchfem writes parses in any language.

Python's ``json`` writes ``NaN`` and ``Infinity`` by default, which is not JSON (JavaScript's,
Go's and Rust's parsers reject it).  :func:`clean` turns non-finite floats into ``null`` and
numpy scalars/arrays into plain Python; :func:`dumps` refuses anything left over
(``allow_nan=False``), so a stray infinity is a bug found in a test, not a file nobody reads.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np


def clean(x):
    """A copy of ``x`` with NaN/inf -> None, numpy scalars/arrays -> Python, tuples -> lists."""
    if isinstance(x, dict):
        return {str(k): clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [clean(v) for v in x]
    if isinstance(x, np.ndarray):
        return clean(x.tolist())
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(float(x)) else None
    if isinstance(x, Path):
        return str(x)
    return x


def dumps(obj, **kw) -> str:
    """Strict JSON text of ``obj`` (cleaned first: NaN and infinities become ``null``, numpy
    scalars and arrays plain numbers and lists, paths strings).

    Parameters
    ----------
    obj : object
        Dicts, lists, tuples, numbers (Python or numpy), arrays, strings, paths, None.
    **kw
        Passed to :func:`json.dumps` (``indent``, ``sort_keys``, ...).

    Returns
    -------
    str
        JSON that parses in any language (``allow_nan=False``: anything left unclean raises).

    Examples
    --------
    >>> import clutchfem as cf, numpy as np
    >>> cf.dumps({"slip_rpm": float("nan"), "rpm": np.array([0.0, 7000.0]), "n": np.int64(3)})
    '{"slip_rpm": null, "rpm": [0.0, 7000.0], "n": 3}'
    """
    return json.dumps(clean(obj), allow_nan=False, **kw)


def write(path: Path, obj, **kw) -> Path:
    """Write strict JSON to ``path`` atomically (a temporary file, then rename)."""
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(dumps(obj, **kw))
    tmp.replace(path)
    return path
