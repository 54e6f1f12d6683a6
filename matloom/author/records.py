"""Run records: the pydantic schema of ``record.json`` and its incremental, atomic storage.

One folder per run holds ``record.json`` (everything: prompt, settings, model ids, per-stage
durations, every message, every program, critiques, scores, selection, seed-search log) and the
critic renders under ``renders/``; at the end the final material is installed beside them in
the layout ``matloom render`` writes (``material.mat``, ``preview.png``, the maps and
``material.json``, as one staged batch). The record is rewritten atomically after every step, so
a crash or a kill keeps every finished step and ``--resume`` continues from there.
"""

from __future__ import annotations

import os
from datetime import UTC, datetime
from pathlib import Path
from typing import Any, Literal

from pydantic import AliasChoices, BaseModel, ConfigDict, Field

from matloom.author.config import AuthorConfig
from matloom.author.redact import Redactor, redact_settings
from matloom.io.atomic import atomic_write_bytes
from matloom.io.outdir import OutputFolder

RECORD_NAME = "record.json"
#: The most bytes of ``record.json`` read on resume (every round's programs and capped replies).
RECORD_MAX_BYTES = 512 * 1024 * 1024
RECORD_FORMAT = "matloom-run"
RECORD_VERSION = 1
#: Artefacts written as text, so :meth:`RecordStore.write_file` can redact them.
TEXT_SUFFIXES = frozenset({".mat", ".json", ".txt", ".md"})

Status = Literal["running", "finished", "failed"]
#: ``RunRecord.author`` values of a run without a model (``"builtin"``: older records).
OFFLINE_AUTHORS = frozenset({"library", "builtin"})


def utc_now() -> str:
    """ISO-8601 UTC timestamp with seconds."""
    return datetime.now(UTC).isoformat(timespec="seconds")


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid")


class MessageRecord(_Model):
    """One chat turn; images are paths relative to the run folder."""

    role: Literal["system", "user", "assistant"]
    text: str
    images: list[str] = Field(default_factory=list)


class AttemptRecord(_Model):
    """One model reply inside a generation turn, and what the parser made of it."""

    attempt: int
    reply: str
    outcome: Literal["accepted", "no_program", "parse_error", "too_large", "bad_reply"]
    diagnostics: list[dict[str, Any]] = Field(default_factory=list)
    #: Why a reply was refused unread (``too_large``: over the reply-size cap; the reply above
    #: is then only its start; ``bad_reply``: no usable reply came, e.g. a malformed body).
    error: str | None = None
    seconds: float
    model: str


class TurnRecord(_Model):
    """A generation (program 0), another first draft (``drafts``) or revision (program k > 0)
    turn with its repair attempts."""

    program_index: int
    kind: Literal["initial", "draft", "revision"]
    attempts: list[AttemptRecord] = Field(default_factory=list)
    accepted: bool = False
    seconds: float = 0.0
    error: str | None = None


class ProgramRecord(_Model):
    """A trajectory program P_k (canonical text, seeds explicit)."""

    index: int
    text: str
    authored: str
    #: Who wrote it: the model, or the material library (``"builtin"`` in records written
    #: before the library replaced the built-in recipes).
    source: Literal["generator", "library", "builtin"]
    program_seed: int
    #: The seeds given to noise calls the author left unseeded (told to the model in the
    #: revision turn, since its own text, which it sees again, lacks them).
    added_seeds: list[str] = Field(default_factory=list)


class EditRecord(_Model):
    """One concrete edit proposed by the critic."""

    layer: int | None = None
    channel: str | None = None
    define: str | None = None
    change: str


class HistoryRecord(_Model):
    """What a critic with ``critic_history`` saw of the previous round, and its verdict."""

    previous_index: int
    previous_score: int | None = None
    previous_renders: list[str] = Field(default_factory=list)
    #: The critic's answer to "is this version better than the previous one?".
    better: bool | None = None


class CritiqueRecord(_Model):
    """One stateless critique of P_k."""

    program_index: int
    ok: bool
    match_score: int | None = None
    differences: list[str] = Field(default_factory=list)
    suggestions: list[str] = Field(default_factory=list)
    edits: list[EditRecord] = Field(default_factory=list)
    #: Structural changes asked for (``critic_structural``): a new layer, another primitive.
    structural: list[str] = Field(default_factory=list)
    #: Only the score was asked for (``score_only_last``: the last program's critique).
    score_only: bool = False
    signals: list[str]
    #: The first image shown (this round's first view), for older readers of the record.
    render: str | None = None
    #: The preview layouts shown and their images (this round's), in order.
    views: list[str] = Field(default_factory=list)
    renders: list[str] = Field(default_factory=list)
    history: HistoryRecord | None = None
    model: str
    attempts: int
    seconds: float
    messages: list[MessageRecord] = Field(default_factory=list)
    replies: list[str] = Field(default_factory=list)
    error: str | None = None


