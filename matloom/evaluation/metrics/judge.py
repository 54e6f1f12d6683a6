"""The MLLM judge: any OpenAI-compatible multimodal model scores how well a render matches its
prompt, on [0, 100], with the paper's critic schema at temperature 0.

Protocol (the paper's evaluation, ``../shared/spec/evaluation.md``): one fresh conversation per
sample and layout; the system prompt casts the model as a material-appearance judge that sees
only the render; the user turn holds the description and the image; the answer is the critic's
JSON (``match_score`` "0-100, how well the image matches the description", ``differences``,
``suggestions``: the field descriptions verbatim from the paper's appendix, as
:mod:`matloom.author.prompts.critic` states them), parsed leniently by
:func:`~matloom.author.stages.critique_parse.parse_critique`. Temperature is forced to 0.

Values: ``judge.<layout>`` per layout scored (``quick`` by default: the flat quick preview;
``flat``/``staged``: the Blender layouts, when asked and present; a layout a sample has no
image of is left out) and ``judge.score``, their mean. :attr:`JudgeMetric.reasons` keeps, per
sample id and layout, the judge's differences and suggestions (or why there is no score).

Where the model is: only the user's configuration (``options``: ``profile`` of the
``matloom.toml`` named by ``config`` or found at the usual places, and/or ``model``,
``base_url``, ``api_key_env``; the key is read from the environment variable the settings
name, as every model call does). Retries: 429, 5xx, timeouts and bad HTTP replies by the model
client (``max_retries``, ``backoff_s``), then up to ``parse_retries`` follow-ups for answers
that are not the JSON asked for (NaN after that). A permanent failure (a refused key, an
unreachable server) raises :class:`~matloom.author.llm.base.ModelError`: every other sample
would fail the same way.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from matloom.author.config import (
    DEFAULT_MAX_REPLY_CHARS,
    ConfigError,
    ModelSettings,
    load_config_file,
    one_line,
    resolve_profile,
    with_overrides,
)
from matloom.author.llm import BadReplyError, ChatMessage, ImageInput, ModelError, get_model
from matloom.author.llm.base import ChatModel, complete_within
from matloom.author.prompts.critic import critic_retry_message, response_skeleton
from matloom.author.stages.critique_parse import CritiqueParseError, parse_critique
from matloom.evaluation.metrics.base import MetricUnavailableError, Sample, register_metric

FAMILY = "judge"
#: Layouts judged unless asked otherwise: the flat quick preview.
DEFAULT_LAYOUTS: tuple[str, ...] = ("quick",)
#: Follow-ups after an answer that is not the JSON asked for (then the score is NaN).
PARSE_RETRIES = 2
#: The judge's sampling temperature (the paper: zero).
TEMPERATURE = 0.0
#: Longest answer read, in characters (a longer one counts as unparseable).
MAX_REPLY_CHARS = DEFAULT_MAX_REPLY_CHARS
#: Settings the options may give besides a profile (as the ``generate`` flags do).
SETTING_OPTIONS = (
    "provider",
    "model",
    "base_url",
    "api_key_env",
    "timeout_s",
    "max_retries",
    "backoff_s",
    "max_completion_tokens",
    "reasoning_effort",
    "images",
)
#: What the judge is told about each layout's image.
LAYOUT_NOTES: dict[str, str] = {
    "quick": (
        "a fast preview: the material on a flat plane seen head-on under one fixed light; "
        "little relief, reflectance or transmission is visible in it, so do not over-penalise "
        "those"
    ),
    "flat": "a path-traced render of the material on a flat plane seen head-on in a studio",
    "staged": (
        "a path-traced render of the material on an upright plane in a grey room, with objects "
        "behind it and reflected in it, seen from slightly above and to the side"
    ),
}
_MIME = {".png": "image/png", ".jpg": "image/jpeg", ".jpeg": "image/jpeg", ".webp": "image/webp"}


def judge_system_prompt(layout: str) -> str:
    """The judge's system prompt for one layout."""
    note = LAYOUT_NOTES.get(layout, f"a render of the material ({layout} layout)")
    return (
        "You are a meticulous material-appearance judge.\n\n"
        "You are shown:\n- the target description\n- one image of a material: " + note + "\n\n"
        "Judge only from visible appearance (colour, gloss, pattern and structure, scale, "
        "relief, special qualities) how well the image matches the description; never assume "
        "anything about how the material was made. Be specific.\n"
    )


def judge_user_text(description: str) -> str:
    """The user turn's text (the image follows it)."""
    notes = "match_score is a number, not a string."
    return (
        "## Objective\nCompare the attached image against the description "
        f"<description>{description}</description>.\n\n"
        "## Style\nJSON only: no preamble, no markdown, no missing or extra fields.\n\n"
        "## Response\nAnswer with exactly this structure:\n"
        + response_skeleton(edits=False)
        + "\n"
        + notes
    )


def image_input(path: Path) -> ImageInput:
    """The image file as a chat attachment (PNG, JPEG or WebP)."""
    mime = _MIME.get(path.suffix.lower())
    if mime is None:
        raise ValueError(f"{path.name}: not a PNG, JPEG or WebP image")
    return ImageInput(data=path.read_bytes(), mime=mime, path=str(path))


