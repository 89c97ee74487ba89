"""The house rules of the source tree, checked on every run (docs/architecture.md):

* layers only point down: the import-linter contract in pyproject.toml (``lint-imports``);
* one job per module, stated in the first line of its docstring;
* no source file over ~500 lines, except the ones listed in :data:`LONG_FILES` with a reason;
* no stage package over ~3,000 lines (:data:`MAX_PACKAGE_LINES` lines of code: blank and
  comment-only lines not counted; docstrings are);
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
#: lines of code (not blank, not a comment alone) a stage package may hold
MAX_PACKAGE_LINES = 3000
#: files allowed above MAX_LINES, with the reason
LONG_FILES: dict[str, str] = {}
#: third-party packages that may be imported inside a function: each costs >= 0.3 s to import
#: (measured: matplotlib 0.8 s, pyvista 1.6 s, dask 0.5 s, distributed 1.6 s) or is optional
#: (sksparse: the CHOLMOD back-end; threadpoolctl), and most analyses never need them
HEAVY = {"matplotlib", "pyvista", "vtk", "dask", "distributed", "sksparse", "threadpoolctl", "ezdxf",
         "trame", "trame_vuetify", "trame_vtk", "nicegui", "playwright",
         "scipy.optimize",  # 0.7 s (measured with python -X importtime): the base layer's brentq defers it
         "sklearn",  # ~0.6 s: the reduced model's fit only (a fitted model answers with numpy)
         "scipy.stats",  # ~0.4 s: the reduced model's Sobol sample (a build's, not a live answer's)
         "scipy.interpolate",  # 0.35 s: a table profile's spline (a live answer's concept needs none)
         "emcee",  # the calibration's sampler: only when a calibration samples (Laplace does not)
         "PIL",  # matplotlib's image writer: only when a picture is written
         "scipy.spatial",  # ~0.65 s: the k-d tree of a geometry build's outline check (a live answer builds none)
         "pandas"}  # ~0.4 s: tables of study rows and of curves (a live answer's start-up reads none)
#: the faces whose commands import the API on use (the command line starts in ~0.3 s instead of ~3 s)
FACES = ("cli/", "app/")
#: the stages of the FE work (meshing, the FE model and its solves, evaluating designs, building a
#: reduced model) that a module may import inside the function that does that work: a design
#: answered live (``--fidelity live``, :mod:`clutchfem.reduced`) is never meshed, and the modules
#: its answer passes through load none of them (measured: the FE stack 1.1 s of a 2.1 s live
#: ``analyze``; docs/reduced.md).  The layer contract still checks these imports.
FE_WORK = ("clutchfem.mesh", "clutchfem.fe", "clutchfem.contact", "clutchfem.softening", "clutchfem.loadcase.case",
           "clutchfem.analysis.pipeline", "clutchfem.evaluation.point", "clutchfem.evaluation.runner",
           "clutchfem.evaluation.sensitivity", "clutchfem.reduced.build")


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


def test_no_package_over_the_line_limit():
    """A stage package that outgrows ~3,000 lines of code is split by job (``thermal`` left
    ``durability`` this way)."""
    sizes: dict[str, int] = {}
    for rel, f in _modules():
        if "/" in rel:
            code = [ln for ln in f.read_text().splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
            sizes[rel.split("/")[0]] = sizes.get(rel.split("/")[0], 0) + len(code)
    assert len(sizes) >= 17  # every stage package was counted
    big = {k: n for k, n in sizes.items() if n > MAX_PACKAGE_LINES}
    assert not big, f"packages over {MAX_PACKAGE_LINES} lines of code (split them by job): {big}"


def _function_imports(tree):
    for fn in ast.walk(tree):
        if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for node in ast.walk(fn):
                if isinstance(node, (ast.Import, ast.ImportFrom)):
                    yield node


def _absolute(rel: str, node: ast.ImportFrom) -> str:
    """The absolute module an ``from ... import`` in the module at ``rel`` (under SRC) imports from."""
    if not node.level:
        return node.module or ""
    package = ["clutchfem", *rel.removesuffix(".py").split("/")][:-node.level]  # (a package's __init__ too)
    return ".".join(package + ([node.module] if node.module else []))


@pytest.mark.slow
def test_imports_inside_functions_only_defer_heavy_dependencies():
    bad = []
    for rel, f in _modules():
        for node in _function_imports(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith("clutchfem")):
                target = _absolute(rel, node)
                if not rel.startswith(FACES) and not any(target == s or target.startswith(s + ".") for s in FE_WORK):
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


def test_analyze_does_not_load_the_reduced_models_machinery():
    """``cf.analyze`` registers the live path (``clutchfem.reduced.live``) but loads neither
    scikit-learn (a fit's only) nor the study engine's cluster (~0.8 s together)."""
    code = ("import sys, clutchfem as cf; cf.analyze; import clutchfem.analysis as a; "
            "heavy = [m for m in ('sklearn', 'distributed') if m in sys.modules]; "
            "print(len(a.LIVE), ','.join(heavy))")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "1", f"cf.analyze loaded {r.stdout.strip()}"


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


# ---------------------------------------------------------------------------------------
# one vocabulary (issue 35): public names, serialisers, results, the command line's API
# ---------------------------------------------------------------------------------------
#: public functions whose answer is a plain JSON record, with the reason
PLAIN_RECORDS = {
    "finished_summary": "the stored summary.json itself, read with the standard library only (a rerun of a "
                        "finished study loads no FE stack: studies/rerun.py)",
    "sweep_errors": "one AnswerError record per answer, the same form as Analysis.errors",
}
#: method names of other serialisers (one name: to_json)
OTHER_SERIALISERS = {"as_dict", "as_json", "to_dict", "asdict", "json", "serialize", "serialise"}


def _public():
    import clutchfem as cf

    return cf, [n for n in cf.__all__ if n != "__version__"]


def test_public_names_are_the_names_where_they_are_defined():
    """``cf.X`` is the object defined as ``X`` in the package ``_API`` names (no renames)."""
    import inspect

    cf, names = _public()
    bad = []
    for n in names:
        obj = getattr(cf, n)
        defined = getattr(obj, "__name__", n)
        module = getattr(obj, "__module__", "") or ""
        if (inspect.isclass(obj) or inspect.isfunction(obj) or callable(obj)) and defined != n:
            bad.append(f"{n} is defined as {defined}")
        if module.startswith("clutchfem") and not module.startswith(cf._API[n]):
            bad.append(f"{n} lives in {module}, _API says {cf._API[n]}")
    assert not bad, bad


def test_type_checking_block_lists_the_public_names():
    """The TYPE_CHECKING imports of ``clutchfem/__init__.py`` (for IDEs) are exactly ``_API``."""
    import clutchfem as cf

    tree = ast.parse((SRC / "__init__.py").read_text())
    block = next(n for n in tree.body if isinstance(n, ast.If) and ast.unparse(n.test) == "TYPE_CHECKING")
    seen = {}
    for node in ast.walk(block):
        if isinstance(node, ast.ImportFrom):
            for a in node.names:
                assert a.asname is None, f"a renamed import in the TYPE_CHECKING block: {a.name} as {a.asname}"
                seen[a.name] = "clutchfem" + "." * 0 + f".{node.module}"
    assert seen == dict(cf._API)


def test_one_serialiser_name():
    """Every class that serialises itself does it as ``to_json`` (no as_dict / as_json ...)."""
    bad = []
    for rel, f in _modules():
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ClassDef):
                bad += [f"{rel}: {node.name}.{m.name}" for m in node.body
                        if isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef)) and m.name in OTHER_SERIALISERS]
    assert not bad, bad


def test_public_functions_return_typed_results():
    """Every public function states what it returns, and no answer is an untyped dict, list of
    dicts or data frame (except the records of :data:`PLAIN_RECORDS`, with their reason)."""
    import inspect

    cf, names = _public()
    bad = []
    for n in names:
        obj = getattr(cf, n)
        if inspect.isclass(obj) or not callable(obj):
            continue
        ann = inspect.signature(obj).return_annotation
        text = ann if isinstance(ann, str) else getattr(ann, "__name__", str(ann))
        if ann is inspect.Signature.empty:
            bad.append(f"{n}: no return annotation")
        elif n not in PLAIN_RECORDS and text.replace(" ", "") in ("dict", "list[dict]", "DataFrame", "pd.DataFrame",
                                                                  "dict|None", "list"):
            bad.append(f"{n} -> {text}")
    assert not bad, bad


def test_public_results_serialise_as_to_json():
    """The result classes of the public API serialise with ``to_json`` (a JSON-ready dict)."""
    import inspect

    cf, names = _public()
    results = [n for n in names if inspect.isclass(getattr(cf, n)) and n.endswith(("Result", "Run", "Front"))]
    assert results, "no result classes found"
    missing = [n for n in results if not callable(getattr(getattr(cf, n), "to_json", None))]
    assert not missing, missing


def test_the_command_line_stands_on_the_public_api():
    """``cli/`` imports from clutchfem only public names (``from .. import X``, X in
    ``clutchfem.__all__``) and its own modules: the API covers what its own face needs, and no
    command borrows another command's helpers (shared ones live in cli/common.py, options.py)."""
    cf, names = _public()
    public = set(names) | {"__version__"}
    bad = []
    for f in sorted((SRC / "cli").glob("*.py")):
        rel = f"cli/{f.name}"
        for node in ast.walk(ast.parse(f.read_text())):
            if not isinstance(node, ast.ImportFrom):
                continue
            if node.level == 2 and node.module is None:
                bad += [f"{rel}:{node.lineno} {a.name} is not public" for a in node.names if a.name not in public]
            elif node.level >= 2 or (node.module or "").startswith("clutchfem"):
                bad.append(f"{rel}:{node.lineno} {ast.unparse(node)}")
            elif node.level == 1 and node.module and node.module.endswith("_cmd") and f.stem != "_app":
                bad.append(f"{rel}:{node.lineno} borrows from another command: {ast.unparse(node)}")
    assert not bad, "\n".join(bad)


def test_every_public_name_has_one_group():
    """The public API is declared once, by job (``clutchfem._GROUPS``: the documentation's
    groups); ``_API`` and ``__all__`` follow from it, every name in exactly one group."""
    import clutchfem as cf

    listed = [n for names in cf._GROUPS.values() for n in names]
    assert len(listed) == len(set(listed)), "a public name in two groups"
    assert set(listed) == set(cf._API) == set(cf.__all__) - {"__version__"}
