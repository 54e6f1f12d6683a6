# MatLoom: two set-up commands. `make demo` runs the main job offline; `make test` runs the suite.
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
PIP := $(VENV)/bin/pip
DEMO_OUT ?= demo-output

.PHONY: demo test lint bench clean

$(VENV)/.installed-%: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PIP) install --quiet --upgrade pip
	$(PIP) install --quiet -e ".[$*]"
	touch $@

demo: $(VENV)/.installed-fast,llm
	$(VENV)/bin/matloom demo -o $(DEMO_OUT)

test: $(VENV)/.installed-fast,llm,test
	$(PY) -m pytest -q -n 2 -p no:cacheprovider

lint: $(VENV)/.installed-fast,llm,test
	$(VENV)/bin/ruff check matloom tests benchmarks
	$(VENV)/bin/ruff format --check matloom tests benchmarks

bench: $(VENV)/.installed-fast,llm
	$(PY) benchmarks/engine.py

clean:
	rm -rf $(VENV) $(DEMO_OUT) build *.egg-info
