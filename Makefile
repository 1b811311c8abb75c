# One command each on a fresh machine: `make demo`, `make test`.
SHELL := /bin/bash
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.deps-stamp
CPP_BUILD := build/cpp
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
DEMO_OUT ?= demo-out
# the real robot's recordings for benchmarks/realdata.py (not in this repository)
REALDATA ?= ../shared/data/nhoyh_vio_com

.PHONY: all venv install demo test test-python test-cpp gtest chromium bench results readme lint clean

all: install

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet "scikit-build-core>=0.10" "nanobind>=2.0"
	touch $(STAMP)

venv: $(STAMP)

# No build isolation: the build tools live in the venv and the CMake build
# directory (build/) is kept, so a rebuild only recompiles what changed.
install: $(STAMP)
	$(PY) -m pip install --quiet --no-build-isolation ".[test]"

demo: install
	$(VENV)/bin/tendonsheath demo --out $(DEMO_OUT)

gtest:
	@if [ ! -f /usr/include/gtest/gtest.h ] && [ ! -f /usr/local/include/gtest/gtest.h ]; then \
	  echo "GoogleTest not found: installing libgtest-dev with apt-get"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libgtest-dev googletest; \
	fi

# The report test renders report.html in headless Chromium (Debian's package).
chromium:
	@if ! command -v chromium > /dev/null && ! command -v chromium-browser > /dev/null; then \
	  echo "Chromium not found: installing Debian's chromium package with apt-get"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium > /dev/null; \
	fi

test-cpp: gtest
	cmake -S . -B $(CPP_BUILD) -DCMAKE_BUILD_TYPE=Release -DTENDONSHEATH_BUILD_TESTS=ON \
	  -DTENDONSHEATH_BUILD_EXAMPLES=ON > /dev/null
	cmake --build $(CPP_BUILD) -j $(JOBS)
	ctest --test-dir $(CPP_BUILD) --output-on-failure
	@# the core as a CMake package: install it, then build the examples against it
	cmake --install $(CPP_BUILD) --prefix build/cpp-install > /dev/null
	cmake -S examples/cpp -B build/cpp-consumer -DCMAKE_PREFIX_PATH=$(CURDIR)/build/cpp-install > /dev/null
	cmake --build build/cpp-consumer -j $(JOBS)

test-python: install chromium
	$(PY) -m pytest -q

test: test-cpp lint test-python

bench: install
	@for f in benchmarks/[a-z]*.py; do \
	  [ "$$f" = benchmarks/readme_tables.py ] && continue; \
	  echo "== $$f"; $(PY) $$f || exit 1; \
	done

# Refresh the committed result files (benchmarks/results/*.json) that README.md's tables are
# generated from, then regenerate the tables: the demo's metrics.json, the benchmark scripts'
# JSON, and realdata.json when $(REALDATA) is there (~6 min; else the committed one is kept).
results: demo
	cp $(DEMO_OUT)/metrics.json benchmarks/results/demo-metrics.json
	@for f in models plant identify identify_long compensators sweep; do \
	  echo "== benchmarks/$$f.py"; $(PY) benchmarks/$$f.py || exit 1; \
	done
	@if [ -f $(REALDATA)/config_000deg.csv ]; then \
	  echo "== benchmarks/realdata.py"; $(PY) benchmarks/realdata.py --data $(REALDATA) || exit 1; \
	else echo "no data in $(REALDATA): benchmarks/results/realdata.json kept"; fi
	$(MAKE) readme

# README.md's tables from the committed result files (no build needed)
readme:
	$(PYTHON) benchmarks/readme_tables.py

lint: install
	$(VENV)/bin/ruff check python tests benchmarks examples
	$(VENV)/bin/ruff format --check python tests benchmarks examples

clean:
	rm -rf build $(VENV) $(DEMO_OUT) .pytest_cache .ruff_cache
