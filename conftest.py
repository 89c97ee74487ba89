import os

import pytest

# The suite's machinery tests run on the fast 2-D path (the shipped default is "best", about
# twice the cost: the suite would double).  Tests of the best path ask for it; tests of the
# default itself unset this (tests/test_fidelity_default.py).  CLUTCHFEM_FIDELITY=best make
# test runs everything on the best path.
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")


@pytest.fixture(autouse=True, scope="session")
def _isolated_cache(tmp_path_factory, request):
    """One mesh cache for the whole test run (tests and doctests), never the developer's
    (no stale meshes from a home cache): under pytest-xdist every worker, and every process
    a test starts (they inherit the variable), meshes into the same folder of this run's
    temporary root, so a design two workers need is meshed once (the cache's entry lock
    makes the second wait for the first)."""
    base = tmp_path_factory.getbasetemp()
    if hasattr(request.config, "workerinput"):  # an xdist worker (not a pytest a test starts)
        base = base.parent  # pytest-of-USER/pytest-N/popen-gwK -> the run's shared root
    d = base / "clutchfem-cache"
    d.mkdir(exist_ok=True)
    os.environ["CLUTCHFEM_CACHE"] = str(d)
    yield


#: the doctests that mesh and solve, by module file and name (so that they are found after a
#: module moves to another package), with their seconds in the baseline of issue 35; the
#: fast tier (``make check``, ``-m "not slow"``) leaves them to ``make test``
SLOW_DOCTESTS = {
    "robust.robust_optimize",  # 7.7 s
    "guideline_study.run_guidelines",  # 7.6 s
    "tolerancing.tolerance",  # 4.2 s
    "peak.peak_stress_converged",  # 3.2 s
    "optimization.optimize",  # 2.3 s
    "sensitivity.sensitivities",  # 1.9 s
    "runs.design_report",  # 1.7 s
    "pipeline.analyze",  # 1.5 s
    "export.export",  # 1.5 s
    "runner.run_study",  # 1.3 s
    "compensation.compensate",  # 1.1 s
    "runner.validate",  # 1.1 s
    "design.comparison_plot",  # 1.0 s
    "allocation.yield_front",  # 0.9 s
    "allocation.allocate_tolerances",  # 0.9 s
    "slip_heat.slip_heat",  # 0.8 s
    "design.Design.from_concept",  # 0.7 s
    "grid.run_grid",  # 0.6 s
    "morphing.morph",  # 0.3 s after the others, 1.3 s alone (it meshes)
    "answers.Analysis",  # 0.3 s after the others, 1.0 s alone
}


def pytest_collection_modifyitems(config, items):
    """Doctests cannot carry a decorator: the ones in :data:`SLOW_DOCTESTS` are marked slow here."""
    for item in items:
        if isinstance(item, pytest.DoctestItem) and any(item.name.endswith("." + k) for k in SLOW_DOCTESTS):
            item.add_marker(pytest.mark.slow)