class SelectionRecord(_Model):
    """Trajectory selection: which P_j goes on, and by what."""

    method: Literal["scorer", "critic", "single", "last"]
    index: int
    scorer: str | None = None
    size: int | None = None
    scores: list[float | None] = Field(default_factory=list)
    seconds: float


class SweepRecord(_Model):
    """The seed sweep of one candidate program (variant 0 = the original)."""

    program_index: int
    variants: int
    size: int
    seed: int
    best_variant: int
    best_score: float | None
    original_score: float | None
    best_program: str
    scores: list[float | None]
    seconds: float
    rate: float
    message: str = ""


class SeedSearchRecord(_Model):
    """Stage III seed search over the distinct {first, selected, last} programs."""

    candidates: list[int] = Field(default_factory=list)
    sweeps: list[SweepRecord] = Field(default_factory=list)
    skipped: str | None = None
    done: bool = False


class ReferenceRecord(_Model):
    """The reference photo of ``--reference``: its hash and size, never its pixels."""

    name: str
    sha256: str
    width: int
    height: int


class FittedParamRecord(_Model):
    """One parameter fitted by ``--polish``: its search window and values (a colour: r, g, b)."""

    address: str
    label: str
    kind: str
    low: list[float]
    high: list[float]
    before: list[float]
    after: list[float] = Field(default_factory=list)
    #: Parameters with the same function, name and value that moved with this one.
    tied: list[str] = Field(default_factory=list)


class PolishRecord(_Model):
    """``--polish cmaes``: the exposed numeric parameters of the chosen program fitted after
    selection and seed search, kept only when the critic does not score the fit lower."""

    method: Literal["cmaes"] = "cmaes"
    #: What was minimised or maximised: the scorer's score, the statistics distance to the
    #: reference photo, or the critic's match score.
    objective: Literal["scorer", "reference", "critic"] | None = None
    #: "higher" or "lower": which objective values are better.
    better: Literal["higher", "lower"] = "higher"
    program_index: int
    variant: int = 0
    seed: int = 0
    parameters: list[FittedParamRecord] = Field(default_factory=list)
    evaluations: int = 0
    seconds: float = 0.0
    objective_before: float | None = None
    objective_after: float | None = None
    #: The critic's fresh match scores of the unfitted and the fitted program (the guard).
    critic_before: int | None = None
    critic_after: int | None = None
    guard: list[CritiqueRecord] = Field(default_factory=list)
    #: The fitted program (canonical text), kept or not.
    program: str | None = None
    kept: bool = False
    reason: str = ""
    skipped: str | None = None
    done: bool = False


class FinalRecord(_Model):
    """The returned program and where it came from."""

    program: str
    program_index: int
    variant: int
    score: float | None
    files: dict[str, str] = Field(default_factory=dict)
    #: Texels with a NaN or infinite value in some map at the export size (0 = all finite).
    nonfinite_texels: int = 0


class Durations(_Model):
    """Wall seconds per stage (lists: one entry per call)."""

    total: float = 0.0
    generation: list[float] = Field(default_factory=list)
    critique: list[float] = Field(default_factory=list)
    select: float | None = None
    seed_search: list[float] = Field(default_factory=list)
    export: float | None = None


class ModelIds(_Model):
    generator: str | None = None
    critic: str | None = None
    scorer: str | None = None


class BlenderRecord(_Model):
    """The final material's Blender renders (``--blender-layouts``)."""

    layouts: list[str]
    files: list[str] = Field(default_factory=list)
    seconds: float = 0.0
    error: str | None = None


