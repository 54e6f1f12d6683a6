"""The report files: results.csv round trip, summary.json strict JSON, a self-contained HTML."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("scipy", reason="needs the bench extra (pip install 'matloom[bench]')")
pytest.importorskip("matplotlib", reason="needs the bench extra (pip install 'matloom[bench]')")

from matloom.evaluation.report import (  # noqa: E402
    CSV_COLUMNS,
    ReportInput,
    read_results_csv,
    report_html,
    results_csv,
    summarize,
    summary_json,
)
from matloom.evaluation.stats import Row  # noqa: E402
from matloom.io.png import save_png  # noqa: E402


def _data(tmp_path: Path) -> ReportInput:
    rows, images = [], {}
    for i in range(5):
        pid = f"p{i}"
        for system, shift in (("a", 2.0), ("b", 0.0)):
            path = tmp_path / f"{pid}-{system}.png"
            save_png(path, np.full((16, 16, 3), 40 * i + int(shift), dtype=np.uint8))
            images[(pid, system, 0)] = path
            for run in (0, 1):
                rows.append(Row(pid, "S" + str(i % 2), system, run, 42, "m", i + shift + run))
        rows.append(Row(pid, "S" + str(i % 2), "a", 0, 42, "empty", math.nan))
    return ReportInput(
        prompts={f"p{i}": (f"prompt <{i}>", "S" + str(i % 2)) for i in range(5)},
        systems=["a", "b"],
        seeds=(42, 123),
        rows=rows,
        pairs=[("a", "b")],
        images=images,
        cells={"total": 20, "done": 20, "missing": 0},
        resamples=300,
    )


def test_results_csv_round_trip(tmp_path: Path) -> None:
    data = _data(tmp_path)
    path = tmp_path / "results.csv"
    path.write_bytes(results_csv(data.rows))
    assert path.read_text(encoding="utf-8").splitlines()[0] == ",".join(CSV_COLUMNS)
    back = read_results_csv(path)
    assert len(back) == len(data.rows)
    key = lambda r: (r.metric, r.system, r.prompt_id, r.run)  # noqa: E731
    for got, want in zip(sorted(back, key=key), sorted(data.rows, key=key), strict=True):
        assert (got.prompt_id, got.system, got.run, got.metric) == (
            want.prompt_id, want.system, want.run, want.metric,
        )  # fmt: skip
        assert (math.isnan(got.value) and math.isnan(want.value)) or got.value == want.value


def test_summary_and_html(tmp_path: Path) -> None:
    data = _data(tmp_path)
    summary = summarize(data)
    json.loads(summary_json(summary))  # strict JSON: no NaN
    assert summary["table"]["m"]["a"]["mean"] == pytest.approx(4.5)  # mean of i + 2.5
    c = next(c for c in summary["contrasts"] if c["metric"] == "m")
    assert c["mean_diff"] == pytest.approx(2.0) and c["n"] == 5
    assert set(summary["by_source"]) == {"S0", "S1"}
    page = report_html(data, summary).decode("utf-8")
    assert "prompt &lt;3&gt;" in page  # escaped
    assert not re.search(r'(src|href)="(?!data:)', page)  # self-contained
    assert page.count("data:image/png;base64,") >= 2  # a box plot per metric, the forest plot
    assert page.count("data:image/jpeg;base64,") == 10  # each thumbnail embedded once
