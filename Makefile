# curverecon: everything runs inside a virtual environment that this Makefile makes.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed-stamp

.PHONY: setup derive test fuzz demo bench lint format clean

setup: $(STAMP)

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[dev]'
	touch $(STAMP)

## derive: rebuild generated/ and docs/derivation.md from derivations/
derive: $(STAMP)
	$(BIN)/python -m derivations

## test: the whole test suite (includes the generated-code staleness check)
test: $(STAMP)
	$(BIN)/python -m pytest -q

## fuzz: the property-based tests with a large randomised budget (tests/conftest.py)
fuzz: $(STAMP)
	HYPOTHESIS_PROFILE=fuzz $(BIN)/python -m pytest -q tests/test_fuzz.py --hypothesis-show-statistics

## demo: reconstruct the bundled example; trace the rendered video examples/trace/sequence.mp4 and
## reconstruct them; write demo-output/
demo: $(STAMP)
	mkdir -p demo-output
	$(BIN)/curverecon reconstruct examples/wire.json -o demo-output/wire.reconstruction.json --plot demo-output/wire.png
	@echo "wrote demo-output/wire.reconstruction.json and demo-output/wire.png"
	$(BIN)/curverecon trace examples/trace/sequence.mp4 -o demo-output/trace.observations.json --plot demo-output/trace-overlays
	$(BIN)/curverecon reconstruct demo-output/trace.observations.json -o demo-output/trace.reconstruction.json --plot demo-output/trace.png
	@echo "wrote demo-output/trace.observations.json, demo-output/trace-overlays/, demo-output/trace.reconstruction.json and demo-output/trace.png"

## bench: accuracy, robustness, stability and speed; writes bench/REPORT.md and bench/report.json
bench: $(STAMP)
	$(BIN)/python -m bench

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

format: $(STAMP)
	$(BIN)/ruff format .

clean:
	rm -rf $(VENV) demo-output .pytest_cache
