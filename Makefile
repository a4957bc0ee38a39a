# curverecon: everything runs inside a virtual environment that this Makefile makes.
# Each target installs only what it needs: the runtime for setup and demo, the development and
# derivation tools (and the batch extra) for test, the derivation tools for derive and bench.
# One stamp file per set of extras, so a later target only adds what the earlier ones left out.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
# --no-compile: Python writes the bytecode of the modules it imports on first use; compiling every
# installed file ahead (SciPy, matplotlib, scikit-image: most never imported) took 12 of the
# runtime install's 20 s of CPU time and 100 MB.
PIP    := $(BIN)/python -m pip install --quiet --no-compile
STAMP_RUNTIME := $(VENV)/.stamp-runtime
STAMP_TEST    := $(VENV)/.stamp-dev-batch
STAMP_DERIVE  := $(VENV)/.stamp-derive

.PHONY: setup derive test fuzz demo bench lint format clean

## setup: the runtime only, then numba's kernels compiled once into its cache (python -m
## curverecon.warmup), so that the first reconstruction does not compile them
setup: $(STAMP_RUNTIME)

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(STAMP_RUNTIME): pyproject.toml | $(BIN)/python
	$(PIP) -e .
	$(BIN)/python -m curverecon.warmup
	touch $@

$(STAMP_TEST): pyproject.toml $(STAMP_RUNTIME)
	$(PIP) -e '.[dev,batch]'
	touch $@

$(STAMP_DERIVE): pyproject.toml $(STAMP_RUNTIME)
	$(PIP) -e '.[derive]'
	touch $@

## derive: rebuild generated/ and docs/derivation.md from derivations/
derive: $(STAMP_DERIVE)
	$(BIN)/python -m derivations

## test: the whole test suite (includes the generated-code staleness check)
test: $(STAMP_TEST)
	$(BIN)/python -m pytest -q

## fuzz: the property-based tests with a large randomised budget (tests/conftest.py)
fuzz: $(STAMP_TEST)
	HYPOTHESIS_PROFILE=fuzz $(BIN)/python -m pytest -q tests/test_fuzz.py --hypothesis-show-statistics

## demo: reconstruct the bundled example; trace the rendered video examples/trace/sequence.mp4 and
## reconstruct them; write demo-output/
demo: $(STAMP_RUNTIME)
	mkdir -p demo-output
	$(BIN)/curverecon reconstruct examples/wire.json -o demo-output/wire.reconstruction.json --plot demo-output/wire.png
	@echo "wrote demo-output/wire.reconstruction.json and demo-output/wire.png"
	$(BIN)/curverecon trace examples/trace/sequence.mp4 -o demo-output/trace.observations.json --plot demo-output/trace-overlays
	$(BIN)/curverecon reconstruct demo-output/trace.observations.json -o demo-output/trace.reconstruction.json --plot demo-output/trace.png
	@echo "wrote demo-output/trace.observations.json, demo-output/trace-overlays/, demo-output/trace.reconstruction.json and demo-output/trace.png"

## bench: accuracy, robustness, stability and speed; writes bench/REPORT.md and bench/report.json
## (some sections use SymPy and the derivations: the derive extra)
bench: $(STAMP_DERIVE)
	$(BIN)/python -m bench

lint: $(STAMP_TEST)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

format: $(STAMP_TEST)
	$(BIN)/ruff format .

clean:
	rm -rf $(VENV) demo-output .pytest_cache
