"""The options of `matloom generate` and how they become one frozen :class:`AuthorConfig`.

Precedence, lowest first: the defaults (the paper's settings) or a resumed run's recorded
settings, the settings preset (``--settings``, or ``[matloom] settings`` in matloom.toml for a
new run), then the flags given on the command line. Model access comes from the model profile
(``--profile`` or matloom.toml's default) and the model flags; a resumed run takes the recorded
servers and key variables only with ``--trust-record`` (:mod:`matloom.author.resume`).
"""

from __future__ import annotations

import json
from typing import Any

import click
from click.core import ParameterSource

from matloom.author.config import MAX_SIZE, AuthorConfig, ModelSettings

#: Flags that map 1:1 onto AuthorConfig fields.
_CONFIG_FLAGS: dict[str, str] = {
    "rounds": "rounds",
    "variants": "variants",
    "scorer": "scorer",
    "scorer_weights": "scorer_weights",
    "critic_signals": "critic_signals",
    "seed": "seed",
    "repair_turns": "repair_turns",
    "sweep_jobs": "sweep_jobs",
    "critique_size": "critique_size",
    "select_size": "select_size",
    "sweep_size": "sweep_size",
    "export_size": "export_size",
    "stats_grid": "stats_grid",
    "playbook": "playbook",
    "few_shot": "few_shot",
    "examples": "examples",
    "start": "start",
    "library_refs": "library_refs",
    "drafts": "drafts",
    "pick": "pick",
    "max_reply_chars": "max_reply_chars",
    "tileable": "tileable",
    "critic_views": "critic_views",
    "critic_history": "critic_history",
    "stop_when_satisfied": "stop_when_satisfied",
    "blender_layouts": "blender_layouts",
    "blender_size": "blender_size",
    "critic_stats": "critic_stats",
    "revision_images": "revision_images",
    "revision_warnings": "revision_warnings",
    "refuse_warnings": "refuse_warnings",
    "reference": "reference",
    "polish": "polish",
    "polish_evaluations": "polish_evaluations",
    "polish_seconds": "polish_seconds",
    "polish_critic_calls": "polish_critic_calls",
    "polish_size": "polish_size",
}
#: Flags saying that the user asked for a scorer or a seed search (a skipped search is then
#: reported on stderr; otherwise it is only recorded).
SEARCH_FLAGS = frozenset({"scorer", "scorer_weights", "variants"})
#: Flags that override generator model settings.
_MODEL_FLAGS: dict[str, str] = {
    "model": "model",
    "base_url": "base_url",
    "temperature": "temperature",
    "reasoning_effort": "reasoning_effort",
    "timeout": "timeout_s",
    "max_retries": "max_retries",
    "images": "images",
    "retry_backoff": "backoff_s",
}


def explicit_flags(ctx: click.Context) -> set[str]:
    """Names of the options the user actually gave on the command line."""
    return {
        name
        for name in ctx.params
        if ctx.get_parameter_source(name) not in (ParameterSource.DEFAULT, None)
    }


def _generator_settings(
    params: dict[str, Any], given: set[str], base: ModelSettings | None
) -> ModelSettings | None:
    from matloom.author.config import load_config_file, resolve_profile, with_overrides

    data = load_config_file(params["config_file"])
    if "profile" in given or (base is None and "model" not in given):
        base = resolve_profile(data, params["profile"]) or base
    updates = {_MODEL_FLAGS[k]: params[k] for k in _MODEL_FLAGS if k in given}
    if params.get("extra_body"):
        updates["extra_body"] = _extra_body(params["extra_body"])
    return with_overrides(base, **updates)


def _extra_body(text: str) -> dict[str, Any]:
    """``--extra-body`` as a JSON object (ConfigError in one line otherwise)."""
    from matloom.author.config import ConfigError

    try:
        body = json.loads(text)
    except json.JSONDecodeError as err:
        raise ConfigError(f"--extra-body is not valid JSON: {err}") from None
    if not isinstance(body, dict):
        raise ConfigError("--extra-body must be a JSON object, e.g. '{\"reasoning\": {}}'")
    return body


