"""Discovery of concept geometries: one Python file per concept in ``geometries/``.

A file ``geometries/<stem>.py`` defines ``CONCEPT``, an instance of a
:class:`~clutchfem.geometry.Concept` subclass.  Search path, first hit wins:
``$CLUTCHFEM_GEOMETRIES`` (os.pathsep-separated folders), the repository's ``geometries/``
(editable install) and the copy packaged in the wheel (``clutchfem/_geometries``).
Dropping a new file into one of these folders adds a concept; nothing else to register.

A file that fails to load (a syntax error, an import it lacks, no ``CONCEPT``) costs only
itself: it is named in one warning, ``clutchfem geometry --list`` shows it with its error,
and asking for it by name (its file stem) is refused with that error; every other concept,
the built-in ones included, works as before (issue 24: one broken plug-in in
``$CLUTCHFEM_GEOMETRIES`` broke every command).
"""

from __future__ import annotations

import importlib.util
import logging
import os
import sys
from functools import lru_cache
from pathlib import Path

from ..core import ParameterError
from .concept import Concept

_PKG = Path(__file__).resolve().parent.parent
log = logging.getLogger("clutchfem")
#: concept files that failed to load: path -> the error (each warned about once)
_BROKEN: dict[str, str] = {}


def search_path() -> list[Path]:
    dirs = [Path(p) for p in os.environ.get("CLUTCHFEM_GEOMETRIES", "").split(os.pathsep) if p]
    dirs += [_PKG.parent.parent / "geometries", _PKG / "_geometries"]
    return [d for d in dirs if d.is_dir()]


@lru_cache(maxsize=None)
def load_concept_file(path: str) -> Concept:
    spec = importlib.util.spec_from_file_location(f"clutchfem_geometries.{Path(path).stem}", path)
    mod = importlib.util.module_from_spec(spec)
    assert spec.loader is not None
    sys.modules[spec.name] = mod  # lets inspect/dataclasses find the module (cache hashing)
    try:
        spec.loader.exec_module(mod)
    except BaseException:
        sys.modules.pop(spec.name, None)
        raise
    concept = getattr(mod, "CONCEPT", None)
    if not isinstance(concept, Concept):
        raise TypeError(f"{path} does not define CONCEPT = <Concept subclass instance>")
    return concept


def concepts() -> dict[str, Concept]:
    """All concepts found, by name, in name order.

    Returns
    -------
    dict of str to Concept
        Every concept file of the search path (``$CLUTCHFEM_GEOMETRIES``, the repository's
        ``geometries/``, the copy in the wheel) that loads; first hit wins.

    Examples
    --------
    >>> import clutchfem as cf
    >>> [n for n in cf.concepts() if n in ("concept1", "concept4")]
    ['concept1', 'concept4']
    """
    found: dict[str, Concept] = {}
    for d in search_path():
        for f in sorted(d.glob("*.py")):
            if f.name.startswith("_"):
                continue
            try:
                c = load_concept_file(str(f))
            except (Exception, SystemExit) as exc:  # a plug-in's failure costs only itself
                if str(f) not in _BROKEN:
                    _BROKEN[str(f)] = f"{type(exc).__name__}: {exc}"
                    log.warning(f"concept file {f} does not load and is left out ({_BROKEN[str(f)]})")
                continue
            found.setdefault(c.name, c)
    return dict(sorted(found.items()))


def broken_concepts() -> dict[str, str]:
    """The concept files of the search path that fail to load: {path: error}.

    Returns
    -------
    dict of str to str
        Empty when every concept file loads.

    Examples
    --------
    >>> from clutchfem.geometry import broken_concepts
    >>> broken_concepts()
    {}
    """
    concepts()
    dirs = set(search_path())
    return {p: e for p, e in _BROKEN.items() if Path(p).parent in dirs}


def get_concept(name: str) -> Concept:
    """A concept by name.

    Parameters
    ----------
    name : str
        ``"concept4"``, ``"4"``, ``"concept3.1"``, ``"3.1"`` all work.

    Returns
    -------
    Concept
        The geometry plug-in: ``Params`` (its parameter set with units and ranges),
        ``params(**values)``, ``build()``.

    Examples
    --------
    >>> import clutchfem as cf
    >>> c = cf.get_concept("4")
    >>> c.name, c.params(flexure_thickness="2mm").flexure_thickness
    ('concept4', 0.002)
    """
    allc = concepts()
    if not isinstance(name, str):
        raise ParameterError("concept", name, "a concept name (text: '4' or 'concept4'), one of " + ", ".join(allc))
    key = name.strip().lower()
    for cand in (key, f"concept{key}", key.replace("_", ".")):
        if cand in allc:
            return allc[cand]
    for path, error in broken_concepts().items():
        if Path(path).stem.lower() in (key, f"concept{key}"):
            raise ParameterError("concept", name, f"a concept whose file loads: {path} fails to load ({error}); "
                                 "the others: " + ", ".join(allc))
    raise ParameterError("concept", name, "one of " + ", ".join(allc))
