# MatLoom: two set-up commands. `make demo` runs the main job offline; `make test` runs the suite.
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
PIP := $(VENV)/bin/pip
DEMO_OUT ?= demo-output

.PHONY: demo studio studio-build studio-venv test-studio test lint bench clean clip-venv test-clip metrics-venv test-metrics dask-venv test-dask tools interop-venv test-interop blender-venv test-blender test-grid test-fuzz

$(VENV)/.installed-%: pyproject.toml setup.py matloom/engine/kernels/_cnoise.c
	$(PYTHON) -m venv $(VENV)
	$(PIP) install --quiet --upgrade pip
	$(PIP) install --quiet -e ".[$*]"
	touch $@

demo: $(VENV)/.installed-fast,llm
	$(VENV)/bin/matloom demo -o $(DEMO_OUT)

# The studio in the browser, on a copy of the demo material in ./matloom-studio/.
studio: $(VENV)/.installed-fast,llm,studio
	$(VENV)/bin/matloom studio

test: $(VENV)/.installed-fast,llm,test,studio,bench,polish tools
	$(PY) -m pytest -q -n 2 -p no:cacheprovider -m "not blender and not browser and not grid and not fuzz"

# The engine's 2,000 random programs (about 2 minutes on 2 cores), outside the default suite
# to keep it under 10 minutes; .ci/run runs it after `make test`.
test-fuzz: $(VENV)/.installed-fast,llm,test,studio,bench,polish
	$(PY) -m pytest -q -n 2 -p no:cacheprovider -m fuzz tests/engine/test_fuzz_engine.py

# The composer's full base x layout x motif product (about 19,000 programs; a few minutes).
test-grid: $(VENV)/.installed-fast,llm,test,studio,bench,polish
	$(PY) -m pytest -q -n 2 -p no:cacheprovider -m grid tests/library/test_compose_product.py

# Rebuild the studio's front end (studio-web/, TypeScript) into matloom/studio/static/ with the
# pinned toolchain in studio-web/package-lock.json. Only needed after changing studio-web/src:
# the built assets are committed, so installing MatLoom needs no node.
studio-build:
	cd studio-web && npm ci --no-audit --no-fund && node build.mjs

# The studio's real-browser tests: Playwright for Python driving Debian's chromium (headless,
# WebGL2 through SwiftShader), in their own venv. Without chromium they skip and say why.
STUDIO_VENV ?= .venv-studio
PLAYWRIGHT_VERSION ?= 1.65.3

studio-venv: $(STUDIO_VENV)/.installed

$(STUDIO_VENV)/.installed: pyproject.toml setup.py matloom/engine/kernels/_cnoise.c
	$(PYTHON) -m venv $(STUDIO_VENV)
	$(STUDIO_VENV)/bin/pip install --quiet --upgrade pip
	$(STUDIO_VENV)/bin/pip install --quiet -e ".[fast,llm,test,studio]" "playwright==$(PLAYWRIGHT_VERSION)"
	touch $@

test-studio: $(STUDIO_VENV)/.installed tools
	$(STUDIO_VENV)/bin/python -m pytest -q -p no:cacheprovider -m browser tests/studio/browser

# The Khronos glTF validator (npm) for the glTF preset tests, in a project-local folder. If npm
# or the registry is unreachable the tests that need it skip and say so; `make test` goes on.
TOOLS ?= .tools
GLTF_VALIDATOR_VERSION ?= 2.0.0-dev.3.10

tools:
	@if [ -f $(TOOLS)/node_modules/gltf-validator/index.js ]; then :; \
	elif command -v npm >/dev/null 2>&1; then \
	  npm install --silent --no-audit --no-fund --prefix $(TOOLS) gltf-validator@$(GLTF_VALIDATOR_VERSION) \
	    || echo "tools: could not install gltf-validator; its tests will be skipped" >&2; \
	else echo "tools: npm not found; the glTF validator tests will be skipped" >&2; fi

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

# The learned text-image metrics (CLIPScore, BLIPScore, VQAScore): the clip extra plus
# transformers in one heavy venv, which also runs the clip tests (CI builds only this one).
METRICS_VENV ?= .venv-metrics

metrics-venv: $(METRICS_VENV)/.installed

$(METRICS_VENV)/.installed: pyproject.toml
	$(PYTHON) -m venv $(METRICS_VENV)
	$(METRICS_VENV)/bin/pip install --quiet --upgrade pip
	$(METRICS_VENV)/bin/pip install --quiet $(TORCH_PINS)
	$(METRICS_VENV)/bin/pip install --quiet -e ".[fast,llm,test,metrics]" $(TORCH_PINS)
	touch $@

test-metrics: $(METRICS_VENV)/.installed
	HF_HUB_OFFLINE=1 TRANSFORMERS_OFFLINE=1 $(METRICS_VENV)/bin/python -m pytest -q -p no:cacheprovider -m "metrics or clip" tests/evaluation tests/author

# Optional dask extra (dask.distributed + pyarrow): `matloom dataset` and `bench` on a Dask
# cluster, tested on a real LocalCluster in its own venv; `make test` skips these tests.
DASK_VENV ?= .venv-dask

dask-venv: $(DASK_VENV)/.installed

$(DASK_VENV)/.installed: pyproject.toml setup.py matloom/engine/kernels/_cnoise.c
	$(PYTHON) -m venv $(DASK_VENV)
	$(DASK_VENV)/bin/pip install --quiet --upgrade pip
	$(DASK_VENV)/bin/pip install --quiet -e ".[fast,llm,test,bench,dask]"
	touch $@

test-dask: $(DASK_VENV)/.installed
	$(DASK_VENV)/bin/python -m pytest -q -p no:cacheprovider -m dask tests/evaluation

# Optional interop extra (MaterialX + usd-core): its own venv; `make test` skips these tests.
INTEROP_VENV ?= .venv-interop

interop-venv: $(INTEROP_VENV)/.installed

$(INTEROP_VENV)/.installed: pyproject.toml
	$(PYTHON) -m venv $(INTEROP_VENV)
	$(INTEROP_VENV)/bin/pip install --quiet --upgrade pip
	$(INTEROP_VENV)/bin/pip install --quiet -e ".[fast,test,interop]"
	touch $@

test-interop: $(INTEROP_VENV)/.installed
	$(INTEROP_VENV)/bin/python -m pytest -q -p no:cacheprovider -m interop tests/io

# Optional Blender path: the bpy module (bpy 5.0.x needs Python 3.11) in its own venv.
# Only bpy goes in it (its own numpy); MatLoom runs it as a separate process.
BLENDER_VENV ?= .venv-blender
BLENDER_PY ?= $(PYTHON)
BPY_VERSION ?= 5.0.1

blender-venv: $(BLENDER_VENV)/.installed

$(BLENDER_VENV)/.installed:
	$(BLENDER_PY) -m venv $(BLENDER_VENV)
	$(BLENDER_VENV)/bin/pip install --quiet --upgrade pip
	$(BLENDER_VENV)/bin/pip install --quiet bpy==$(BPY_VERSION)
	touch $@

test-blender: $(VENV)/.installed-fast,llm,test,studio $(BLENDER_VENV)/.installed
	MATLOOM_BLENDER_PYTHON=$(abspath $(BLENDER_VENV))/bin/python $(PY) -m pytest -q -p no:cacheprovider -m blender tests/blender tests/studio/test_api_blender.py

clean:
	rm -rf $(VENV) $(CLIP_VENV) $(METRICS_VENV) $(DASK_VENV) $(INTEROP_VENV) $(BLENDER_VENV) $(TOOLS) $(DEMO_OUT) build *.egg-info