def _critic_settings(
    params: dict[str, Any],
    given: set[str],
    generator: ModelSettings | None,
    base: ModelSettings | None,
) -> ModelSettings | None:
    from matloom.author.config import load_config_file, resolve_profile, with_overrides

    if "critic_profile" in given:
        base = resolve_profile(load_config_file(params["config_file"]), params["critic_profile"])
    if "critic_model" in given and generator is not None and base is None:
        base = generator.model_copy(update={"images": None})
    updates: dict[str, Any] = {}
    if "critic_model" in given:
        updates["model"] = params["critic_model"]
    if "critic_base_url" in given:
        updates["base_url"] = params["critic_base_url"]
    if "critic_images" in given:
        updates["images"] = params["critic_images"]
    return with_overrides(base, **updates)


def _preset_values(params: dict[str, Any], given: set[str], fresh: bool) -> dict[str, Any]:
    """The AuthorConfig values of the settings preset: ``--settings``, else (for a new run) the
    config file's default; {} when neither names one."""
    from matloom.author.config import load_config_file
    from matloom.author.settings_presets import default_preset, preset_values

    data = load_config_file(params["config_file"])
    name = params.get("settings") if "settings" in given else None
    if name is None and fresh:
        name = default_preset(data)
    return preset_values(name, data) if name is not None else {}


def _blender_layouts(_ctx: Any, _param: Any, value: str) -> tuple[str, ...]:
    """``flat,staged`` / ``both`` -> the layout names, in order, without repeats."""
    names: list[str] = []
    for part in (p.strip() for p in value.split(",") if p.strip()):
        for name in ("flat", "staged") if part == "both" else (part,):
            if name not in ("flat", "staged"):
                raise click.BadParameter(f"unknown layout {name!r}: use flat, staged or both")
            if name not in names:
                names.append(name)
    return tuple(names)


def _absolute(_ctx: Any, _param: Any, value: str | None) -> str | None:
    """A path made absolute (not resolved: the photo's own checks see the path given)."""
    import os

    return None if value is None else os.path.abspath(value)


def build_config(
    params: dict[str, Any],
    given: set[str],
    base: AuthorConfig | None = None,
    *,
    trust_record: bool = False,
    library_env: str | None = None,
) -> AuthorConfig:
    """The frozen config: the defaults (or ``base``, a resumed run's settings), then the
    settings preset (``--settings`` or matloom.toml's default), then the explicit flags; model
    access comes from the profile and model flags, and from ``base`` only as far as the user
    confirms it (:func:`matloom.author.resume.resumed_access`). The user library folders are
    ``library_env``'s (the value of ``$MATLOOM_LIBRARY_PATH``, for a new run) then ``--library``'s;
    a resumed run keeps its recorded ones unless ``--library`` is given."""
    from matloom.author.resume import AccessFlags, resumed_access

    recorded = base
    base = base or AuthorConfig()
    preset = _preset_values(params, given, recorded is None)
    update: dict[str, Any] = {
        field: params[flag] for flag, field in _CONFIG_FLAGS.items() if flag in given
    }
    if "library_dirs" in given or (recorded is None and library_env):
        from matloom.library.user import library_dirs

        env = library_env if recorded is None else None
        update["library_dirs"] = tuple(str(d) for d in library_dirs(params["library_dirs"], env))
    generator = _generator_settings(params, given, base.generator)
    critic = _critic_settings(params, given, generator, base.critic)
    data = {**base.model_dump(), **preset, **update, "generator": generator, "critic": critic}
    if recorded is None and data.get("reference") and not {"tileable"} & (given | set(preset)):
        data["tileable"] = True  # a material from a photo is tileable unless --no-tileable
    config = AuthorConfig.model_validate(data)
    if recorded is None:
        return config
    flags = AccessFlags(
        generator_endpoint=bool({"base_url", "profile"} & given),
        generator_profile="profile" in given,
        critic_endpoint=bool({"critic_base_url", "critic_profile"} & given),
        critic_profile="critic_profile" in given,
        trust_record=trust_record,
    )
    return resumed_access(recorded, config, flags)


