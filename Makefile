# seacable: two commands on a fresh machine with only python3 -- `make demo` and `make test`.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed
DEMO_STAMP := $(VENV)/.installed-demo
DOCS_STAMP := $(VENV)/.installed-docs

.PHONY: demo test test-all docs lint typecheck bench clean clean-cache

$(VENV)/bin/python:
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip

# the demo installs what a run needs and nothing else; the tests add their tools and Dask
$(DEMO_STAMP): pyproject.toml $(VENV)/bin/python
	$(PY) -m pip install -q -e .
	touch $(DEMO_STAMP)

$(STAMP): pyproject.toml $(VENV)/bin/python
	$(PY) -m pip install -q -e ".[test,dask]"
	touch $(STAMP) $(DEMO_STAMP)

$(DOCS_STAMP): pyproject.toml $(VENV)/bin/python
	$(PY) -m pip install -q -e ".[docs]"
	touch $(DOCS_STAMP)

demo: $(DEMO_STAMP)
	mkdir -p results
	$(VENV)/bin/seacable run examples/thesis_6_1_sim6_submerged_60_links_forced.yaml -o results/demo.nc
	$(VENV)/bin/seacable plot results/demo.nc -o results/demo.png --every 1.0
	@echo "demo: results/demo.nc and results/demo.png written"

lint: $(STAMP)
	$(VENV)/bin/ruff format --check src tests benchmarks docs
	$(VENV)/bin/ruff check src tests benchmarks docs

typecheck: $(STAMP)
	$(VENV)/bin/mypy src

test: lint typecheck
	OPENBLAS_NUM_THREADS=1 $(PY) -m pytest -q -n auto --dist loadfile -m "not slow"

test-all: lint typecheck
	OPENBLAS_NUM_THREADS=1 $(PY) -m pytest -q -n auto --dist loadfile

# the documentation site, warnings as errors: docs/_build/html/index.html
docs: $(DOCS_STAMP)
	$(PY) -m sphinx -b html -W --keep-going -q docs docs/_build/html
	@echo "docs: docs/_build/html/index.html written"

bench: $(STAMP)
	OPENBLAS_NUM_THREADS=1 $(PY) benchmarks/thesis_timings.py

clean-cache:
	find src -name "*.nbi" -delete; find src -name "*.nbc" -delete
	$(PY) -c "from seacable.system import variants; import shutil; shutil.rmtree(variants.cache_folder())"

clean:
	rm -rf $(VENV) results build docs/_build *.egg-info src/*.egg-info
