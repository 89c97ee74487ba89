import os
import re
import sys

import pytest

# The suite's machinery tests run on the fast 2-D path (the shipped default is "best", about
# twice the cost: the suite would double).  Tests of the best path ask for it; tests of the
# default itself unset this (tests/test_fidelity_default.py).  CLUTCHFEM_FIDELITY=best make
# test runs everything on the best path.
os.environ.setdefault("CLUTCHFEM_FIDELITY", "fast")

# One BLAS thread in every process of the run (this one, the xdist workers, the processes the
# tests start; the study tests' environments and Dask's nannies already set it).  Two workers
# on two cores are the run's parallelism: a threaded OpenBLAS on top spins on busy cores, and
# the dense solves of small systems then take 25x the CPU (measured: the held-contact walk of
# the 1 mm clearance case in tests/support/solver_edges.py, 15.5 s -> 0.6 s).  Set before
# numpy loads OpenBLAS (it reads the variable once); the answers are the same.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")


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


@pytest.fixture(autouse=True)
def _cache_kept():
    """The run's one cache for every test: an example that points ``CLUTCHFEM_CACHE`` at an
    empty folder of its own (the reduced model's doctests do, to show a build) would leave
    every later test of its worker meshing from scratch into it; the variable is put back."""
    before = os.environ.get("CLUTCHFEM_CACHE")
    yield
    if before is not None and os.environ.get("CLUTCHFEM_CACHE") != before:
        os.environ["CLUTCHFEM_CACHE"] = before


@pytest.fixture(autouse=True)
def _no_rows_from_another_test():
    """Each test evaluates its own designs: the study engine's in-process rows of recent
    designs (clutchfem.evaluation.batch.RECENT_ROWS) are not shared between tests, so a test
    about a failure or a worker never gets another test's answer instead."""
    yield
    batch = sys.modules.get("clutchfem.evaluation.batch")
    if batch is not None:
        batch.RECENT_ROWS.clear()


#: a doctest whose example calls one of these meshes, solves, runs designs or draws: the fast
#: tier (``make check``, ``-m "not slow"``) leaves it to ``make test``.  Read from the
#: examples' source, so a new or moved example is placed without a list to keep.
HEAVY_EXAMPLE = re.compile(
    r"Design\.from_concept|Design\.from_mesh|\banalyze\(|\brun_(study|grid|guidelines|points)\(|\boptimize\("
    r"|\btolerance\(|\bsensitivities\(|\bcompensate\(|\bexport\(|\bwrite_report\(|\bvalidate\("
    r"|\bbest_estimate\(|\bslip_heat\(|\bmesh_concept\(|\bmorph\(|\bdraw_concept\(|\byield_front\("
    r"|\ballocate_tolerances\(|\brobust_optimize\(|\bpeak_stress_converged\(|\bdefault_design_report\("
    r"|\btorque_speed_plot\(|\bevaluate_many\(|\bReducedModel|\breduce\(")


def pytest_collection_modifyitems(config, items):
    """Doctests cannot carry a decorator: the ones whose examples do heavy work
    (:data:`HEAVY_EXAMPLE`) are marked slow here."""
    for item in items:
        if isinstance(item, pytest.DoctestItem) and any(HEAVY_EXAMPLE.search(ex.source)
                                                         for ex in item.dtest.examples):
            item.add_marker(pytest.mark.slow)
