"""A package's public names imported on first use (PEP 562): one ``__getattr__``/``__dir__`` pair."""

from __future__ import annotations

import importlib
from typing import Any, Callable


def lazy_names(package: str, namespace: dict, names: dict[str, str | None]) -> tuple[Callable, Callable]:
    """The ``__getattr__`` and ``__dir__`` of a package whose names load on first use.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    namespace : dict
        The package's ``globals()``: each name is kept there after its first use.
    names : dict
        Public name -> the submodule that holds it (None: the name is a submodule itself).

    Returns
    -------
    tuple of callable
        ``(__getattr__, __dir__)`` to assign at the package's top level.

    Examples
    --------
    >>> ns = {}
    >>> get, ls = lazy_names("clutchfem.core", ns, {"parse_quantity": "units"})
    >>> get("parse_quantity")("2mm", "m"), ls()
    (0.002, ['parse_quantity'])
    """

    def __getattr__(name: str) -> Any:
        if name not in names:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        module = names[name]
        mod = importlib.import_module(f"{package}.{module or name}")
        value = mod if module is None else getattr(mod, name)
        namespace[name] = value
        if module is not None and names.get(module) == module:
            # a public name that is also its module's name (``slip_heat`` in ``slip_heat.py``):
            # importing the module set the package's attribute to the module; the name wins
            namespace[module] = getattr(mod, module)
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(names))

    return __getattr__, __dir__
