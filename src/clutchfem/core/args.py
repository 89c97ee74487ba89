"""Checking the types of public API arguments: one refusal that names the argument, the
type it got and what it takes (issue 24: ``analyze(d, engine="x.csv")`` and
``d.sweep("8000", mu="abc")`` were raw ``AttributeError``/``ValueError`` tracebacks)."""

from __future__ import annotations

import os
from pathlib import Path

from .errors import ParameterError

__all__ = ["as_bool", "as_path"]


def as_path(value, name: str, what: str = "a file path") -> Path:
    """``value`` as a :class:`~pathlib.Path` (a ``str`` or ``os.PathLike``), else a
    :class:`ParameterError` naming the argument ``name``.

    >>> as_path("out/c1", "out")
    PosixPath('out/c1')
    """
    if isinstance(value, (str, os.PathLike)) and str(value).strip():
        return Path(value)
    raise ParameterError(name, value if isinstance(value, str) else type(value).__name__, f"{what} (a str or Path)")


def as_bool(value, name: str) -> bool:
    """``value`` if it is a bool (``errors="no"`` would be true), else a
    :class:`ParameterError` naming the argument.

    >>> as_bool(False, "errors")
    False
    """
    if isinstance(value, bool):
        return value
    raise ParameterError(name, value, "True or False")
