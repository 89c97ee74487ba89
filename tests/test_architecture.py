"""The house rules of the source tree, checked on every run (docs/architecture.md):

* layers only point down: the import-linter contract in pyproject.toml (``lint-imports``);
* one job per module, stated in the first line of its docstring;
* no source file over ~500 lines, except the ones listed in :data:`LONG_FILES` with a reason;
* no import inside a function, except of a measured heavy third-party dependency
  (:data:`HEAVY`) or, in the command-line and app faces, of the API itself (so that
  ``clutchfem --help`` does not load the FE stack);
* no private name (``_x``) imported from another module;
* ``import clutchfem`` loads no numerical library (the public API is imported lazily).
"""

from __future__ import annotations

import ast
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "clutchfem"
MAX_LINES = 500
#: files allowed above MAX_LINES, with the reason
LONG_FILES: dict[str, str] = {}
#: third-party packages that may be imported inside a function: each costs >= 0.3 s to import
#: (measured: matplotlib 0.8 s, pyvista 1.6 s, dask 0.5 s, distributed 1.6 s) or is optional
#: (sksparse: the CHOLMOD back-end; threadpoolctl), and most analyses never need them
HEAVY = {"matplotlib", "pyvista", "vtk", "dask", "distributed", "sksparse", "threadpoolctl", "ezdxf",
         "trame", "trame_vuetify", "trame_vtk", "nicegui", "playwright",
         "scipy.optimize"}  # 0.7 s (measured with python -X importtime): the base layer's brentq defers it
#: the faces whose commands import the API on use (the command line starts in ~0.3 s instead of ~3 s)
FACES = ("cli/", "app/")


def _modules():
    for f in sorted(SRC.rglob("*.py")):
        yield f.relative_to(SRC).as_posix(), f


def test_layer_contract():
    exe = shutil.which("lint-imports", path=str(Path(sys.executable).parent))
    assert exe, "import-linter is part of the test extras"
    r = subprocess.run([exe], capture_output=True, text=True, cwd=SRC.parents[1])
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-2000:]


@pytest.mark.slow
def test_every_module_states_its_job():
    missing = [rel for rel, f in _modules()
               if not (ast.get_docstring(ast.parse(f.read_text())) or "").strip().split("\n")[0]
               and rel != "cli/__main__.py"]
    assert not missing, f"modules without a one-line job in their docstring: {missing}"


def test_no_file_over_the_line_limit():
    long = {rel: n for rel, f in _modules() if (n := len(f.read_text().splitlines())) > MAX_LINES
            and rel not in LONG_FILES}
    assert not long, f"files over {MAX_LINES} lines (split them, or give the reason in LONG_FILES): {long}"


def _function_imports(tree):
    for fn in ast.walk(tree):
        if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for node in ast.walk(fn):
                if isinstance(node, (ast.Import, ast.ImportFrom)):
                    yield node


@pytest.mark.slow
def test_imports_inside_functions_only_defer_heavy_dependencies():
    bad = []
    for rel, f in _modules():
        for node in _function_imports(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith("clutchfem")):
                if not rel.startswith(FACES):
                    bad.append(f"{rel}:{node.lineno} {ast.unparse(node)}")
                continue
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
            for name in names:
                if name not in HEAVY and name.split(".")[0] not in HEAVY:
                    bad.append(f"{rel}:{node.lineno} {ast.unparse(node)}")
    assert not bad, f"{len(bad)} imports inside functions (move them to the top of the module):\n" + "\n".join(bad)


@pytest.mark.slow
def test_no_private_name_crosses_modules():
    bad = []
    for rel, f in _modules():
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith("clutchfem")):
                bad += [f"{rel}:{node.lineno} {a.name}" for a in node.names
                        if a.name.startswith("_") and not a.name.startswith("__")]
    assert not bad, f"private names imported from another module: {bad}"


def test_import_clutchfem_loads_no_numerical_library():
    code = ("import sys, clutchfem; heavy = [m for m in ('numpy', 'scipy', 'skfem', 'gmsh', 'pandas', "
            "'matplotlib', 'pydantic', 'dask') if m in sys.modules]; print(','.join(heavy))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "", f"import clutchfem loaded {r.stdout.strip()}"


@pytest.mark.parametrize("rel", ["__init__.py"])
def test_public_api_lists_its_names(rel):
    import clutchfem

    assert clutchfem.__all__, "clutchfem.__all__ lists the public API"
    for name in clutchfem.__all__:
        assert getattr(clutchfem, name) is not None


def test_public_names_are_documented_with_runnable_examples():
    """numpydoc sections on every public name (their Examples run as doctests in make test)."""
    import inspect

    import clutchfem as cf

    missing = []
    for name in cf.__all__:
        if name == "__version__":
            continue
        obj = getattr(cf, name)
        doc = inspect.getdoc(obj) or ""
        needs = ["Examples"]
        if inspect.isfunction(obj):
            needs += ["Parameters", "Returns"] if inspect.signature(obj).parameters else ["Returns"]
        missing += [f"{name}: {s}" for s in needs if f"{s}\n--" not in doc]
    assert not missing, f"public names without numpydoc sections: {missing}"


def test_public_names_are_not_shadowed_by_subpackages():
    """``cf.report`` is a function only if no subpackage of that name exists: importing the
    subpackage would replace the attribute (a public name must not clash)."""
    import importlib
    import pkgutil

    import clutchfem as cf

    subpackages = {m.name for m in pkgutil.iter_modules(cf.__path__)}
    assert not (set(cf.__all__) & subpackages)
    for m in subpackages:
        importlib.import_module(f"clutchfem.{m}")
    assert all(not inspect_ismodule(getattr(cf, n)) for n in cf.__all__ if n != "__version__")


def inspect_ismodule(obj) -> bool:
    import inspect

    return inspect.ismodule(obj)
