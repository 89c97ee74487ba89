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
