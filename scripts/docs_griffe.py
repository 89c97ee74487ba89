"""Two griffe extensions for the documentation site (mkdocs.yml: ``mkdocstrings`` -> ``python``
-> ``options`` -> ``extensions``).  griffe reads the source without importing it; in two
places that is not what the code does at run time, and these say what it does.

:class:`ParamSetSignatures`: the keyword signature of a parameter set.  Every parameter set
(``clutchfem.core.params.ParamSet``, a frozen pydantic model) takes its fields as keywords:
``cf.Material(name="my steel", E="200GPa")``.  In the source its ``__init__`` is
``ParamSet.__init__(self, **values)`` (unit strings are parsed there, then pydantic checks
each field), so griffe sees only ``**values`` and takes the numpydoc ``Parameters`` section
(one entry per field) for parameters the signature does not have.  This gives each such
class the signature pydantic builds at run time: one keyword-only parameter per field, its
annotation and its default (the first argument of ``param(...)`` or ``choice(...)``),
inherited fields first.  Only classes that derive from ``ParamSet`` and have no ``__init__``
of their own, or one that hands ``**values`` on (``OperatingPoint``'s), are touched.

:class:`SphinxRoles`: the docstrings cross-reference with Sphinx roles (``:func:`analyze```,
``:class:`~clutchfem.loadcase.Design```, ``:mod:`.dxf```), which Markdown would show as
text.  Each role becomes an optional cross-reference (mkdocs-autorefs): a link where the
site documents the object, else the name in code, without a warning either way.  The
target is found as Sphinx finds it (relative to the docstring's object and module, ``~``
shows the last part only) and then where it is *defined*: the packages re-export their names
lazily (PEP 562), which griffe cannot follow, so a name griffe cannot reach is imported.
"""

from __future__ import annotations

import importlib
import inspect
import re
import sys
from pathlib import Path
from typing import Any

import griffe

SRC = Path(__file__).resolve().parents[1] / "src"
if str(SRC) not in sys.path:
    sys.path.insert(0, str(SRC))  # the checkout's source, as mkdocstrings reads it

#: where ParamSet is defined, and the lazy package name the stages import it by (which griffe,
#: reading ``clutchfem.core``'s lazy name table statically, cannot follow)
PARAMSET_PATHS = {"clutchfem.core.params.ParamSet", "clutchfem.core.ParamSet"}
FIELD_HELPERS = {"param", "choice", "Field"}


def _bases(cls: griffe.Class, collection: griffe.ModulesCollection) -> list[griffe.Class | str]:
    """The class's bases: a class griffe can reach, or the path of ParamSet itself."""
    bases: list[griffe.Class | str] = []
    for expr in cls.bases:
        path = expr.canonical_path if isinstance(expr, griffe.Expr) else str(expr)
        if path in PARAMSET_PATHS:
            bases.append(path)
            continue
        try:
            base = collection.get_member(path)
            base = base.final_target if base.is_alias else base
        except (KeyError, ValueError, griffe.AliasResolutionError, griffe.CyclicAliasError):
            continue
        if base.is_class:
            bases.append(base)
    return bases


def _lineage(cls: griffe.Class, collection: griffe.ModulesCollection) -> list[griffe.Class] | None:
    """The ParamSet subclasses from ParamSet down to ``cls``, or None if ``cls`` is no ParamSet."""
    for base in _bases(cls, collection):
        if isinstance(base, str):
            return [cls]
        above = _lineage(base, collection)
        if above is not None:
            return [*above, cls]
    return None


def _default(attr: griffe.Attribute) -> Any:
    value = attr.value
    if isinstance(value, griffe.ExprCall) and str(value.function).rsplit(".", 1)[-1] in FIELD_HELPERS:
        positional = [a for a in value.arguments if not isinstance(a, griffe.ExprKeyword)]
        keyword = {a.name: a.value for a in value.arguments if isinstance(a, griffe.ExprKeyword)}
        return positional[0] if positional else keyword.get("default")
    return value


def _fields(lineage: list[griffe.Class]) -> dict[str, griffe.Attribute]:
    fields: dict[str, griffe.Attribute] = {}
    for klass in lineage:  # a subclass's field overrides its base's
        for name, member in klass.members.items():
            if member.is_alias or not member.is_attribute or name.startswith("_"):
                continue
            if member.annotation is None or "instance-attribute" not in member.labels:
                continue  # a ClassVar (griffe labels it a class attribute only) or not a field
            fields[name] = member
    return fields


