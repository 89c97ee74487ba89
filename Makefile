# clutchfem: two commands on a fresh Debian machine.
#   make demo   set up, then build every concept and run the main job on the default design
#   make test   set up, then run the whole test suite (and print its 20 slowest tests)
#   make check  set up, then run the fast tier (-m "not slow": no meshing, solving, processes) for the inner loop
#   make docs   set up, then build the documentation site into site/ (every warning an error)
#   make pictures  regenerate the README's and docs' study, target, field, report and cutting pictures
#   make bench-peer  install CalculiX (Debian calculix-ccx, benchmarks only) and run the peer checks
PYTHON ?= python3.11
# Python's byte-code cache on, even where the environment turns it off: every process of a test
# run (the two xdist workers, the Dask workers, the CLI and app processes the tests start) would
# otherwise compile the package from source, and pytest would rewrite every test module's asserts
# again in each worker (collection 11 s -> 5 s a worker, measured).
unexport PYTHONDONTWRITEBYTECODE
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed
DOCS_STAMP := $(VENV)/.installed-docs
OUT ?= out/demo
# Shared libraries that the gmsh wheel loads (X/GL), OSMesa for off-screen pyvista renders,
# SuiteSparse headers for the CHOLMOD solver back-end (scikit-sparse builds from source).
APT_PKGS := libglu1-mesa libxcursor1 libxinerama1 libxft2 libxrender1 libxext6 libgl1 libosmesa6 \
            libsuitesparse-dev chromium
# The peer solver of the benchmarks only (never a runtime or test dependency): CalculiX 2.20.
BENCH_APT_PKGS := calculix-ccx

.PHONY: setup sysdeps demo test check docs bench bench-peer pictures clean

sysdeps:
	@bash scripts/sysdeps.sh $(APT_PKGS)

$(STAMP): pyproject.toml
	$(MAKE) sysdeps
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	@# CHOLMOD (faster, robust factorisation; see BENCHMARKS.md).  Optional: if its build fails
	@# clutchfem falls back to SuperLU, so a missing compiler never blocks setup.
	$(PY) -m pip install --quiet -e '.[cholmod]' || echo "note: CHOLMOD unavailable, using SuperLU"
	@touch $(STAMP)

setup: $(STAMP)

demo: setup
	$(VENV)/bin/clutchfem demo --out $(OUT)

# Two workers (the 2-core machine of CI and the developers).  worksteal: an idle worker takes
# half of the other's queue, so a long test near the end does not leave one core idle; one
# mesh cache for the run (conftest.py).
PYTEST := $(PY) -m pytest -n 2 --dist worksteal -q

test: setup
	$(PYTEST) --durations=20

check: setup
	$(PYTEST) -m "not slow" --durations=10

# The site: MkDocs (Material) + mkdocstrings; the API, CLI and benchmarks pages are generated
# at build time (scripts/docs_pages.py).  The two variables only hush the banners that
# mkdocs-material and properdocs print about MkDocs 2 (not build warnings: --strict sees those).
$(DOCS_STAMP): pyproject.toml $(STAMP)
	$(PY) -m pip install --quiet -e '.[docs]'
	@touch $(DOCS_STAMP)

docs: setup $(DOCS_STAMP)
	NO_MKDOCS_2_WARNING=1 DISABLE_MKDOCS_2_WARNING=true $(PY) -m mkdocs build --strict --site-dir site

pictures: setup
	OPENBLAS_NUM_THREADS=1 $(PY) scripts/make_pictures.py

bench: setup
	$(PY) benchmarks/bench_sweep.py && $(PY) benchmarks/bench_solvers.py && $(PY) benchmarks/bench_stress.py \
	  && $(PY) benchmarks/bench_sweep_throughput.py && $(PY) benchmarks/bench_modelform.py

bench-peer: setup
	@bash scripts/sysdeps.sh $(BENCH_APT_PKGS)
	$(PY) benchmarks/bench_calculix.py && $(PY) benchmarks/bench_calculix_nl.py

clean:
	rm -rf out .pytest_cache site
