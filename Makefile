# Quick start: `make demo` and `make test`. Both create .venv on first use.
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: install browser demo test test-fast lint bench clean

install: $(STAMP)

$(STAMP): pyproject.toml requirements.txt requirements-dev.txt
	$(PYTHON) -c 'import sys; assert sys.version_info >= (3, 11), "kitchen_tamp needs Python 3.11+"'
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -r requirements-dev.txt
	$(BIN)/python -m pip install --quiet --no-deps -e .
	$(BIN)/python -m kitchen_tamp.cli.prepare
	touch $(STAMP)

# Debian's Chromium for the replay.html browser test (which skips, saying why, without it).
browser:
	command -v chromium >/dev/null || (apt-get update && apt-get install -y chromium)

demo: install
	$(BIN)/python final_project.py rrt

# Both suites run on every core (pytest-xdist), a test file to a worker.
PYTEST := $(BIN)/python -m pytest -q -n auto --dist loadfile

test: install
	$(PYTEST)

# The quick loop: everything but whole pipelines and long agreement checks (marked slow).
test-fast: install
	$(PYTEST) -m "not slow"

lint: install
	$(BIN)/ruff check .
	$(BIN)/mypy

bench: install
	$(BIN)/python benchmarks/symbolic.py
	$(BIN)/python benchmarks/motion.py --query-set kitchen
	$(BIN)/python benchmarks/collision.py
	$(BIN)/python benchmarks/trajopt.py
	$(BIN)/python benchmarks/clearance.py
	$(BIN)/python benchmarks/bilevel.py

clean:
	rm -rf $(VENV) out .pytest_cache .mypy_cache .ruff_cache