class ParamSetSignatures(griffe.Extension):
    """Give every ParamSet subclass an ``__init__(self, *, field=default, ...)``."""

    def on_package(self, *, pkg: griffe.Module, loader: griffe.GriffeLoader, **kwargs: Any) -> None:
        if pkg.path != "clutchfem":
            return
        for cls in _walk(pkg, classes_only=True):
            own = cls.members.get("__init__")
            if own is not None and not _passes_through(own):
                continue  # a signature of its own: as written
            lineage = _lineage(cls, loader.modules_collection)
            if lineage is None:
                continue
            parameters = [griffe.Parameter("self", kind=griffe.ParameterKind.positional_or_keyword)]
            parameters += [griffe.Parameter(name, annotation=attr.annotation, default=_default(attr),
                                            kind=griffe.ParameterKind.keyword_only)
                           for name, attr in _fields(lineage).items()]
            if own is not None:  # __init__(self, **values) handing the fields on: the same keywords
                own.parameters = griffe.Parameters(*parameters)
                continue
            init = griffe.Function("__init__", parameters=griffe.Parameters(*parameters), returns="None",
                                   lineno=cls.lineno, endlineno=cls.lineno)
            cls.set_member("__init__", init)


def _passes_through(init: griffe.Object) -> bool:
    """``__init__(self, **values)``: an ``__init__`` that hands every keyword to pydantic."""
    if init.is_alias or not init.is_function:
        return False
    kinds = [p.kind for p in init.parameters]
    return kinds[-1:] == [griffe.ParameterKind.var_keyword] and len(kinds) == 2


def _walk(obj: griffe.Object, *, classes_only: bool = False):
    """Every class (or every object) below ``obj``, aliases left out."""
    for member in obj.members.values():
        if member.is_alias:
            continue
        if member.is_class or (not classes_only and (member.is_function or member.is_attribute)):
            yield member
        if member.is_class or member.is_module:
            yield from _walk(member, classes_only=classes_only)


ROLE = re.compile(r":(?:py:)?(?P<role>func|class|meth|mod|attr|exc|obj|data):`(?P<target>[^`<>]+)`")


class SphinxRoles(griffe.Extension):
    """Sphinx roles in the docstrings -> optional cross-references (module docstring)."""

    def on_package(self, *, pkg: griffe.Module, loader: griffe.GriffeLoader, **kwargs: Any) -> None:
        if pkg.path != "clutchfem":
            return
        self.collection = loader.modules_collection
        self.cache: dict[str, str | None] = {}
        for obj in [pkg, *_walk(pkg)]:
            if obj.docstring is not None and ":" in obj.docstring.value:
                obj.docstring.value = ROLE.sub(lambda m, o=obj: self.reference(m, o), obj.docstring.value)

    def reference(self, match: re.Match, obj: griffe.Object) -> str:
        target = match["target"].strip()
        short = target.startswith("~")
        target = target.lstrip("~")
        title = target.rsplit(".", 1)[-1] if short else target.lstrip(".")
        path = None
        for candidate in self.candidates(target, obj):
            path = self.canonical(candidate)
            if path is not None:
                break
        if path is None:
            return f"`{title}`"
        return f'<autoref identifier="{path}" optional><code>{title}</code></autoref>'

    @staticmethod
    def candidates(target: str, obj: griffe.Object) -> list[str]:
        module = obj if obj.is_module else obj.module
        if target.startswith("."):  # relative to the module (a package: to itself), then upwards
            found, scope = [], module
            while scope is not None:
                found.append(scope.path + target)
                scope = scope.parent
            return found
        if target.startswith("clutchfem."):
            return [target]
        found = []
        scope: griffe.Object | None = obj
        while scope is not None:  # the object's scope, its class, its module, the packages above
            found.append(f"{scope.path}.{target}")
            scope = scope.parent
        first, _, rest = target.partition(".")
        try:
            resolved = obj.resolve(first) if not obj.is_module else module.resolve(first)
            found.insert(0, resolved + (f".{rest}" if rest else ""))
        except (griffe.NameResolutionError, AttributeError, KeyError, ValueError):
            pass
        return found

    def canonical(self, path: str) -> str | None:
        """Where ``path`` is defined, or None if it names nothing."""
        if path not in self.cache:
            self.cache[path] = self._static(path) or self._runtime(path)
        return self.cache[path]

    def _static(self, path: str) -> str | None:
        try:
            found = self.collection.get_member(path)
            return (found.final_target if found.is_alias else found).path
        except Exception:  # not there, or an alias griffe cannot follow (a lazy name)
            return None

    @staticmethod
    def _runtime(path: str) -> str | None:
        parts = path.split(".")
        for cut in range(len(parts), 0, -1):
            try:
                value = importlib.import_module(".".join(parts[:cut]))
            except Exception:
                continue
            owner = None
            for name in parts[cut:]:
                owner, value = value, getattr(value, name, _MISSING)
                if value is _MISSING:
                    return None
            if inspect.ismodule(value):
                return value.__name__
            module, qualname = getattr(value, "__module__", None), getattr(value, "__qualname__", None)
            if isinstance(module, str) and isinstance(qualname, str) and (inspect.isclass(value) or callable(value)):
                return f"{module}.{qualname}"
            if inspect.isclass(owner):  # an attribute or property of a class
                return f"{owner.__module__}.{owner.__qualname__}.{parts[-1]}"
            if inspect.ismodule(owner):  # a module-level value
                return f"{owner.__name__}.{parts[-1]}"
            return None
        return None


_MISSING = object()
