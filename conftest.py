import os

import pytest


@pytest.fixture(autouse=True, scope="session")
def _isolated_cache(tmp_path_factory):
    """Each test session (tests and doctests) meshes into its own cache (no stale meshes from a developer's home)."""
    d = tmp_path_factory.mktemp("cache")
    os.environ["CLUTCHFEM_CACHE"] = str(d)
    yield
