"""The studio's HTTP API against a real server (tests/studio/conftest.py): security, the
language endpoints, the panel's edits and evaluation (docs/studio-api.md)."""

from __future__ import annotations

import json
import threading
from typing import Any

import numpy as np
import pytest

pytest.importorskip("starlette", reason="the studio needs the [studio] extra (starlette)")

from matloom.studio.wire import unpack  # noqa: E402

DEMO = "black_ceramic_tiles.mat"
#: The conftest's server helper (tests/studio/conftest.py).
StudioServer = Any


def demo(studio: StudioServer) -> str:
    return (studio.root / DEMO).read_text(encoding="utf-8")


# ---------------------------------------------------------------------------- security
def test_no_token_wrong_token_forged_host_and_bad_origin_are_refused(studio: StudioServer) -> None:
    assert studio.get("/api/session").status == 200
    assert studio.get("/api/session", token=None).status == 403
    assert studio.get("/api/session", token="x" * 43).status == 403
    forged = studio.get("/api/session", headers={"Host": f"evil.example:{studio.port}"})
    assert forged.status == 403 and "Host" in forged.json()["error"]
    assert studio.get("/", headers={"Host": f"rebind.example:{studio.port}"}).status == 403
    other_port = studio.get("/api/session", headers={"Host": f"127.0.0.1:{studio.port + 1}"})
    assert other_port.status == 403
    cross = studio.post("/api/check", {"text": ""}, headers={"Origin": "http://evil.example"})
    assert cross.status == 403
    same = studio.post(
        "/api/check", {"text": ""}, headers={"Origin": f"http://localhost:{studio.port}"}
    )
    assert same.status == 200
    assert studio.get(f"/api/session?token={studio.token}", token=None).status == 200
    # the query token is for GET (downloads, event streams) only
    assert studio.post(f"/api/check?token={studio.token}", {"text": ""}, token=None).status == 403


def test_bodies_over_the_cap_get_413(studio: StudioServer) -> None:
    from matloom.studio.protocol import MAX_BODY

    big = json.dumps({"text": "#" * (MAX_BODY + 10)}).encode()
    reply = studio.post("/api/check", big)
    assert reply.status == 413 and "error" in reply.json()


def test_static_page_is_served_without_a_token(studio: StudioServer) -> None:
    page = studio.get("/", token=None)
    assert page.status in (200, 503)
    if page.status == 503:
        assert b"make studio-build" in page.body
    else:
        assert b"<" in page.body and "content-security-policy" in page.headers
    assert page.headers["x-content-type-options"] == "nosniff"
    assert studio.get("/../../etc/passwd", token=None).status in (403, 404)


def test_session_lists_the_workspace(studio: StudioServer) -> None:
    info = studio.get("/api/session").json()
    assert info["opened"] == DEMO and DEMO in info["files"]
    assert info["text"] == demo(studio) and info["token_ok"] is True
    assert info["model"] is False and isinstance(info["blender"], bool)
    assert "gltf" in info["presets"] and info["limits"]["max_size"] == 2048


def test_vocab_comes_from_the_registry(studio: StudioServer) -> None:
    from matloom.vocab import CHANNELS, FUNCTIONS

    vocab = studio.get("/api/vocab").json()
    names = {f["name"] for f in vocab["functions"]}
    assert names == set(FUNCTIONS)
    bricks = next(f for f in vocab["functions"] if f["name"] == "Bricks")
    mortar = next(p for p in bricks["params"] if p["name"] == "mortar")
    assert mortar["doc"] and mortar["type"] == "float" and mortar["required"] is False
    assert {c["name"] for c in vocab["channels"]} == set(CHANNELS)
    assert ".basecolor" in vocab["layer_methods"] and "Material" in vocab["keywords"]
    assert {c["name"] for c in vocab["constants"]} == {"pi", "e"}


