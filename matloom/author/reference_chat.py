"""How the reference photo reaches the models of a run: one wrapper around each chat model.

:func:`with_reference` wraps the generator and the critic so that every request they make
carries the photo (resized to the critique size, as JPEG like the previews) after the images
of its newest user turn, with a short note saying what the last image is. Every stage (the
first request, repairs, revisions, critiques, their retries, the score-only requests and
``--polish``'s critic calls) is covered without the stages knowing about the photo. A model
that takes no images gets neither the photo nor the note; the run records a warning, and the
critic still gets the statistics comparison (:func:`matloom.render.compare_stats`) through
its statistics (:class:`matloom.author.views.Renderer` appends it).

The record keeps the photo's hash (``RunRecord.reference``); the recorded conversations do not
list the photo, which goes with every request as described here.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

from matloom.author.config import DEFAULT_MAX_REPLY_CHARS
from matloom.author.llm.base import ChatMessage, ChatModel, ChatReply, ImageInput, complete_within
from matloom.author.reference import ReferencePhoto

#: What the generator is told with every request.
GENERATOR_NOTE = (
    "Reference photo: the last attached image is a photo of the material to make (not a "
    "render). Match its colours, contrast, pattern scale and orientation, and its kind of "
    "detail. Make a material whose pattern repeats, not a copy of the photo's layout."
)
#: What the critic is told with every request.
CRITIC_NOTE = (
    "Reference photo: the last attached image is a photo of the material the description "
    "asks for (not a render, and lit as it was taken). Judge how well the render(s) match "
    "both the description and this photo: colours, contrast, pattern scale and orientation, "
    "kind of detail. The statistics, when given, compare the render with the photo."
)


def reference_input(photo: ReferencePhoto, size: int) -> ImageInput:
    """The photo as a model input: ``size`` x ``size`` JPEG, like the previews (not stored)."""
    from matloom.author.views import jpeg_bytes

    return ImageInput(data=jpeg_bytes(photo.at(size)), mime="image/jpeg")


@dataclass(frozen=True)
class ReferenceModel:
    """A chat model whose requests carry the reference photo and a note (module docstring)."""

    inner: ChatModel
    image: ImageInput
    note: str

    @property
    def model_id(self) -> str:
        return self.inner.model_id

    @property
    def accepts_images(self) -> bool:
        return self.inner.accepts_images

    def with_photo(self, messages: Sequence[ChatMessage]) -> list[ChatMessage]:
        """``messages`` with the photo and note added to the newest user turn."""
        out = list(messages)
        for k in range(len(out) - 1, -1, -1):
            if out[k].role == "user":
                turn = out[k]
                out[k] = replace(
                    turn, text=f"{turn.text}\n\n{self.note}", images=(*turn.images, self.image)
                )
                break
        return out

    def complete(
        self, messages: Sequence[ChatMessage], max_reply_chars: int = DEFAULT_MAX_REPLY_CHARS
    ) -> ChatReply:
        return complete_within(self.inner, self.with_photo(messages), max_reply_chars)


def with_reference(
    photo: ReferencePhoto | None,
    size: int,
    generator: ChatModel | None,
    critic: ChatModel | None,
) -> tuple[ChatModel | None, ChatModel | None, list[str]]:
    """(generator, critic, warnings): the models wrapped to send the photo at ``size`` px when
    they take images; a warning for each that does not."""
    if photo is None or (generator is None and critic is None):
        return generator, critic, []
    image = reference_input(photo, size)
    warnings = []

    def wrap(model: ChatModel | None, note: str, role: str) -> ChatModel | None:
        if model is None:
            return None
        if not model.accepts_images:
            warnings.append(
                f"the {role} ({model.model_id}) takes no images, so it does not see the "
                "reference photo"
                + ("; it gets the statistics comparison only" if role == "critic" else "")
            )
            return model
        return ReferenceModel(model, image, note)

    return (
        wrap(generator, GENERATOR_NOTE, "generator"),
        wrap(critic, CRITIC_NOTE, "critic"),
        warnings,
    )
