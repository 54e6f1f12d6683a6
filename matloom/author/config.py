"""The one frozen configuration of an authoring run, shared by the CLI, the API and the record.

:class:`AuthorConfig` holds every tunable of the pipeline; the CLI builds one from its flags,
the API takes one as an argument, and ``record.json`` stores its dump, so a run can be resumed
with exactly the settings it started with. Model backends are described by :class:`ModelSettings`
and can be named in a ``matloom.toml`` file::

    [matloom]
    profile = "luna"            # used when no --profile/--model is given

    [profiles.luna]
    model = "openai/gpt-5.6-luna"
    base_url = "https://openrouter.ai/api/v1"
    api_key_env = "OPENROUTER_API_KEY"
    reasoning_effort = "low"

    [profiles.glm]
    model = "z-ai/glm-5.2"
    base_url = "https://openrouter.ai/api/v1"
    images = false              # text-only: the critic gets code and statistics, no render
    extra_body = { reasoning = { enabled = true } }

The file is looked up at ``$MATLOOM_CONFIG``, then ``~/.config/matloom/matloom.toml``: files
the user chose. A ``matloom.toml`` in the current folder may come from whoever made the folder
(a cloned repository, an unpacked archive), and a profile names the server that receives an API
key, so it is read only when named with ``--config``. It can also name settings presets
(``[settings.NAME]``, ``[matloom] settings``; :mod:`matloom.author.settings_presets`).
"""

from __future__ import annotations

import os
import tomllib
from pathlib import Path
from typing import Any, Literal

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    ValidationError,
    field_validator,
    model_validator,
)

#: The critic's configurable inputs (paper Sec. 4, Stage II).
CRITIC_SIGNALS: tuple[str, ...] = ("render", "stats", "code")
#: Name fragments of backbones known to take no image input (the paper's text-only critics).
TEXT_ONLY_MODEL_HINTS: tuple[str, ...] = ("deepseek", "glm")
#: Default reply-size cap in characters (``AuthorConfig.max_reply_chars``, ``--max-reply-chars``).
DEFAULT_MAX_REPLY_CHARS = 1_000_000
#: Preview layouts a critic can be shown (``--critic-views``): "both" sends flat, then lit.
CRITIC_VIEWS: dict[str, tuple[str, ...]] = {
    "flat": ("flat",),
    "lit": ("lit",),
    "both": ("flat", "lit"),
}


#: Largest image side of any size setting: the engine's ``Limits.max_resolution`` (docs/limits.md;
#: a test keeps the two equal), checked when the settings are made, before any model request.
MAX_SIZE = 8192
#: Key variables read when a model's settings name none, in order.
DEFAULT_KEY_VARIABLES: tuple[str, ...] = ("MATLOOM_API_KEY", "OPENAI_API_KEY")
#: The server the ``openai`` client talks to without a base URL (``$OPENAI_BASE_URL`` overrides).
DEFAULT_BASE_URL = "https://api.openai.com/v1"

#: Old names of ``AuthorConfig.start`` values, read as the new ones.
START_ALIASES: dict[str, str] = {"builtin": "library"}


class ConfigError(ValueError):
    """A configuration file or value is invalid; the message says what to change."""


