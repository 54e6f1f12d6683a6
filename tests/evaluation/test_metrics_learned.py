"""CLIPScore, BLIPScore and VQAScore on tiny randomly initialised models of the real architectures.

Each test saves a tiny model in the layout real weights have (an open_clip state-dict file, a
``save_pretrained`` BLIP-2 ITM folder, a CLIP-FlanT5 checkpoint as t2v_metrics saves it) and
loads it through the metric's own loading code, then scores rendered material previews. Nothing
is downloaded: ``HF_HUB_OFFLINE`` is set and ``HF_HOME`` points at an empty folder.
"""

from __future__ import annotations

import importlib.util
import json
import string
from pathlib import Path

import pytest

from matloom.evaluation.metrics.base import MetricUnavailableError, Sample
from matloom.evaluation.metrics.registry import get_metric, metric_names

HAS_METRICS = all(
    importlib.util.find_spec(m) is not None for m in ("torch", "open_clip", "transformers")
)
needs_extra = pytest.mark.skipif(
    not HAS_METRICS, reason="needs the metrics extra (make metrics-venv)"
)
EXAMPLES = Path(__file__).resolve().parents[2] / "matloom" / "examples"
PROMPTS = {
    "weathered_brick": "weathered red brick wall with mortar",
    "black_ceramic_tiles": "glossy black ceramic tiles",
}


def test_learned_metric_families_are_registered() -> None:
    assert {"blip", "clip", "vqa"} <= set(metric_names())


@pytest.mark.skipif(HAS_METRICS, reason="the metrics extra is installed here")
@pytest.mark.parametrize("name", ["clip", "blip", "vqa"])
def test_missing_extra_says_how_to_install(name: str) -> None:
    with pytest.raises(MetricUnavailableError, match=r"matloom\[metrics\]"):
        get_metric(name)


# --- fixtures: real images, an empty offline cache ------------------------------------------


@pytest.fixture(scope="module")
def samples(tmp_path_factory: pytest.TempPathFactory) -> list[Sample]:
    """Two rendered materials; the first has two layouts, the second only the quick preview."""
    from matloom.io.png import save_png
    from matloom.render.api import preview

    root = tmp_path_factory.mktemp("images")
    out = []
    for index, (stem, prompt) in enumerate(PROMPTS.items()):
        text = (EXAMPLES / f"{stem}.mat").read_text(encoding="utf-8")
        images = {"quick": save_png(root / f"{stem}-quick.png", preview(text, 48))}
        if index == 0:
            wide = preview(text, width=64, height=40, layout="flat")
            images["flat"] = save_png(root / f"{stem}-flat.png", wide)
        out.append(Sample(id=stem, prompt=prompt, program=text, images=images))
    return out


@pytest.fixture(scope="module", autouse=True)
def _offline(tmp_path_factory: pytest.TempPathFactory):
    """Before anything imports huggingface_hub here: offline, with an empty cache."""
    home = tmp_path_factory.mktemp("empty-hf-home")
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("HF_HUB_OFFLINE", "1")
        patch.setenv("TRANSFORMERS_OFFLINE", "1")
        patch.setenv("HF_HOME", str(home))
        patch.setenv("HF_HUB_CACHE", str(home / "hub"))
        yield


def _check_scores(rows: list[dict[str, float]], family: str) -> None:
    assert [sorted(r) for r in rows] == [[f"{family}.flat", f"{family}.quick"], [f"{family}.quick"]]
    values = [v for r in rows for v in r.values()]
    assert all(isinstance(v, float) and 0.0 <= v <= 100.0 for v in values)


# --- CLIPScore ------------------------------------------------------------------------------

TINY_CLIP = "matloom-tiny-clip"


