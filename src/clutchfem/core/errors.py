"""Exception hierarchy of clutchfem.

Every error a user can provoke with bad input is a :class:`ClutchfemError`; the CLI prints
its message (never a traceback).  Messages name the offending input, its value and the
allowed range or form.
"""

from __future__ import annotations

from typing import Any


class ClutchfemError(Exception):
    """Base class of all errors that clutchfem raises on purpose: a refusal whose message
    names the input, its value and what is allowed (never a traceback in the CLI).

    Examples
    --------
    >>> import clutchfem as cf
    >>> try:
    ...     cf.get_concept("concept9")
    ... except cf.ClutchfemError as e:
    ...     print(type(e).__name__)
    ParameterError
    """


class ParameterError(ClutchfemError, ValueError):
    """A parameter is outside its declared range or inconsistent with others.

    ``name`` is the parameter, ``value`` its value, ``allowed`` a human-readable statement of
    what is allowed (range with units, or the relation it must satisfy); ``shown`` the value
    as the message shows it (as the user typed it, or in the parameter's display unit, e.g.
    ``19 mm``; default: ``repr(value)``).

    Examples
    --------
    >>> import clutchfem as cf
    >>> try:
    ...     cf.get_concept("concept1").params(flexure_thickness="9mm")
    ... except cf.ParameterError as e:
    ...     print(e.name, "|", e.shown, "|", e.allowed)
    flexure_thickness | 9 mm | a number in [0.3 mm, 6 mm] (flexure thickness)
    """

    def __init__(self, name: str, value: Any, allowed: str, context: str | None = None, shown: str | None = None):
        self.name = name
        self.value = value
        self.allowed = allowed
        self.context = context
        self.shown = shown if shown is not None else repr(value)
        msg = f"parameter '{name}' = {self.shown} is not allowed: {allowed}"
        if context:
            msg = f"{context}: {msg}"
        super().__init__(msg)


class InputError(ClutchfemError, ValueError):
    """Bad user input that is not a single named parameter (files, specs, tables).

    Examples
    --------
    >>> import clutchfem as cf
    >>> issubclass(cf.InputError, cf.ClutchfemError)
    True
    """


class GeometryError(ClutchfemError):
    """gmsh could not build or mesh a geometry; carries the parameter set.

    Examples
    --------
    >>> import clutchfem as cf
    >>> print(cf.GeometryError("boolean cut failed", params={"shoe_arc": 80}))
    boolean cut failed
    parameter set: {'shoe_arc': 80}
    """

    def __init__(self, message: str, params: Any = None):
        self.params = params
        if params is not None:
            message = f"{message}\nparameter set: {params}"
        super().__init__(message)


class MeshError(ClutchfemError):
    """A mesh (generated or user supplied) is unusable: missing groups, not planar, inverted.

    Examples
    --------
    >>> import clutchfem as cf
    >>> issubclass(cf.MeshError, cf.ClutchfemError)
    True
    """


class SolverError(ClutchfemError):
    """A numerical solve failed (singular system, contact iteration without convergence).

    Examples
    --------
    >>> import clutchfem as cf
    >>> issubclass(cf.SolverError, cf.ClutchfemError)
    True
    """


class EquilibriumError(SolverError):
    """A solved state failed its equilibrium check (the residual of K u = f past its bound):
    the answer would be wrong, so it is refused (``analyze`` retries a pre-stress Ritz space
    that misses with the per-speed factorisation, :class:`clutchfem.softening.PrestressExact`).

    Examples
    --------
    >>> from clutchfem.core import EquilibriumError, SolverError
    >>> issubclass(EquilibriumError, SolverError)
    True
    """
