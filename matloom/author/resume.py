"""What a resumed run may take from its record, and what must match it.

A run folder may come from anyone (a shared archive, a cloned repository), and ``record.json``
is plain JSON that anyone can edit. Two things follow:

* **Model access is never taken from the record unasked.** The server a key is sent to
  (``base_url``) and the variable the key is read from (``api_key_env``) come from the user's
  own config or flags: on ``--resume`` the user gives them again (``--base-url``/``--profile``,
  ``--critic-base-url``/``--critic-profile``) or says ``--trust-record``. A critic that used
  the generator's server follows the generator's new one. ``extra_body`` values are not stored
  (:func:`matloom.author.redact.redact_extra_body`), so a run that had them needs them again.
* **A resumed run is the same run.** A different prompt, or settings that change the result,
  would silently mix two runs in one record: :func:`differences` names them and the run stops.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from matloom.author.config import AuthorConfig, ConfigError, ModelSettings
from matloom.author.redact import has_redacted_values, redact_url

#: ModelSettings fields that say where requests go and which key they carry.
ENDPOINT_FIELDS: tuple[str, ...] = ("base_url", "api_key_env")
#: ModelSettings fields that change what a model answers (compared on resume).
ANSWER_FIELDS: tuple[str, ...] = (
    "provider",
    "model",
    "temperature",
    "reasoning_effort",
    "max_completion_tokens",
    "images",
)
#: AuthorConfig fields not compared on resume: the models (compared by ANSWER_FIELDS; their
#: access may change) and the preset's name (a label; its values are compared).
_NOT_COMPARED = frozenset({"generator", "critic", "settings_preset"})


@dataclass(frozen=True)
class AccessFlags:
    """Which model-access choices the user made again for a resumed run."""

    #: ``--base-url`` or ``--profile`` given (the generator's server is the user's).
    generator_endpoint: bool = False
    #: ``--profile`` given (its ``api_key_env`` is the user's too).
    generator_profile: bool = False
    critic_endpoint: bool = False
    critic_profile: bool = False
    #: ``--trust-record``: the recorded servers and key variables may be used.
    trust_record: bool = False


def endpoint(settings: ModelSettings | None) -> tuple[Any, ...]:
    """Where ``settings`` send requests and which key variable they name."""
    return tuple(getattr(settings, f) for f in ENDPOINT_FIELDS) if settings else ()


def _describe(settings: ModelSettings) -> str:
    parts = []
    if settings.base_url:
        parts.append(f"server {redact_url(settings.base_url)}")
    if settings.api_key_env:
        parts.append(f"key variable ${settings.api_key_env}")
    return " and ".join(parts)


def resumed_access(recorded: AuthorConfig, built: AuthorConfig, flags: AccessFlags) -> AuthorConfig:
    """``built`` (the recorded settings with the flags applied) with no model access adopted
    from the record that the user did not confirm; :class:`ConfigError` naming what to pass
    when the run needs it."""
    generator, problems = _role_access(
        "generator",
        recorded.generator,
        built.generator,
        confirmed=flags.generator_endpoint,
        from_profile=flags.generator_profile,
        trust=flags.trust_record,
        again="--base-url (or --profile)",
    )
    critic, critic_problems = built.critic, []
    follows = (
        recorded.critic is not None
        and flags.generator_endpoint
        and not flags.critic_endpoint
        and endpoint(recorded.critic) == endpoint(recorded.generator)
    )
    if follows and critic is not None and generator is not None:
        # The critic used the generator's server: it follows the generator's new one.
        update = {f: getattr(generator, f) for f in ENDPOINT_FIELDS}
        if recorded.critic.extra_body == recorded.generator.extra_body:  # type: ignore[union-attr]
            update["extra_body"] = generator.extra_body
        critic = critic.model_copy(update=update)
    else:
        critic, critic_problems = _role_access(
            "critic",
            recorded.critic,
            built.critic,
            confirmed=flags.critic_endpoint,
            from_profile=flags.critic_profile,
            trust=flags.trust_record,
            again="--critic-base-url (or --critic-profile)",
        )
    problems += critic_problems
    for role, settings in (("generator", generator), ("critic", critic)):
        if settings is not None and has_redacted_values(settings.extra_body):
            flag = "--extra-body (or --profile)" if role == "generator" else "--critic-profile"
            problems.append(
                f"the {role}'s extra_body had values that record.json does not store; "
                f"pass {flag} again"
            )
    if problems:
        raise ConfigError("--resume: " + "; ".join(problems))
    return built.model_copy(update={"generator": generator, "critic": critic})


def _role_access(  # noqa: PLR0913 - one role's recorded, built and confirmed access
    role: str,
    recorded: ModelSettings | None,
    built: ModelSettings | None,
    *,
    confirmed: bool,
    from_profile: bool,
    trust: bool,
    again: str,
) -> tuple[ModelSettings | None, list[str]]:
    if recorded is None or built is None or trust:
        return built, []
    if confirmed:
        if from_profile:
            return built, []
        # A server given again by --base-url: the recorded key variable is not adopted.
        return built.model_copy(update={"api_key_env": None}), []
    if not any(endpoint(recorded)):
        return built, []  # the default server and key variables: the user's environment
    return built, [
        f"record.json names the {role}'s {_describe(recorded)}; a record's servers and key "
        f"variables are used only with --trust-record (for a run folder you made): pass {again} "
        "again, or --trust-record"
    ]


def check_recorded_access(recorded: AuthorConfig, trust_record: bool) -> None:
    """:class:`ConfigError` when resuming ``recorded`` as it is would adopt model access from
    the record (a resume with no new settings; see :func:`resumed_access`)."""
    resumed_access(recorded, recorded, AccessFlags(trust_record=trust_record))


def _answer(settings: ModelSettings | None) -> dict[str, Any]:
    if settings is None:
        return {"model": "none (the material library)"}
    return {f: getattr(settings, f) for f in ANSWER_FIELDS}


def differences(recorded: AuthorConfig, given: AuthorConfig) -> list[str]:
    """The settings that differ between a run's record and the settings given to resume it,
    as ``name: recorded -> given`` (empty when the run may continue)."""
    found = []
    before, after = recorded.model_dump(), given.model_dump()
    for name in AuthorConfig.model_fields:
        if name not in _NOT_COMPARED and before[name] != after[name]:
            found.append(f"{name}: {before[name]!r} -> {after[name]!r}")
    roles = (
        ("generator", recorded.generator, given.generator),
        ("critic", recorded.critic_settings, given.critic_settings),
    )
    for role, old, new in roles:
        a, b = _answer(old), _answer(new)
        for name in a.keys() | b.keys():
            if a.get(name) != b.get(name):
                found.append(f"{role} {name}: {a.get(name)!r} -> {b.get(name)!r}")
    return sorted(found)