@pytest.fixture(scope="module")
def clip_weights(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A tiny ViT CLIP registered with open_clip and its random weights as a safetensors file."""
    import open_clip
    import torch
    from safetensors.torch import save_file

    root = tmp_path_factory.mktemp("clip")
    config = {
        "embed_dim": 16,
        "vision_cfg": {
            "image_size": 32,
            "layers": 1,
            "width": 32,
            "patch_size": 8,
            "head_width": 16,
        },
        "text_cfg": {
            "context_length": 77,
            "vocab_size": 49408,
            "width": 32,
            "heads": 2,
            "layers": 1,
        },
    }
    (root / f"{TINY_CLIP}.json").write_text(json.dumps(config), encoding="utf-8")
    open_clip.add_model_config(root / f"{TINY_CLIP}.json")
    torch.manual_seed(0)
    model = open_clip.create_model(TINY_CLIP, pretrained=None)
    state = {k: v.contiguous().clone() for k, v in model.state_dict().items()}
    save_file(state, str(root / "tiny.safetensors"))
    return root / "tiny.safetensors"


@pytest.mark.metrics
@needs_extra
def test_clip_score_matches_hessel_definition(clip_weights: Path, samples: list[Sample]) -> None:
    import open_clip
    import torch
    from PIL import Image

    name = f"clip:{TINY_CLIP}:{clip_weights}"
    metric = get_metric(name, {"device": "cpu"})
    assert metric.name == name and metric.layouts == ("quick", "flat", "staged")
    rows = metric.score(samples)
    _check_scores(rows, "clip")
    assert metric.score(samples) == rows  # deterministic
    assert get_metric(name, {"device": "cpu"}).score(samples) == rows  # and across loads

    # The definition computed directly: max(100 * cos(image, raw prompt), 0).
    net, _, preprocess = open_clip.create_model_and_transforms(
        TINY_CLIP, pretrained=str(clip_weights)
    )
    net.eval()
    tokenizer = open_clip.get_tokenizer(TINY_CLIP)
    for sample, row in zip(samples, rows):
        for key, value in row.items():
            image = Image.open(sample.images[key.split(".")[1]]).convert("RGB")
            with torch.no_grad():
                cos = torch.nn.functional.cosine_similarity(
                    net.encode_image(preprocess(image).unsqueeze(0)),
                    net.encode_text(tokenizer([sample.prompt])),
                ).item()
            assert value == pytest.approx(max(100.0 * cos, 0.0), abs=1e-3)


@pytest.mark.metrics
@needs_extra
def test_clip_score_missing_weights_say_how_to_get_them(tmp_path: Path) -> None:
    with pytest.raises(MetricUnavailableError, match="no such weights file"):
        get_metric(f"clip:ViT-B-32:{tmp_path / 'absent.safetensors'}")
    with pytest.raises(MetricUnavailableError, match=r"(?s)not in the local cache.*clip:ViT-L-14:"):
        get_metric("clip")  # ViT-L-14 / openai: not in the (empty) cache
    with pytest.raises(MetricUnavailableError, match="bad metric name"):
        get_metric("clip:ViT-L-14")


# --- BLIPScore ------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def blip_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A tiny BLIP-2 ITM model and processor saved as ``save_pretrained`` writes them."""
    import torch
    from transformers import (
        BertTokenizerFast,
        Blip2Config,
        Blip2ForImageTextRetrieval,
        Blip2Processor,
        BlipImageProcessor,
    )

    words = ["[PAD]", "[UNK]", "[CLS]", "[SEP]", "[MASK]"]
    words += sorted({w for prompt in PROMPTS.values() for w in prompt.split()})
    tokenizer = BertTokenizerFast(vocab={w: i for i, w in enumerate(words)})
    config = Blip2Config(
        vision_config={
            "hidden_size": 32,
            "intermediate_size": 37,
            "num_hidden_layers": 1,
            "num_attention_heads": 2,
            "image_size": 32,
            "patch_size": 8,
        },
        qformer_config={
            "hidden_size": 32,
            "num_hidden_layers": 2,
            "num_attention_heads": 2,
            "intermediate_size": 37,
            "encoder_hidden_size": 32,
            "vocab_size": len(words),
            "max_position_embeddings": 64,
            "use_qformer_text_input": True,
        },
        text_config={
            "model_type": "opt",
            "hidden_size": 16,
            "num_hidden_layers": 1,
            "num_attention_heads": 2,
            "ffn_dim": 16,
            "vocab_size": 50,
            "word_embed_proj_dim": 16,
        },
        num_query_tokens=4,
        image_text_hidden_size=16,
    )
    torch.manual_seed(0)
    root = tmp_path_factory.mktemp("blip")
    Blip2ForImageTextRetrieval(config).save_pretrained(root)
    image_processor = BlipImageProcessor(size={"height": 32, "width": 32})
    Blip2Processor(image_processor, tokenizer, num_query_tokens=4).save_pretrained(root)
    return root


@pytest.mark.metrics
@needs_extra
def test_blip_score_is_the_itm_match_probability(blip_dir: Path, samples: list[Sample]) -> None:
    import torch
    from PIL import Image
    from transformers import Blip2ForImageTextRetrieval, Blip2Processor

    metric = get_metric(f"blip:{blip_dir}", {"device": "cpu"})
    assert metric.name == f"blip:{blip_dir}"
    rows = metric.score(samples)
    _check_scores(rows, "blip")
    assert metric.score(samples) == rows
    assert get_metric(f"blip:{blip_dir}", {"device": "cpu"}).score(samples) == rows

    # Directly: softmax of the ITM head's logits, column "match", one pair at a time.
    model = Blip2ForImageTextRetrieval.from_pretrained(blip_dir).eval()
    processor = Blip2Processor.from_pretrained(blip_dir)
    for sample, row in zip(samples, rows):
        for key, value in row.items():
            image = Image.open(sample.images[key.split(".")[1]]).convert("RGB")
            text = processor.tokenizer([sample.prompt], return_tensors="pt")
            with torch.no_grad():
                logits = model(
                    pixel_values=processor.image_processor([image], return_tensors="pt")[
                        "pixel_values"
                    ],
                    input_ids=text["input_ids"],
                    attention_mask=text["attention_mask"],
                    use_image_text_matching_head=True,
                ).logits_per_image
            assert value == pytest.approx(100 * torch.softmax(logits, 1)[0, 1].item(), abs=1e-3)


@pytest.mark.metrics
@needs_extra
def test_blip_score_missing_weights_say_how_to_get_them(tmp_path: Path) -> None:
    with pytest.raises(MetricUnavailableError, match="huggingface-cli download Salesforce/blip2"):
        get_metric("blip")
    with pytest.raises(MetricUnavailableError, match="no such file or folder"):
        get_metric(f"blip:{tmp_path / 'absent'}")
    (tmp_path / "empty").mkdir()
    with pytest.raises(MetricUnavailableError, match="cannot load a BLIP-2 ITM model"):
        get_metric(f"blip:{tmp_path / 'empty'}")


# --- VQAScore -------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def vqa_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A tiny CLIP-FlanT5 checkpoint laid out as t2v_metrics saves one (T5 tensors, the
    projector and the vision tower under ``vision_tower.vision_tower.vision_model.``, config
    ``clip_t5`` with the ``mm_*`` fields) and its CLIP vision-tower folder."""
    import torch
    from safetensors.torch import load_file, save_file
    from transformers import (
        CLIPImageProcessor,
        CLIPVisionConfig,
        CLIPVisionModel,
        T5Config,
        T5ForConditionalGeneration,
        T5Tokenizer,
    )

    from matloom.evaluation.metrics.vqa_score import ANSWER, format_question

    words = {w for p in PROMPTS.values() for w in format_question(p).split()} | {ANSWER}
    pieces = [("<pad>", 0.0), ("</s>", 0.0), ("<unk>", 0.0), ("▁", -3.0)]
    pieces += [(f"▁{w}", -2.0) for w in sorted(words)]
    pieces += [(c, -5.0) for c in string.ascii_letters + string.digits + string.punctuation]
    tokenizer = T5Tokenizer(vocab=pieces, extra_ids=0)
    root = tmp_path_factory.mktemp("vqa")
    model_dir, tower_dir = root / "model", root / "tower"
    torch.manual_seed(0)
    t5 = T5ForConditionalGeneration(
        T5Config(
            vocab_size=len(tokenizer),
            d_model=32,
            d_kv=8,
            d_ff=37,
            num_layers=1,
            num_decoder_layers=1,
            num_heads=4,
            decoder_start_token_id=0,
            pad_token_id=0,
            eos_token_id=1,
            feed_forward_proj="gated-gelu",
            tie_word_embeddings=False,
        )
    )
    vision_config = CLIPVisionConfig(
        hidden_size=24,
        intermediate_size=37,
        num_hidden_layers=2,
        num_attention_heads=2,
        image_size=32,
        patch_size=8,
    )
    CLIPVisionModel(vision_config).save_pretrained(tower_dir)  # the tower's own weights...
    CLIPImageProcessor(
        size={"shortest_edge": 32}, crop_size={"height": 32, "width": 32}
    ).save_pretrained(tower_dir)
    tuned = CLIPVisionModel(vision_config)  # ...and the checkpoint's, which replace them
    projector = torch.nn.Sequential(
        torch.nn.Linear(24, 32), torch.nn.GELU(), torch.nn.Linear(32, 32)
    )
    t5.save_pretrained(model_dir)
    tokenizer.save_pretrained(model_dir)
    state = load_file(model_dir / "model.safetensors")
    prefix = "vision_tower.vision_tower.vision_model."
    state.update({prefix + k: v.clone() for k, v in tuned.state_dict().items()})
    state.update({"mm_projector." + k: v.clone() for k, v in projector.state_dict().items()})
    save_file(state, str(model_dir / "model.safetensors"), metadata={"format": "pt"})
    config = json.loads((model_dir / "config.json").read_text(encoding="utf-8"))
    config.update(
        model_type="clip_t5",
        architectures=["CLIPT5ForConditionalGeneration"],
        mm_vision_tower=str(tower_dir),
        mm_hidden_size=24,
        mm_projector_type="mlp2x_gelu",
        mm_vision_select_layer=-2,
        mm_vision_select_feature="patch",
        use_mm_proj=True,
    )
    (model_dir / "config.json").write_text(json.dumps(config), encoding="utf-8")
    return model_dir


def _vqa_by_hand(model_dir: Path, image_path: Path, prompt: str) -> float:
    """VQAScore step by step: P("Yes") at decoder step 1, P(</s>) at step 2, geometric mean."""
    import torch
    from PIL import Image
    from safetensors.torch import load_file
    from transformers import (
        AutoTokenizer,
        CLIPImageProcessor,
        CLIPVisionConfig,
        CLIPVisionModel,
        T5ForConditionalGeneration,
    )

    from matloom.evaluation.metrics.vqa_score import SYSTEM_MSG

    config = json.loads((model_dir / "config.json").read_text(encoding="utf-8"))
    state = load_file(model_dir / "model.safetensors")
    tower = config["mm_vision_tower"]
    vision = CLIPVisionModel(CLIPVisionConfig.from_pretrained(tower)).eval()
    prefix = "vision_tower.vision_tower.vision_model."
    vision.load_state_dict({k[len(prefix) :]: v for k, v in state.items() if k.startswith(prefix)})
    linear1, linear2 = torch.nn.Linear(24, 32), torch.nn.Linear(32, 32)
    linear1.load_state_dict(
        {"weight": state["mm_projector.0.weight"], "bias": state["mm_projector.0.bias"]}
    )
    linear2.load_state_dict(
        {"weight": state["mm_projector.2.weight"], "bias": state["mm_projector.2.bias"]}
    )
    t5 = T5ForConditionalGeneration.from_pretrained(model_dir).eval()
    tok = AutoTokenizer.from_pretrained(model_dir)
    image = Image.open(image_path).convert("RGB")
    side = max(image.size)
    square = Image.new(
        "RGB",
        (side, side),
        tuple(int(255 * m) for m in CLIPImageProcessor.from_pretrained(tower).image_mean),
    )
    square.paste(image, ((side - image.size[0]) // 2, (side - image.size[1]) // 2))
    pixels = CLIPImageProcessor.from_pretrained(tower)(square, return_tensors="pt")["pixel_values"]
    before = f"{SYSTEM_MSG} USER: "
    after = f'\nDoes this figure show "{prompt}"? Please answer yes or no. ASSISTANT: '
    embed = t5.get_input_embeddings()
    with torch.no_grad():
        patches = vision(pixels, output_hidden_states=True).hidden_states[-2][0, 1:]
        image_tokens = linear2(torch.nn.functional.gelu(linear1(patches)))
        inputs = torch.cat(
            [
                embed(torch.tensor(tok(before).input_ids)),
                image_tokens,
                embed(torch.tensor(tok(after).input_ids)),
            ]
        ).unsqueeze(0)
        yes, eos = tok("Yes").input_ids
        decoder = torch.tensor([[t5.config.decoder_start_token_id, yes]])
        probs = t5(inputs_embeds=inputs, decoder_input_ids=decoder).logits.softmax(-1)[0]
    return 100.0 * float((probs[0, yes] * probs[1, eos]).sqrt())


@pytest.mark.metrics
@needs_extra
def test_vqa_score_is_the_yes_probability(vqa_dir: Path, samples: list[Sample]) -> None:
    metric = get_metric(f"vqa:{vqa_dir}", {"device": "cpu", "layouts": "quick,flat"})
    assert metric.name == f"vqa:{vqa_dir}" and metric.layouts == ("quick", "flat")
    rows = metric.score(samples)  # one batch: prompts of different lengths, padded
    _check_scores(rows, "vqa")
    assert metric.score(samples) == rows
    for sample, row in zip(samples, rows):
        for key, value in row.items():
            expected = _vqa_by_hand(vqa_dir, sample.images[key.split(".")[1]], sample.prompt)
            assert value == pytest.approx(expected, rel=1e-4)
    alone = metric.score(samples[1:])  # batching does not change a score
    assert alone[0]["vqa.quick"] == pytest.approx(rows[1]["vqa.quick"], rel=1e-4)


@pytest.mark.metrics
@needs_extra
def test_vqa_score_missing_or_wrong_weights_say_why(vqa_dir: Path, tmp_path: Path) -> None:
    import shutil

    with pytest.raises(
        MetricUnavailableError, match="huggingface-cli download zhiqiulin/clip-flant5-xxl"
    ):
        get_metric("vqa")
    with pytest.raises(MetricUnavailableError, match="no such file or folder"):
        get_metric(f"vqa:{tmp_path / 'absent'}")
    plain = tmp_path / "plain-t5"
    shutil.copytree(vqa_dir, plain)
    config = json.loads((plain / "config.json").read_text(encoding="utf-8"))
    del config["mm_vision_tower"]
    (plain / "config.json").write_text(json.dumps(config), encoding="utf-8")
    with pytest.raises(MetricUnavailableError, match="not a CLIP-FlanT5 config"):
        get_metric(f"vqa:{plain}")
    bare = tmp_path / "no-tokenizer"
    shutil.copytree(vqa_dir, bare)
    (bare / "tokenizer_config.json").unlink()
    with pytest.raises(MetricUnavailableError, match="holds no tokenizer"):
        get_metric(f"vqa:{bare}")
