# MatLoom: two set-up commands. `make demo` runs the main job offline; `make test` runs the suite.
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
PIP := $(VENV)/bin/pip
DEMO_OUT ?= demo-output

.PHONY: demo test lint bench clean clip-venv test-clip

$(VENV)/.installed-%: pyproject.toml setup.py matloom/engine/kernels/_cnoise.c
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

# Optional heavy extra (torch + open_clip, ~5.6 GB): its own venv so `make test` stays light.
CLIP_VENV ?= .venv-clip
ARCH := $(shell uname -m)
ifeq ($(ARCH),aarch64)
TORCH_PINS := torch==2.9.1 torchvision==0.24.1
else
TORCH_PINS := torch==2.14.1 torchvision==0.29.1
endif

clip-venv: $(CLIP_VENV)/.installed

$(CLIP_VENV)/.installed: pyproject.toml
	$(PYTHON) -m venv $(CLIP_VENV)
	$(CLIP_VENV)/bin/pip install --quiet --upgrade pip
	$(CLIP_VENV)/bin/pip install --quiet $(TORCH_PINS)
	$(CLIP_VENV)/bin/pip install --quiet -e ".[fast,llm,test,clip]" $(TORCH_PINS)
	touch $@

test-clip: $(CLIP_VENV)/.installed
	HF_HUB_OFFLINE=1 $(CLIP_VENV)/bin/python -m pytest -q -p no:cacheprovider -m clip tests/author

clean:
	rm -rf $(VENV) $(CLIP_VENV) $(DEMO_OUT) build *.egg-info
