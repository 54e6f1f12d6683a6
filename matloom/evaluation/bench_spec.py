"""What a bench runs: its prompts (with their sources) and its systems (``NAME=SPEC``).

A SPEC is ``library`` (the offline author), ``profile:NAME`` (a model profile of the user's
``matloom.toml``, with the file's default settings preset), ``PRESET+profile:NAME`` (a settings
preset, built in or from the file, with that profile) or ``PRESET`` alone (with ``--profile`` or
the file's default profile). Model systems resolve to a frozen
:class:`~matloom.author.config.AuthorConfig`, which is what the cells are keyed by.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from matloom.author.batch import read_prompts
from matloom.author.config import AuthorConfig, ConfigError, resolve_profile
from matloom.author.settings_presets import default_preset, preset_names, preset_values

#: The paper's procedural-noise seeds, one per run.
PAPER_SEEDS: tuple[int, ...] = (42, 123, 2026)
#: Model settings that change how a request travels, not what it asks: left out of cell keys.
_TRANSPORT_FIELDS = ("timeout_s", "max_retries", "backoff_s", "api_key_env")


class BenchInputError(ValueError):
    """A bench request that cannot run (bad SPEC, prompts file, metric): one line for the user."""


@dataclass(frozen=True)
class BenchPrompt:
    """One benchmark prompt: a stable id, its text and its source (for the per-source tables)."""

    id: str
    text: str
    source: str


@dataclass(frozen=True)
class System:
    """A named system: ``spec`` as given, and ``config`` (None for the offline library)."""

    name: str
    spec: str
    config: AuthorConfig | None = None

    @property
    def uses_llm(self) -> bool:
        return self.config is not None

    def identity(self) -> dict[str, Any]:
        """What the system's cells are keyed by: the settings, without transport details."""
        if self.config is None:
            return {"author": "library"}
        data = self.config.model_dump(mode="json")
        for role in ("generator", "critic"):
            if data.get(role):
                for name in _TRANSPORT_FIELDS:
                    data[role].pop(name, None)
        return {"author": "model", "settings": data}


def read_bench_prompts(path: str | Path) -> list[BenchPrompt]:
    """The prompts of a JSON file in any format :func:`read_prompts` reads, with each entry's
    ``source`` (the file's stem where an entry names none)."""
    path = Path(path)
    if not path.is_file():
        raise BenchInputError(f"prompts file {path} does not exist")
    try:
        items = read_prompts(path)
        data: Any = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError) as err:
        raise BenchInputError(f"cannot read prompts from {path}: {one_line(err)}") from None
    entries = data.get("prompts") if isinstance(data, dict) else data
    out = []
    for item, entry in zip(items, entries, strict=True):
        source = entry.get("source") if isinstance(entry, dict) else None
        out.append(BenchPrompt(item.id, item.text, str(source) if source else path.stem))
    if not out:
        raise BenchInputError(f"{path} holds no prompts")
    return out


def parse_seeds(text: str, runs: int) -> tuple[int, ...]:
    """The first ``runs`` seeds of a comma-separated list."""
    try:
        seeds = tuple(int(s) for s in text.split(",") if s.strip())
    except ValueError:
        raise BenchInputError(f"--seeds {text!r}: give integers separated by commas") from None
    if runs < 1:
        raise BenchInputError(f"--runs {runs}: give at least 1")
    if len(seeds) < runs:
        raise BenchInputError(f"--runs {runs} needs {runs} seeds, --seeds gives {len(seeds)}")
    if len(set(seeds[:runs])) != runs:
        raise BenchInputError(f"--seeds {text!r}: the seeds of the runs must differ")
    return seeds[:runs]


def parse_system(
    arg: str, config_data: dict[str, Any], default_profile: str | None = None
) -> System:
    """``NAME=SPEC`` as a :class:`System` (model settings resolved from ``config_data``)."""
    name, sep, spec = arg.partition("=")
    name, spec = name.strip(), spec.strip()
    if not sep or not name or not spec:
        raise BenchInputError(f"--system {arg!r}: give NAME=SPEC (e.g. lib=library)")
    if not all(c.isalnum() or c in "_.-" for c in name):
        raise BenchInputError(f"--system {arg!r}: a name uses letters, digits, '_', '.' or '-'")
    if spec == "library":
        return System(name, spec)
    preset: str | None = None
    profile: str | None = None
    for part in spec.split("+"):
        part = part.strip()
        if part.startswith("profile:") and profile is None and part[8:]:
            profile = part[8:]
        elif part and ":" not in part and preset is None and part != "library":
            preset = part
        else:
            raise BenchInputError(
                f"--system {arg!r}: SPEC is library, profile:NAME, PRESET+profile:NAME or PRESET"
            )
    try:
        if preset is not None and preset not in preset_names(config_data):
            known = ", ".join(preset_names(config_data))
            raise BenchInputError(f"--system {arg!r}: unknown settings preset (presets: {known})")
        generator = resolve_profile(config_data, profile or default_profile)
        if generator is None:
            raise BenchInputError(
                f"--system {arg!r}: a model system needs a profile (SPEC +profile:NAME, "
                "--profile, or [matloom] profile in the config file)"
            )
        preset = preset or default_preset(config_data)
        values = preset_values(preset, config_data) if preset else {}
        config = AuthorConfig.model_validate({**values, "generator": generator})
        from matloom.author.pipeline import check_sizes

        check_sizes(config)
    except (ConfigError, ValueError) as err:
        if isinstance(err, BenchInputError):
            raise
        raise BenchInputError(f"--system {arg!r}: {one_line(err)}") from None
    return System(name, spec, config)


def one_line(err: BaseException) -> str:
    return " ".join(str(err).split()) or type(err).__name__