def model_options(f: Any) -> Any:
    options = [
        click.option("--profile", help="Model profile from matloom.toml."),
        click.option(
            "--config",
            "config_file",
            type=click.Path(dir_okay=False),
            help="Config file (default: $MATLOOM_CONFIG, else ~/.config/matloom/matloom.toml; "
            "a matloom.toml in the current folder is read only when named here).",
        ),
        click.option("--model", help="Generator model id (OpenAI-compatible)."),
        click.option(
            "--base-url", help="Chat Completions endpoint, e.g. http://localhost:8000/v1."
        ),
        click.option("--temperature", type=float),
        click.option("--reasoning-effort"),
        click.option("--extra-body", help="JSON object merged into each request body."),
        click.option("--timeout", type=float, help="Seconds per model request."),
        click.option("--max-retries", type=int, help="Retries on 429/5xx/timeouts."),
        click.option(
            "--retry-backoff",
            type=float,
            help="First retry delay in seconds (grows 1.5x per retry).",
        ),
        click.option(
            "--images/--no-images",
            default=None,
            help="Whether the generator model accepts images (default: guessed).",
        ),
        click.option("--critic-model", help="Critic model (default: the generator's)."),
        click.option("--critic-profile", help="Critic model profile from matloom.toml."),
        click.option("--critic-base-url"),
        click.option(
            "--critic-images/--no-critic-images",
            default=None,
            help="Whether the critic accepts images; text-only critics get no render.",
        ),
    ]
    for option in reversed(options):
        f = option(f)
    return f


