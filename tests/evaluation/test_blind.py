"""Blind judging: `bench pack` writes shuffled sheets with only the descriptions and a separate
key; `bench collect` folds judges' scores back into results.csv as a metric."""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any

import pytest
from click.testing import CliRunner

pytest.importorskip("scipy", reason="needs the bench extra (pip install 'matloom[bench]')")
pytest.importorskip("matplotlib", reason="needs the bench extra (pip install 'matloom[bench]')")

from matloom.cli.main import cli  # noqa: E402

PROMPTS = Path(__file__).parents[1] / "data" / "prompts-dev.json"


@pytest.fixture
def bench(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    monkeypatch.setenv("MATLOOM_CONFIG", str(tmp_path / "no-such.toml"))
    data = json.loads(PROMPTS.read_text(encoding="utf-8"))
    prompts = tmp_path / "p.json"
    prompts.write_text(json.dumps({"prompts": data["prompts"][:4]}), encoding="utf-8")
    out = tmp_path / "bench"
    result = CliRunner().invoke(
        cli,
        ["bench", str(prompts), "--system", "lib=library", "--runs", "2", "--size", "32",
         "--layouts", "quick", "--metric", "size", "--quiet", "-o", str(out)],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    return out


def _rows(out: Path) -> list[dict[str, str]]:
    with (out / "results.csv").open(encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def test_pack_then_collect(bench: Path, tmp_path: Path) -> None:
    result = CliRunner().invoke(cli, ["bench", "pack", str(bench), "--per-sheet", "3"])
    assert result.exit_code == 0, result.output
    sheets = bench / "blind" / "judge_blind" / "sheets"
    assert sorted(p.name for p in sheets.iterdir()) == [
        "sheet_001.json", "sheet_001.png", "sheet_002.json", "sheet_002.png",
        "sheet_003.json", "sheet_003.png",
    ]  # fmt: skip
    key: dict[str, Any] = json.loads((sheets.parent / "key.json").read_text(encoding="utf-8"))
    assert len(key) == 8  # 4 prompts x 2 runs
    texts = {}
    for f in sorted(sheets.glob("*.json")):
        texts.update(json.loads(f.read_text(encoding="utf-8")))
    assert set(texts) == set(key)
    # the judge sees only descriptions: no system, seed, run or cell key in the sheets' texts
    blob = json.dumps(texts)
    assert "lib" not in blob and not any(k["key"] in blob for k in key.values())
    # shuffled: the ids do not follow the plan's order of (prompt, run)
    order = [(k["prompt_id"], k["run"]) for _, k in sorted(key.items())]
    assert order != sorted(order)

    ids = sorted(key)
    judge1 = {i: {"score": 10 * n, "why": "ok"} for n, i in enumerate(ids)}
    judge2 = {i: {"score": 10 * n + 20} for n, i in enumerate(ids[:4])}
    f1, f2 = tmp_path / "j1.json", tmp_path / "j2.json"
    f1.write_text(json.dumps(judge1), encoding="utf-8")
    f2.write_text(json.dumps(judge2), encoding="utf-8")
    before = _rows(bench)
    result = CliRunner().invoke(cli, ["bench", "collect", str(bench), str(f1), str(f2)])
    assert result.exit_code == 0, result.output
    rows = _rows(bench)
    judged = [r for r in rows if r["metric"] == "judge_blind"]
    assert len(judged) == 8 and len(rows) == len(before) + 8
    expect = {
        (key[i]["prompt_id"], str(key[i]["run"])): 10 * n + (10 if n < 4 else 0)
        for n, i in enumerate(ids)
    }  # the mean of the two judges where both scored
    got = {(r["prompt_id"], r["run"]): float(r["value"]) for r in judged}
    assert got == pytest.approx(expect)
    summary = json.loads((bench / "summary.json").read_text(encoding="utf-8"))
    assert "judge_blind" in summary["metrics"]


@pytest.mark.parametrize(
    ("scores", "message"),
    [
        ({"m9999": {"score": 5}}, "unknown image id 'm9999'"),
        ({"m0001": {"score": 150}}, "outside 0-100"),
        ({"m0001": {"why": "x"}}, 'numeric "score"'),
    ],
)
def test_collect_refuses_bad_scores(
    bench: Path, tmp_path: Path, scores: dict[str, Any], message: str
) -> None:
    assert CliRunner().invoke(cli, ["bench", "pack", str(bench)]).exit_code == 0
    f = tmp_path / "bad.json"
    f.write_text(json.dumps(scores), encoding="utf-8")
    result = CliRunner().invoke(cli, ["bench", "collect", str(bench), str(f)])
    assert result.exit_code != 0 and message in result.output
    assert len(result.output.strip().splitlines()) == 1


def test_collect_before_pack_is_one_line(bench: Path, tmp_path: Path) -> None:
    f = tmp_path / "s.json"
    f.write_text("{}", encoding="utf-8")
    result = CliRunner().invoke(cli, ["bench", "collect", str(bench), str(f)])
    assert result.exit_code != 0 and "run `matloom bench pack" in result.output
