"""Named settings presets for the authoring pipeline (``--settings NAME``, ``matloom.toml``).

A preset is a set of :class:`~matloom.author.config.AuthorConfig` values applied over the
defaults; explicit command-line flags then override it. Two are built in:

* ``paper``: the paper's recorded settings, for reproduction (they are the defaults): the flat
  preview only, a stateless critic, the 28 statistics on a 128 x 128 grid, 5 rounds.
* ``recommended``: what works best with a strong model: the critic sees the ``flat`` and ``lit``
  previews, the previous round's preview and score (``critic_history``) and the statistics of
  what is visible at the critique resolution; 5 rounds; the seed search runs when a scorer is
  available (``scorer = "auto"``) and is skipped quietly otherwise. Critic loop v3: the critic
  knows the resolution and what each preview shows and may ask for structural changes, a
  revision continues from the best program so far, a revision with no visible change is
  reported and counts toward stopping, and the last critique asks for the score only. The
  generator writes three first drafts, each a different approach, and the revisions continue
  from the best (``drafts``); the library's programs for the request go with the first turn.

``matloom.toml`` can choose one by default and define its own, on top of a built-in one::

    [matloom]
    settings = "recommended"    # used when no --settings is given

    [settings.quick]
    base = "recommended"        # optional: start from a built-in or another preset
    rounds = 2
    variants = 200

Model backends are not settings: they are named by ``[profiles.NAME]`` (``--profile``).
"""

from __future__ import annotations

from typing import Any

from matloom.author.config import AuthorConfig, ConfigError
from matloom.lang.codes import Code

#: The recommended ``no_change_threshold`` in levels of 255 (measured with
#: ``benchmarks/visible_change.py``; docs/authoring.md, "Critic loop v3").
NO_CHANGE_THRESHOLD = 3.0
#: The built-in presets: AuthorConfig fields over the defaults.
BUILTIN_PRESETS: dict[str, dict[str, Any]] = {
    "paper": {},
    "recommended": {
        "critic_views": "both",
        "critic_history": True,
        "critic_stats": "visible",
        "stop_when_satisfied": True,
        "rounds": 5,
        "scorer": "auto",
        "critic_previews": True,
        "critic_structural": True,
        "revise_from_best": True,
        "no_change_threshold": NO_CHANGE_THRESHOLD,
        "score_only_last": True,
        "examples": "v3",
        "library_refs": 2,
        "drafts": 3,
        "revision_warnings": True,
        "refuse_warnings": (Code.SHADOWED_DEFINE.code,),
    },
}
#: Config fields a preset may not set (models come from profiles; the name is recorded).
_NOT_SETTINGS = frozenset({"generator", "critic", "settings_preset"})
#: Longest ``base = ...`` chain followed (a cycle is an error long before).
_MAX_DEPTH = 8


def preset_names(data: dict[str, Any] | None = None) -> list[str]:
    """The built-in preset names, then those defined in a parsed ``matloom.toml``."""
    custom = sorted(set((data or {}).get("settings", {})) - set(BUILTIN_PRESETS))
    return [*BUILTIN_PRESETS, *custom]


def preset_values(name: str, data: dict[str, Any] | None = None) -> dict[str, Any]:
    """The AuthorConfig values of preset ``name`` (its ``base`` chain resolved), validated."""
    values = _resolve(name, data or {}, depth=0)
    try:
        AuthorConfig.model_validate(values)
    except ValueError as err:
        raise ConfigError(f"settings preset {name!r} is invalid: {err}") from None
    return {**values, "settings_preset": name}


def default_preset(data: dict[str, Any]) -> str | None:
    """The preset ``matloom.toml`` chooses by default (``[matloom] settings``), if any."""
    name = data.get("matloom", {}).get("settings")
    if name is not None and not isinstance(name, str):
        raise ConfigError("[matloom] settings must be the name of a settings preset")
    return name


def _resolve(name: str, data: dict[str, Any], depth: int) -> dict[str, Any]:
    if depth > _MAX_DEPTH:
        raise ConfigError(f"settings preset {name!r}: the base chain is too long (a cycle?)")
    custom = data.get("settings", {})
    if name in custom:
        table = custom[name]
        if not isinstance(table, dict):
            raise ConfigError(f"[settings.{name}] must be a table of settings")
        table = dict(table)
        base = table.pop("base", None)
        forbidden = sorted(_NOT_SETTINGS & set(table))
        if forbidden:
            raise ConfigError(
                f"[settings.{name}] cannot set {', '.join(forbidden)}: models are chosen with "
                "[profiles.NAME] and --profile"
            )
        inherited = _resolve(base, data, depth + 1) if base is not None else {}
        return {**inherited, **table}
    if name in BUILTIN_PRESETS:
        return dict(BUILTIN_PRESETS[name])
    raise ConfigError(
        f"unknown settings preset {name!r} (presets: {', '.join(preset_names(data))})"
    )