# ---------------------------------------------------------------------------- language
def test_check_gives_line_col_and_offsets(studio: StudioServer) -> None:
    text = "# a comment\nMaterial(Layer(1).roughnes(0.5))"
    reply = studio.post("/api/check", {"text": text}).json()
    assert reply["ok"] is False
    [d] = [d for d in reply["diagnostics"] if d["severity"] == "error"]
    assert (d["line"], d["col"]) == (2, 19)
    assert text[d["from"] : d["to"]] == "roughnes"
    assert d["end_line"] == 2 and d["end_col"] == d["col"] + len("roughnes")
    assert "roughness" in (d["hint"] or "")
    # offsets are JavaScript string indices (UTF-16) after a character outside the BMP
    wide = "# \U0001f600\n" + text.split("\n", 1)[1]
    d2 = next(d for d in studio.post("/api/check", {"text": wide}).json()["diagnostics"])
    assert d2["from"] == wide.index("roughnes") + 1
    assert studio.post("/api/check", {"text": demo(studio)}).json()["ok"] is True


def test_format_keeps_comments_and_refuses_errors(studio: StudioServer) -> None:
    text = "# header\nDefine(g,0.5)  # grout\nMaterial( Layer(1).roughness( g ) )\n"
    out = studio.post("/api/format", {"text": text}).json()["text"]
    assert out.startswith("# header\nDefine(g, 0.5)  # grout\n")
    assert "Layer(1)" in out and ".roughness(g)" in out
    bad = studio.post("/api/format", {"text": "Material(Layer(1).rough(1))"})
    assert bad.status == 422 and bad.json()["diagnostics"][0]["line"] == 1
    assert studio.post("/api/format", {"text": 3}).status == 400
    assert studio.post("/api/format", b"not json").status == 400


# ---------------------------------------------------------------------------- structure
def test_structure_groups_params_and_seeds(studio: StudioServer) -> None:
    s = studio.post("/api/structure", {"text": demo(studio)}).json()
    addresses = {p["address"] for p in s["params"]}
    assert "define:tileMask.Bricks.mortar" in addresses
    assert s["view"] == {"x1": 0.25, "y1": 0.25, "x2": 2.25, "y2": 2.25, "tileable": False,
                         "unit_m": None}  # fmt: skip
    tile = next(d for d in s["defines"] if d["name"] == "tileMask")
    assert "define:tileMask.Bricks.mortar" in tile["params"] and tile["line"] == 2
    assert [layer["index"] for layer in s["layers"]] == [1, 2]
    assert s["layers"][1]["label"] == "tile mask"
    assert "layer:2.coat" in s["layers"][1]["params"]
    seeds = {x["address"]: x for x in s["seeds"]}
    assert seeds["define:glazeRipple.fBm.seed"]["value"] == 1145088217
    assert not seeds["define:glazeRipple.fBm.seed"]["auto"]


def test_set_rewrites_only_the_touched_literal_and_keeps_comments(studio: StudioServer) -> None:
    text = "# tiles\nDefine(g,   0.02)   # grout width\nMaterial(Layer(1).roughness(  0.5 ))\n"
    out = studio.post("/api/set", {"text": text, "values": {"define:g": 0.03}}).json()
    assert out["text"] == text.replace("0.02", "0.03") and out["warnings"] == []
    clamped = studio.post("/api/set", {"text": text, "values": {"layer:1.roughness": 2}}).json()
    assert "roughness(  1 )" in clamped["text"] and clamped["warnings"]
    colour = "Material(Layer(1).basecolor(10, 20, 30))"
    out = studio.post("/api/set", {"text": colour, "values": {"layer:1.basecolor": [1, 2, 3]}})
    assert out.json()["text"] == "Material(Layer(1).basecolor(1, 2, 3))"
    unknown = studio.post("/api/set", {"text": text, "values": {"define:nope": 1}})
    assert unknown.status == 400 and "unknown parameter" in unknown.json()["error"]


def test_layer_operations_keep_comments(studio: StudioServer) -> None:
    text = (
        "Material(\n  # base\n  Layer(1).roughness(0.9),\n  # top\n  Layer(0.5).roughness(0.1)\n)"
    )

    def op(**body: object) -> str:
        reply = studio.post("/api/layers", {"text": text, **body})
        assert reply.status == 200, reply.body
        return reply.json()["text"]

    moved = op(op="move", index=2, to=1)
    assert moved.index("# top") < moved.index("# base")
    assert moved.index("roughness(0.1)") < moved.index("roughness(0.9)")
    assert op(op="duplicate", index=1).count("roughness(0.9)") == 2
    deleted = op(op="delete", index=1)
    assert "0.9" not in deleted and "# base" not in deleted and "# top" in deleted
    assert studio.post("/api/layers", {"text": text, "op": "delete", "index": 3}).status == 400
    last = {"text": "Material(Layer(1))", "op": "delete", "index": 1}
    assert studio.post("/api/layers", last).status == 422