def pipeline_options(f: Any) -> Any:
    d = AuthorConfig()
    options = [
        click.option(
            "--settings",
            help="Named settings preset: recommended (both previews, critic history, visible "
            "statistics), paper (the paper's settings, the defaults) or one from matloom.toml; "
            "other flags override it.",
        ),
        click.option(
            "--start",
            type=click.Choice(["model", "library", "builtin"]),
            default=d.start,
            show_default=True,
            help="Who writes P0 when a model is configured: the model, or the material library "
            "(the model then critiques and revises it); builtin is the old name of library.",
        ),
        click.option(
            "--pick",
            type=click.IntRange(min=1),
            default=None,
            help="Take the N-th library candidate instead of the best (see --explain for the "
            "ranking); wherever the library writes the program.",
        ),
        click.option(
            "--library",
            "library_dirs",
            multiple=True,
            type=click.Path(file_okay=False),
            help="A user library folder (repeatable), after those of $MATLOOM_LIBRARY_PATH: "
            "its entries are ranked with the built-in ones wherever the library writes the "
            "program (docs/library.md).",
        ),
        click.option("--rounds", type=int, default=d.rounds, show_default=True),
        click.option(
            "--variants",
            type=int,
            default=d.variants,
            show_default=True,
            help="Seed variants per candidate in the seed search.",
        ),
        click.option(
            "--scorer",
            default=d.scorer,
            show_default=True,
            help="auto, none, mobileclip2, open_clip:MODEL:WEIGHTS, test-colour, ...",
        ),
        click.option("--scorer-weights", help="Local MobileCLIP2-S2 weights file."),
        click.option("--critic-signals", default=",".join(d.critic_signals), show_default=True),
        click.option(
            "--critic-views",
            type=click.Choice(["flat", "lit", "both"]),
            default=d.critic_views,
            show_default=True,
            help="Preview layouts the critic sees: the flat head-on swatch, the lit studio "
            "layout, or both (two images).",
        ),
        click.option(
            "--critic-history/--no-critic-history",
            default=d.critic_history,
            show_default=True,
            help="The critic also sees the previous round's preview and score and says whether "
            "this round is better.",
        ),
        click.option(
            "--blender-layouts",
            callback=_blender_layouts,
            default="",
            help="Render the final material in these Blender layouts after export "
            "(flat,staged or both) into blender/<layout>.png; Blender as for `matloom blender`.",
        ),
        click.option(
            "--blender-size",
            type=click.IntRange(16, 4096),
            default=d.blender_size,
            show_default=True,
            help="Size in pixels of the --blender-layouts renders.",
        ),
        click.option(
            "--stop-when-satisfied/--all-rounds",
            "stop_when_satisfied",
            default=d.stop_when_satisfied,
            show_default=True,
            help="Stop revising once the critic asks for no changes (recommended), or run every "
            "round (the paper).",
        ),
        click.option(
            "--critic-stats",
            type=click.Choice(["paper", "visible"]),
            default=d.critic_stats,
            show_default=True,
            help="The critic's statistics: the paper's 28 on --stats-grid, or those of what is "
            "visible at --critique-size.",
        ),
        click.option(
            "--revision-images/--no-revision-images",
            default=d.revision_images,
            show_default=True,
            help="Attach the previews to the revision turn when the generator takes images.",
        ),
        click.option(
            "--revision-warnings/--no-revision-warnings",
            default=d.revision_warnings,
            show_default=True,
            help="List the checker's warnings of the program being revised in the revision "
            "turn (the recommended settings: on).",
        ),
        click.option(
            "--refuse-warning",
            "refuse_warnings",
            multiple=True,
            default=d.refuse_warnings,
            show_default=True,
            help="A checker warning code (W005: a Define a built-in constant shadows) answered "
            "with a repair turn like an error; repeat for several (recommended: W005).",
        ),
        click.option("--seed", type=int, default=d.seed, show_default=True),
        click.option("--repair-turns", type=int, default=d.repair_turns, show_default=True),
        click.option(
            "--sweep-jobs",
            type=int,
            default=d.sweep_jobs,
            show_default=True,
            help="Render processes per sweep (0 = all cores).",
        ),
        click.option("--critique-size", type=int, default=d.critique_size, show_default=True),
        click.option("--select-size", type=int, default=d.select_size, show_default=True),
        click.option("--sweep-size", type=int, default=d.sweep_size, show_default=True),
        click.option("--export-size", type=int, default=d.export_size, show_default=True),
        click.option("--stats-grid", type=int, default=d.stats_grid, show_default=True),
        click.option(
            "--max-reply-chars",
            type=int,
            default=d.max_reply_chars,
            show_default=True,
            help="Longest model reply read; a longer one is refused as a bad answer.",
        ),
        click.option("--playbook/--no-playbook", default=d.playbook, show_default=True),
        click.option("--few-shot/--no-few-shot", default=d.few_shot, show_default=True),
        click.option(
            "--examples",
            type=click.Choice(["paper", "v3"]),
            default=d.examples,
            show_default=True,
            help="The few-shot examples: the paper's six, or v3 (language 2 and 3 idioms, "
            "subjects far from the benchmark; the recommended settings' choice).",
        ),
        click.option(
            "--library-refs",
            type=click.IntRange(0, 5),
            default=d.library_refs,
            show_default=True,
            help="Show the generator the library's programs for the request from its N best "
            "candidates, to reuse or ignore (the recommended settings: 2).",
        ),
        click.option(
            "--drafts",
            type=click.IntRange(1, 5),
            default=d.drafts,
            show_default=True,
            help="First drafts the generator writes, each a different approach; every draft "
            "is critiqued and the revisions continue from the best (1: the paper's one "
            "program).",
        ),
        click.option(
            "--tileable/--no-tileable",
            default=d.tileable,
            help="Make the final material tileable (View(..., tileable=True)); the library "
            "already does where the material allows it. On by default with --reference.",
        ),
        click.option(
            "--reference",
            type=click.Path(dir_okay=False),
            callback=_absolute,
            help="A photo (PNG or JPEG) of the material to make: the generator and the critic "
            "see it beside the previews, the critic's statistics compare render and photo; "
            "the record keeps its SHA-256, not the photo.",
        ),
        click.option(
            "--polish",
            type=click.Choice(["none", "cmaes"]),
            default=d.polish,
            show_default=True,
            help="After selection, fit the exposed numeric parameters with CMA-ES (against "
            "the scorer, else the --reference statistics, else the critic); the fit is kept "
            "only if the critic does not score it lower. Needs the polish extra.",
        ),
        click.option(
            "--polish-evaluations",
            type=click.IntRange(2, 100_000),
            default=d.polish_evaluations,
            show_default=True,
            help="Most renders the fit scores.",
        ),
        click.option(
            "--polish-seconds",
            type=click.FloatRange(min=0, min_open=True, max=86_400),
            default=d.polish_seconds,
            show_default=True,
            help="Most seconds the fit's evaluations take.",
        ),
        click.option(
            "--polish-critic-calls",
            type=click.IntRange(2, 1_000),
            default=d.polish_critic_calls,
            show_default=True,
            help="Most critic calls when the critic is the fit's objective.",
        ),
        click.option(
            "--polish-size",
            type=click.IntRange(16, MAX_SIZE),
            default=d.polish_size,
            show_default=True,
            help="Render size of the fit's evaluations.",
        ),
    ]
    for option in reversed(options):
        f = option(f)
    return f