class RunRecord(_Model):
    """Everything about one authoring run (``record.json``)."""

    format: Literal["matloom-run"] = RECORD_FORMAT
    version: int = RECORD_VERSION
    matloom_version: str
    prompt: str
    created: str = Field(default_factory=utc_now)
    updated: str = Field(default_factory=utc_now)
    status: Status = "running"
    error: str | None = None
    #: ``"llm"`` (a model writes or revises), or ``"library"``: the offline author, no model
    #: (``"builtin"`` in records written before the library replaced the built-in recipes).
    author: Literal["llm", "library", "builtin"]
    settings: AuthorConfig
    models: ModelIds = Field(default_factory=ModelIds)
    system_prompt: str | None = None
    #: The generator conversation up to the last accepted program: the model's own replies (the
    #: canonical programs are in ``programs``); images by path, sent only with their own turn.
    conversation: list[MessageRecord] = Field(default_factory=list)
    turns: list[TurnRecord] = Field(default_factory=list)
    programs: list[ProgramRecord] = Field(default_factory=list)
    critiques: list[CritiqueRecord] = Field(default_factory=list)
    stop_reason: str | None = None
    #: The library's explanation of P0 (candidates, entry, adaptations, ignored words) when
    #: the library wrote it; read from ``builtin_explanation`` in older records.
    library_explanation: str | None = Field(
        default=None,
        validation_alias=AliasChoices("library_explanation", "builtin_explanation"),
    )
    selection: SelectionRecord | None = None
    seed_search: SeedSearchRecord | None = None
    final: FinalRecord | None = None
    #: Things the user should know about the result (the CLI prints them on stderr).
    warnings: list[str] = Field(default_factory=list)
    #: The material's name (``name`` in material.json, for the file names of engine exports):
    #: the library entry when the library authored it offline, else a slug of the prompt.
    material_name: str | None = None
    blender: BlenderRecord | None = None
    #: The reference photo (``--reference``): hash and size only.
    reference: ReferenceRecord | None = None
    #: The parameter fit (``--polish``), when one was asked for.
    polish: PolishRecord | None = None
    durations: Durations = Field(default_factory=Durations)
    sessions: list[str] = Field(default_factory=list)

    @property
    def offline(self) -> bool:
        """True when no model is involved: the library wrote the only program."""
        return self.author in OFFLINE_AUTHORS

    def critique_of(self, index: int) -> CritiqueRecord | None:
        """The critique of program ``index``, if one was recorded."""
        return next((c for c in self.critiques if c.program_index == index), None)


class RecordStore:
    """A run folder and its record, saved atomically on every :meth:`save`."""

    def __init__(self, folder: str | os.PathLike[str], record: RunRecord) -> None:
        self.folder = Path(folder)
        self.record = record
        self.out: OutputFolder | None = None

    @property
    def path(self) -> Path:
        return self.folder / RECORD_NAME

    def attach(self, out: OutputFolder) -> None:
        """Write through ``out`` (locked, never replacing a foreign file) from now on; fail at
        once when the record or the final material would replace a foreign file."""
        from matloom.io.export import planned_files

        out.check_writable([RECORD_NAME, *planned_files(None, "png", preview=True)])
        self.out = out

    def redactor(self) -> Redactor:
        """Removes the run's API keys and URL credentials (:mod:`matloom.author.redact`)."""
        return Redactor.for_config(self.record.settings)

    def save(self) -> None:
        """Write ``record.json`` atomically (temp file + rename), credentials redacted."""
        self.record.updated = utc_now()
        stored = self.record.model_copy(update={"settings": redact_settings(self.record.settings)})
        text = self.redactor().json_text(stored.model_dump_json(indent=2) + "\n")
        self._write(RECORD_NAME, text.encode("utf-8"))

    def write_file(self, relative: str, data: bytes) -> str:
        """Store an artefact in the run folder atomically (text ones with credentials
        redacted); return its relative path."""
        if Path(relative).suffix in TEXT_SUFFIXES:
            data = self.redactor().text(data.decode("utf-8")).encode("utf-8")
        self._write(relative, data)
        return relative

    def _write(self, relative: str, data: bytes) -> None:
        """Through the attached output folder when there is one, else straight to disk."""
        if self.out is not None:
            self.out.write_bytes(relative, data)
            return
        target = self.folder / relative
        target.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_bytes(target, data)

    @classmethod
    def load(cls, folder: str | os.PathLike[str]) -> RecordStore:
        """Read and validate the record of an existing run folder."""
        from matloom.io.reading import read_json_file

        # A run folder may come from elsewhere: its record is never read through a symlink.
        data = read_json_file(Path(folder) / RECORD_NAME, RECORD_MAX_BYTES)
        return cls(folder, RunRecord.model_validate(data))


def validate_record_file(path: str | os.PathLike[str]) -> RunRecord:
    """Parse and schema-validate a ``record.json`` (raises pydantic.ValidationError)."""
    return RunRecord.model_validate_json(Path(path).read_text(encoding="utf-8"))


def record_json_schema() -> dict[str, Any]:
    """The JSON Schema of ``record.json``."""
    return RunRecord.model_json_schema()