def test_seed_operations(studio: StudioServer) -> None:
    text = "# seeds\nDefine(n, fBm(seed=5))  # keep\nMaterial(Layer(1).roughness(n + fBm()))"
    seeds = studio.post("/api/structure", {"text": text}).json()["seeds"]
    auto = next(s for s in seeds if s["auto"])
    assert [s["address"] for s in seeds] == ["define:n.fBm.seed", auto["address"]]
    pinned = studio.post("/api/seeds", {"text": text, "op": "pin"}).json()
    assert pinned["changed"] == [auto["address"]]
    assert f"seed={auto['value']}" in pinned["text"] and "# keep" in pinned["text"]
    one = studio.post("/api/seeds", {"text": text, "op": "reroll", "address": "define:n.fBm.seed"})
    rerolled = one.json()
    assert rerolled["changed"] == ["define:n.fBm.seed"]
    assert rerolled["text"].startswith("# seeds\nDefine(n, fBm(seed=")
    assert rerolled["text"].endswith("  # keep\nMaterial(Layer(1).roughness(n + fBm()))")
    every = studio.post("/api/seeds", {"text": text, "op": "reroll_all"}).json()
    assert len(every["changed"]) == 2
    missing = studio.post("/api/seeds", {"text": text, "op": "reroll", "address": "x"})
    assert missing.status == 400


# ---------------------------------------------------------------------------- evaluate
def _evaluate(studio: StudioServer, **body: object) -> tuple[dict, dict]:
    reply = studio.post("/api/evaluate", body)
    assert reply.status == 200, reply.body[:300]
    assert reply.headers["content-type"] == "application/x-matloom-maps"
    return unpack(reply.body)


def test_evaluate_decodes_and_equals_the_library_packed_the_same_way(
    studio: StudioServer,
) -> None:
    import matloom
    from matloom.studio.wire import map_payloads

    text = demo(studio)
    header, maps = _evaluate(studio, text=text, size=64, seq=1, stream="t-eval")
    assert (header["width"], header["height"], header["seq"]) == (64, 64, 1)
    assert header["pass"] == "full" and header["eval_ms"] > 0
    assert header["total_ms"] >= header["eval_ms"]
    for m in header["maps"]:
        assert m["offset"] % 4 == 0
    assert maps["basecolor"].dtype == np.uint8 and maps["basecolor"].shape == (64, 64, 3)
    assert maps["height"].dtype == np.float32 and maps["height"].shape == (64, 64)
    assert {"normal", "orm", "emissive", "coat", "ior"} <= set(maps)
    assert "sheen" not in maps  # the demo does not write it
    expected, _ = map_payloads(matloom.evaluate(text, 64, 64, backend="numpy"))
    for p in expected:
        np.testing.assert_array_equal(maps[p.name], p.array, err_msg=p.name)


def test_evaluate_hidden_solo_lit_and_raw_channels(studio: StudioServer) -> None:
    text = demo(studio)
    _, solo = _evaluate(studio, text=text, size=32, solo=1, stream="t-solo")
    assert "coat" not in solo  # the coated tiles are layer 2
    header, maps = _evaluate(studio, text=text, size=32, hidden=[1], lit=True,
                             channels=["roughness"], pass_="x", stream="t-lit")  # fmt: skip
    assert maps["lit"].shape == (32, 32, 3) and maps["raw:roughness"].dtype == np.float32
    everything = studio.post("/api/evaluate", {"text": text, "size": 32, "hidden": [1, 2]})
    assert everything.status == 422
    assert studio.post("/api/evaluate", {"text": text, "size": 4096}).status == 400
    bad = studio.post("/api/evaluate", {"text": "Material(Layer(1).rough(1))", "size": 32})
    assert bad.status == 422 and bad.json()["diagnostics"]