class ModelSettings(BaseModel):
    """How to reach one chat model (generator or critic)."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    provider: str = "openai"
    model: str
    base_url: str | None = None
    #: Environment variable holding the key (then the only one read); unset: MATLOOM_API_KEY,
    #: else OPENAI_API_KEY.
    api_key_env: str | None = None
    temperature: float | None = Field(None, allow_inf_nan=False)
    reasoning_effort: str | None = None
    extra_body: dict[str, Any] | None = None
    max_completion_tokens: int | None = Field(65536, ge=1)
    #: Seconds one request may take (checked here, so a bad value fails before any request).
    timeout_s: float = Field(600.0, gt=0, le=86_400, allow_inf_nan=False)
    #: Attempts after the first on 429 / 5xx / timeouts / connection errors.
    max_retries: int = Field(5, ge=0, le=100)
    #: First back-off delay; attempt r waits backoff_s * 1.5**r plus up to backoff_s of jitter.
    backoff_s: float = Field(1.0, ge=0, le=3_600, allow_inf_nan=False)
    #: Whether the model accepts image input; ``None`` guesses from the model name.
    images: bool | None = None

    @property
    def accepts_images(self) -> bool:
        """Image capability: the explicit flag, else False for known text-only backbones."""
        if self.images is not None:
            return self.images
        name = self.model.lower()
        return not any(hint in name for hint in TEXT_ONLY_MODEL_HINTS)


class AuthorConfig(BaseModel):
    """Every setting of the three-stage pipeline (defaults = the paper's recorded settings)."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    #: Generator backend; ``None`` means the offline author (the material library).
    generator: ModelSettings | None = None
    #: Critic backend; ``None`` means "same as the generator" (a fresh, stateless conversation).
    critic: ModelSettings | None = None
    #: Who writes P0 when a generator is configured: the model (Stage I), or the material
    #: library (:func:`matloom.library.author`), whose program the model then sees as its own
    #: first answer and revises in Stage II. ``"builtin"`` (the name before the library) is read
    #: as ``"library"``. Irrelevant without a generator (the library is used anyway).
    start: Literal["model", "library"] = "model"
    #: Take the N-th candidate of the library's ranking (1 = the best) instead of the best,
    #: wherever the library writes P0 (``--pick``); ``None`` takes the best.
    pick: int | None = Field(None, ge=1)
    #: User library folders (resolved paths, a later one wins) whose entries the library
    #: ranks with its own wherever it writes P0 (``--library``, ``$MATLOOM_LIBRARY_PATH``;
    #: :func:`matloom.library.user.library_for`); empty: the built-in entries only.
    library_dirs: tuple[str, ...] = ()
    #: Show the generator the material library's programs for the request from its N best
    #: candidates, to reuse or ignore (:mod:`matloom.author.library_refs`); 0: none (the
    #: paper's). Not used with ``start = "library"``, where the library's program is P0.
    library_refs: int = Field(0, ge=0, le=5)
    #: First drafts the generator writes before revising (``--drafts``): each later draft is
    #: asked to take a different approach from the earlier ones, every draft is critiqued and
    #: the revisions continue from the best (the critic's score, or the scorer's); 1: one
    #: program, as in the paper. Not used with ``start = "library"``.
    drafts: int = Field(1, ge=1, le=5)
    rounds: int = Field(5, ge=0)
    repair_turns: int = Field(3, ge=0)
    critic_signals: tuple[Literal["render", "stats", "code"], ...] = CRITIC_SIGNALS
    #: Which preview layouts the critic sees (one image each): the paper's head-on ``flat``
    #: swatch, the ``lit`` studio layout, or ``both``.
    critic_views: Literal["flat", "lit", "both"] = "flat"
    #: From round 1 on, the critic also sees the previous round's preview(s) and score and says
    #: whether this round is better (the paper's critic is stateless: off).
    critic_history: bool = False
    #: Stop revising once the critic asks for no changes (no suggestions, no edits); the
    #: paper always runs every round.
    stop_when_satisfied: bool = False
    #: Critic loop v3 (docs/authoring.md, "Critic loop v3"; all off in the paper):
    #: the critic's system prompt also holds the generator's "Resolution and previews" facts,
    #: how uncovered areas look in each preview and what each layout shows, measured.
    critic_previews: bool = False
    #: The critic may ask for structural changes (a new layer, another primitive) in its own
    #: answer field, not only for the smallest set of line-targeted numeric edits.
    critic_structural: bool = False
    #: Revise the best program so far (by the scorer's score when a scorer is used, else the
    #: critic's) instead of the latest; the revision turn says which one and why.
    revise_from_best: bool = False
    #: A revision whose previews differ from the program it revised by less than this (the
    #: mean absolute difference in levels of 255 at the critique size, the largest over the
    #: critic's layouts) is not critiqued, is reported to the generator as "no visible change"
    #: and counts toward stopping; None: never checked.
    no_change_threshold: float | None = Field(None, ge=0, le=255, allow_inf_nan=False)
    #: The loop stops after this many revisions with no visible change.
    no_change_limit: int = Field(2, ge=1)
    #: The revision turn lists the checker's warnings of the program it revises (a Define a
    #: built-in shadows, a layer that is never visible ...); the paper's does not.
    revision_warnings: bool = False
    #: Checker warnings answered with a repair turn, like errors, before a program is
    #: accepted (``W005``: a Define named ``e`` or ``pi``, which the built-in constant shadows,
    #: so the program silently renders something else); the paper's accepts every warning.
    refuse_warnings: tuple[str, ...] = ()
    #: The last program's critique asks for the score only (its suggestions cannot be used).
    score_only_last: bool = False
    #: Blender layouts to render the final material in after export ("flat", "staged"), into
    #: ``blender/<layout>.png`` of the run folder (empty: none; see docs/blender.md).
    blender_layouts: tuple[str, ...] = ()
    #: Size in pixels of those Blender renders.
    blender_size: int = Field(512, ge=16, le=4096)
    #: The critic's statistics: the paper's 28 statistics on a ``stats_grid`` grid, or the
    #: ``visible`` statistics computed at the critique resolution.
    critic_stats: Literal["paper", "visible"] = "paper"
    #: Attach the preview(s) of the program being revised to the revision turn when the
    #: generator accepts images.
    revision_images: bool = True
    critic_retries: int = Field(3, ge=0)
    #: Longest model reply read, in characters: a longer one is refused like any bad answer
    #: (the generator is asked again, the critic retried) and stored clipped to its start.
    max_reply_chars: int = Field(DEFAULT_MAX_REPLY_CHARS, ge=1_000)
    playbook: bool = True
    few_shot: bool = True
    #: Which few-shot examples the system prompt shows (``--examples``): the ``paper``'s six, or
    #: ``v3``, written in the language 2 and 3 idioms on subjects far from the benchmark
    #: prompts (:data:`matloom.author.prompts.system.EXAMPLE_SETS`).
    examples: Literal["paper", "v3"] = "paper"
    #: Scorer name from the scorer registry; "auto" = open_clip if its weights are local, else
    #: none; "none" = no scorer (critic-score selection, no seed search).
    scorer: str = "auto"
    scorer_weights: str | None = None
    variants: int = Field(1000, ge=0)
    critique_size: int = Field(512, ge=8, le=MAX_SIZE)
    select_size: int = Field(512, ge=8, le=MAX_SIZE)
    sweep_size: int = Field(256, ge=8, le=MAX_SIZE)
    stats_grid: int = Field(128, ge=8, le=MAX_SIZE)
    export_size: int = Field(512, ge=8, le=MAX_SIZE)
    sweep_jobs: int = Field(0, ge=0)
    seed: int = 0
    #: Make the final program tileable (``View(..., tileable=True)``) before it is exported,
    #: whatever wrote it. The library already makes its programs tileable wherever the material
    #: allows it, so without a model this only matters for entries that do not tile.
    tileable: bool = False
    #: The named settings preset these settings started from (``--settings``; recorded only).
    settings_preset: str | None = None
    #: A photo (PNG or JPEG) of the material to make (``--reference``): the generator and the
    #: critic see it beside the previews, the critic's statistics compare render and photo
    #: (:mod:`matloom.author.reference`). Given, ``tileable`` defaults to True.
    reference: str | None = None
    #: Fit the exposed numeric parameters after selection (``--polish``; :mod:`matloom.author.
    #: stages.polish`): ``none``, or ``cmaes`` (needs the ``polish`` extra).
    polish: Literal["none", "cmaes"] = "none"
    #: Most objective evaluations of the fit (renders, or critic calls: see
    #: ``polish_critic_calls``).
    polish_evaluations: int = Field(40, ge=2, le=100_000)
    #: Most seconds the fit's evaluations take (the guard's two critic calls not counted).
    polish_seconds: float = Field(120.0, gt=0, le=86_400, allow_inf_nan=False)
    #: Most critic calls when the critic is the fit's objective (no scorer, no reference).
    polish_critic_calls: int = Field(4, ge=2, le=1_000)
    #: Render size of the fit's evaluations (scorer and reference objectives).
    polish_size: int = Field(128, ge=16, le=MAX_SIZE)

    @model_validator(mode="before")
    @classmethod
    def _reference_tileable(cls, data: Any) -> Any:
        """A run with a reference photo makes a tileable material unless told otherwise."""
        if isinstance(data, dict) and data.get("reference") and "tileable" not in data:
            return {**data, "tileable": True}
        return data

    @field_validator("start", mode="before")
    @classmethod
    def _start_alias(cls, value: Any) -> Any:
        """``"builtin"`` (records and flags from before the library) means ``"library"``."""
        return START_ALIASES.get(value, value) if isinstance(value, str) else value

    @field_validator("refuse_warnings", mode="before")
    @classmethod
    def _warning_codes(cls, value: Any) -> Any:
        """Warning codes of the checker's table, upper-cased ("w005" is W005); an unknown code
        or an error code is refused (errors are always repaired)."""
        if isinstance(value, str):
            value = [value]
        if not isinstance(value, list | tuple):
            return value
        from matloom.lang.codes import CODES

        codes = tuple(str(v).strip().upper() for v in value)
        bad = [v for v in codes if v not in CODES or not v.startswith("W")]
        if bad:
            raise ValueError(f"not a checker warning code: {', '.join(bad)} (e.g. W005)")
        return codes

    @field_validator("critic_signals", mode="before")
    @classmethod
    def _parse_signals(cls, value: Any) -> Any:
        if isinstance(value, str):
            value = [s.strip() for s in value.split(",") if s.strip()]
        if isinstance(value, list | tuple):
            unknown = [s for s in value if s not in CRITIC_SIGNALS]
            if unknown:
                raise ValueError(
                    f"unknown critic signal(s) {unknown}; choose from {CRITIC_SIGNALS}"
                )
            return tuple(s for s in CRITIC_SIGNALS if s in value)
        return value

    @property
    def critic_settings(self) -> ModelSettings | None:
        """The critic backend (the generator's when no separate critic is configured)."""
        return self.critic or self.generator

    def critic_sees_render(self) -> bool:
        """True when the render is requested and the critic model can take images."""
        critic = self.critic_settings
        return "render" in self.critic_signals and critic is not None and critic.accepts_images

    def effective_signals(self) -> tuple[str, ...]:
        """The signals actually sent: the render is dropped for a text-only critic."""
        return tuple(s for s in self.critic_signals if s != "render" or self.critic_sees_render())

    @property
    def views(self) -> tuple[str, ...]:
        """The preview layouts of ``critic_views``, in the order the images are sent."""
        return CRITIC_VIEWS[self.critic_views]


# --------------------------------------------------------------------------- matloom.toml


def config_file_candidates() -> list[Path]:
    """Where ``matloom.toml`` is looked for without ``--config``, in order: only places the user
    chose (the current folder's file is not one; see the module docstring)."""
    paths = []
    env = os.environ.get("MATLOOM_CONFIG")
    if env:
        paths.append(Path(env))
    paths.append(Path.home() / ".config" / "matloom" / "matloom.toml")
    return paths


def find_config_file(path: str | os.PathLike[str] | None = None) -> Path | None:
    """The config file read: ``path`` (which must exist), else the first existing candidate."""
    if path is not None:
        if not Path(path).exists():
            raise ConfigError(f"config file {path} does not exist")
        return Path(path)
    return next((p for p in config_file_candidates() if p.exists()), None)


def ignored_local_config(used: Path | None) -> Path | None:
    """``./matloom.toml`` when it exists and is not the file read (it needs ``--config``)."""
    local = Path("matloom.toml")
    if not local.is_file():
        return None
    if used is not None and used.exists() and used.resolve() == local.resolve():
        return None
    return local


def load_config_file(path: str | os.PathLike[str] | None = None) -> dict[str, Any]:
    """The parsed TOML of ``path`` (or of the first existing default location); ``{}`` if none."""
    found = find_config_file(path)
    if found is None:
        return {}
    try:
        return tomllib.loads(found.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
        raise ConfigError(f"cannot read {found}: {one_line(e)}") from None


def one_line(err: Exception) -> str:
    """A one-line message: a pydantic error as ``field: problem (got value)`` items."""
    if isinstance(err, ValidationError):
        parts = []
        for item in err.errors():
            where = ".".join(str(x) for x in item["loc"]) or "value"
            got = repr(item.get("input"))
            got = got if len(got) <= 60 else got[:57] + "..."
            parts.append(f"{where}: {item['msg']} (got {got})")
        return "; ".join(parts)
    return " ".join(str(err).split())


def profile_names(data: dict[str, Any]) -> list[str]:
    """Names of the model profiles in a parsed config file."""
    return sorted(data.get("profiles", {}))


def default_profile_name(data: dict[str, Any]) -> str | None:
    """The profile a config file chooses by default (``[matloom] profile``), if any."""
    return data.get("matloom", {}).get("profile")


def resolve_profile(data: dict[str, Any], name: str | None) -> ModelSettings | None:
    """The :class:`ModelSettings` of profile ``name`` (or of the file's default profile)."""
    name = name or default_profile_name(data)
    if name is None:
        return None
    profiles = data.get("profiles", {})
    if name not in profiles:
        known = ", ".join(profile_names(data)) or "none defined"
        raise ConfigError(f"unknown model profile {name!r} (profiles: {known})")
    if not isinstance(profiles[name], dict):
        raise ConfigError(f"[profiles.{name}] must be a table of model settings")
    try:
        return ModelSettings(**profiles[name])
    except ValueError as e:
        raise ConfigError(f"profile {name!r} is invalid: {one_line(e)}") from None


def with_overrides(settings: ModelSettings | None, **overrides: Any) -> ModelSettings | None:
    """``settings`` with the non-None ``overrides`` applied (a new, validated frozen object).

    A ``model`` override with no base settings creates fresh settings for that model.
    """
    given = {k: v for k, v in overrides.items() if v is not None}
    if settings is None:
        if "model" not in given:
            return None
        return ModelSettings(**given)
    if not given:
        return settings
    return ModelSettings.model_validate({**settings.model_dump(), **given})


def key_variables(settings: ModelSettings) -> tuple[str, ...]:
    """The variables the API key is read from: the profile's ``api_key_env`` alone when it
    names one (another provider's key must not go to its server), else the defaults."""
    return (settings.api_key_env,) if settings.api_key_env else DEFAULT_KEY_VARIABLES


def api_key_source(settings: ModelSettings) -> str | None:
    """The name of the variable the API key is taken from (None when all are empty)."""
    return next((name for name in key_variables(settings) if os.environ.get(name)), None)


def api_key_for(settings: ModelSettings) -> str | None:
    """The API key: the value of :func:`api_key_source` (see :func:`key_variables`)."""
    name = api_key_source(settings)
    return os.environ[name] if name else None