class JudgeMetric:
    """Scores samples with a chat model (see the module docstring)."""

    def __init__(
        self,
        name: str,
        settings: ModelSettings,
        layouts: Sequence[str] = DEFAULT_LAYOUTS,
        parse_retries: int = PARSE_RETRIES,
    ) -> None:
        self._name = name
        self.settings = settings
        self._layouts = tuple(layouts)
        self.parse_retries = parse_retries
        self._model: ChatModel | None = None
        #: Sample id -> layout -> what the judge said: ``score``, ``differences``,
        #: ``suggestions``, ``attempts``, or ``error`` when there is no score.
        self.reasons: dict[str, dict[str, dict[str, Any]]] = {}

    def __getstate__(self) -> dict[str, Any]:
        """Picklable (to ship to workers): the model client is made again where it is used."""
        state = dict(self.__dict__)
        state["_model"] = None
        return state

    @property
    def name(self) -> str:
        return self._name

    @property
    def layouts(self) -> tuple[str, ...]:
        return self._layouts

    @property
    def model(self) -> ChatModel:
        """The chat model (made on first use)."""
        if self._model is None:
            self._model = get_model(self.settings)
        return self._model

    def judge(self, description: str, image: ImageInput, layout: str) -> dict[str, Any]:
        """One fresh judgement: ``score`` (NaN when no usable answer came) and the reasons."""
        messages = [
            ChatMessage("system", judge_system_prompt(layout)),
            ChatMessage("user", judge_user_text(description), (image,)),
        ]
        problem = ""
        for attempt in range(1, self.parse_retries + 2):
            try:
                reply = complete_within(self.model, messages, MAX_REPLY_CHARS)
            except BadReplyError as err:
                return {"score": math.nan, "attempts": attempt, "error": str(err)}
            try:
                if reply.cut_at_bytes is not None:
                    raise CritiqueParseError(f"the answer is over {MAX_REPLY_CHARS} characters")
                critique = parse_critique(reply.text)
            except CritiqueParseError as err:
                problem = str(err)
                messages += [
                    ChatMessage("assistant", reply.text[:2000]),
                    ChatMessage("user", critic_retry_message(problem, edits=False)),
                ]
                continue
            return {
                "score": float(critique.match_score),
                "differences": list(critique.differences),
                "suggestions": list(critique.suggestions),
                "attempts": attempt,
            }
        return {
            "score": math.nan,
            "attempts": self.parse_retries + 1,
            "error": f"no usable answer: {problem}",
        }

    def score_one(self, sample: Sample) -> dict[str, float]:
        """``judge.<layout>`` for each layout the sample has, and ``judge.score``."""
        out: dict[str, float] = {}
        said: dict[str, dict[str, Any]] = {}
        for layout in self._layouts:
            path = sample.images.get(layout)
            if path is None:
                continue
            try:
                image = image_input(Path(path))
            except (OSError, ValueError) as err:
                said[layout] = {"score": math.nan, "attempts": 0, "error": str(err)}
            else:
                said[layout] = self.judge(sample.prompt, image, layout)
            out[f"{FAMILY}.{layout}"] = said[layout]["score"]
        self.reasons[sample.id] = said
        scores = list(out.values())
        out[f"{FAMILY}.score"] = math.fsum(scores) / len(scores) if scores else math.nan
        return out

    def score(self, samples: Sequence[Sample]) -> list[dict[str, float]]:
        self.reasons = {}
        return [self.score_one(sample) for sample in samples]


def settings_from_options(options: Mapping[str, Any]) -> ModelSettings:
    """The judge's model settings: the ``profile`` (of the ``config`` file, else of the user's
    ``matloom.toml``) with the other options over it, at temperature 0."""
    try:
        data = load_config_file(options.get("config"))
        base = resolve_profile(data, options.get("profile"))
        given = {k: options[k] for k in SETTING_OPTIONS if options.get(k) is not None}
        settings = with_overrides(base, **given, temperature=TEMPERATURE)
        if settings is None:
            raise MetricUnavailableError(
                "the judge needs a model: give a profile (a matloom.toml [profiles.NAME]) or "
                "a model and base_url"
            )
    except ConfigError as err:
        raise MetricUnavailableError(f"judge: {err}") from None
    except ValueError as err:  # pydantic's ValidationError
        raise MetricUnavailableError(f"judge: {one_line(err)}") from None
    if not settings.accepts_images:
        raise MetricUnavailableError(
            f"judge: model {settings.model!r} takes no images (images=false); the judge needs a "
            "multimodal model"
        )
    return settings


def _layouts(name: str, options: Mapping[str, Any]) -> tuple[str, ...]:
    _, _, rest = name.partition(":")
    value = options.get("layouts", rest or DEFAULT_LAYOUTS)
    if isinstance(value, str):
        value = [part.strip() for part in value.split(",") if part.strip()]
    layouts = tuple(value)
    if not layouts:
        raise MetricUnavailableError("judge: no layouts to judge")
    return layouts


def make_judge(name: str, options: Mapping[str, Any]) -> JudgeMetric:
    """``judge`` or ``judge:LAYOUT[,LAYOUT]`` (options: ``profile``, ``config``, the model
    settings of :data:`SETTING_OPTIONS`, ``layouts``, ``parse_retries``)."""
    settings = settings_from_options(options)
    try:
        retries = int(options.get("parse_retries", PARSE_RETRIES))
    except (TypeError, ValueError):
        raise MetricUnavailableError("judge: parse_retries must be a whole number") from None
    if not 0 <= retries <= 10:
        raise MetricUnavailableError("judge: parse_retries must be 0 to 10")
    metric = JudgeMetric(name, settings, _layouts(name, options), retries)
    try:
        metric.model  # noqa: B018 - make the client now, so a missing `openai` fails at once
    except ModelError as err:
        raise MetricUnavailableError(f"judge: {err}") from None
    return metric


register_metric(FAMILY, make_judge)