def test_evaluate_with_values_evaluates_the_text_set_returns(studio: StudioServer) -> None:
    text = demo(studio)
    address = "define:tileMask.Bricks.mortar"
    params = studio.post("/api/structure", {"text": text}).json()["params"]
    old = next(p["value"] for p in params if p["address"] == address)
    value = old * 1.5
    edited = studio.post("/api/set", {"text": text, "values": {address: value}}).json()
    assert edited["text"] != text and len(edited["text_sha"]) == 16
    header, spec = _evaluate(studio, text=text, values={address: value}, size=32,
                             stream="t-values", pass_="preview")  # fmt: skip
    assert header["text_sha"] == edited["text_sha"]
    plain_header, plain = _evaluate(studio, text=edited["text"], size=32, stream="t-values-b")
    assert "text_sha" not in plain_header and spec.keys() == plain.keys()
    for name, array in plain.items():
        np.testing.assert_array_equal(spec[name], array, err_msg=name)
    for values in ({}, [1], "x", {"define:nope": 1}):
        bad = studio.post("/api/evaluate", {"text": text, "size": 16, "values": values})
        assert bad.status == 400 and "\n" not in bad.json()["error"], values


def test_a_stale_seq_is_superseded(studio: StudioServer) -> None:
    text = demo(studio)
    _evaluate(studio, text=text, size=16, seq=5, stream="t-sup")
    stale = studio.post("/api/evaluate", {"text": text, "size": 16, "seq": 4, "stream": "t-sup"})
    assert stale.status == 409 and "superseded" in stale.json()["error"]
    # other streams are independent
    _evaluate(studio, text=text, size=16, seq=1, stream="t-sup-other")


def test_queued_requests_are_superseded_by_a_newer_one(studio: StudioServer) -> None:
    text = demo(studio)
    statuses: dict[int, int] = {}

    def send(seq: int) -> None:
        body = {"text": text, "size": 512, "seq": seq, "stream": "t-queue"}
        statuses[seq] = studio.post("/api/evaluate", body).status

    threads = [threading.Thread(target=send, args=(seq,)) for seq in range(1, 7)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert statuses[6] == 200
    assert set(statuses.values()) <= {200, 409}


def doubling_chain(levels: int) -> str:
    """2**levels distinct frames of a 16-octave fBm (tests/engine/test_limits.py's reproducer)."""
    lines = ["Define(d0, fBm(octaves=16, seed=1))"]
    for k in range(1, levels + 1):
        lines.append(f"Define(d{k}, Translate(d{k - 1}, 0, 0) + Translate(d{k - 1}, {2**k}, 0))")
    lines.append(f"Material(Layer(1).height(d{levels}))")
    return "\n".join(lines)


def test_a_cost_bomb_gets_its_error_and_the_server_stays_responsive(
    studio: StudioServer,
) -> None:
    # over the cost model at any size: the checker's E071
    bomb = doubling_chain(12)
    reply = studio.post("/api/evaluate", {"text": bomb, "size": 256, "stream": "t-bomb"})
    assert reply.status == 422 and "E071" in reply.json()["error"]
    # checks clean, but over the limits at this size: refused before any work
    heavy = doubling_chain(11)
    assert studio.post("/api/check", {"text": heavy}).json()["ok"] is True
    for size in (1024, 2048):
        reply = studio.post("/api/evaluate", {"text": heavy, "size": size, "stream": "t-bomb"})
        assert reply.status == 422
        error = reply.json()["error"]
        assert "\n" not in error and "lower the size" in error
    _evaluate(studio, text=demo(studio), size=16, stream="t-bomb-after")


def test_compare_two_versions(studio: StudioServer) -> None:
    a = demo(studio)
    b = a.replace("(0.04 + (glazeGrain * 0.05))", "(0.3 + (glazeGrain * 0.05))")
    same = studio.post("/api/compare", {"a": a, "b": a, "size": 32}).json()
    assert same["identical"] is True and same["psnr"] is None and same["ssim"] == 1.0
    diff = studio.post("/api/compare", {"a": a, "b": b, "size": 32, "map": "orm"}).json()
    assert diff["psnr"] > 0 and diff["ssim"] < 1 and diff["map"] == "orm"
    assert studio.post("/api/compare", {"a": a, "b": b, "map": "nope"}).status == 400
