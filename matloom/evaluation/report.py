"""A bench's outputs: ``results.csv``, ``summary.json`` and a self-contained ``report.html``
(tables, matplotlib plots and contact sheets embedded as PNG data; needs the ``[bench]`` extra).
"""

from __future__ import annotations

import base64
import csv
import html
import io
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from matloom.evaluation.stats import (
    Row,
    contrasts,
    prompt_means,
    source_table,
    system_table,
)

CSV_COLUMNS = ("prompt_id", "source", "system", "run", "seed", "metric", "value")
#: Prompts shown per end (best, worst) in each contact sheet.
SHEET_PROMPTS = 3
THUMB = 112


@dataclass
class ReportInput:
    """What a report is made of: the plan, the scores and the cells' preview images."""

    prompts: dict[str, tuple[str, str]]  # prompt_id -> (text, source)
    systems: list[str]
    seeds: tuple[int, ...]
    rows: list[Row]
    pairs: list[tuple[str, str]]
    images: dict[tuple[str, str, int], Path] = field(default_factory=dict)
    cells: dict[str, int] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    resamples: int = 10_000

    @property
    def metrics(self) -> list[str]:
        return sorted({r.metric for r in self.rows})


def results_csv(rows: Sequence[Row]) -> bytes:
    """One line per prompt x system x run x metric value."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for r in sorted(rows, key=lambda r: (r.metric, r.system, r.prompt_id, r.run)):
        value = "" if not math.isfinite(r.value) else repr(float(r.value))
        writer.writerow([r.prompt_id, r.source, r.system, r.run, r.seed, r.metric, value])
    return buf.getvalue().encode("utf-8")


def read_results_csv(path: Path) -> list[Row]:
    """The rows of a ``results.csv`` (empty values read as NaN)."""
    with path.open(encoding="utf-8", newline="") as fh:
        return [
            Row(
                prompt_id=d["prompt_id"],
                source=d["source"],
                system=d["system"],
                run=int(d["run"]),
                seed=int(d["seed"]),
                metric=d["metric"],
                value=float(d["value"]) if d["value"] else math.nan,
            )
            for d in csv.DictReader(fh)
        ]


def summarize(data: ReportInput) -> dict[str, Any]:
    """``summary.json``: the per-system table, the Holm-adjusted contrasts, per-source tables."""
    metrics = data.metrics
    means = prompt_means(data.rows)
    sources = {pid: src for pid, (_, src) in data.prompts.items()}
    found = contrasts(means, data.pairs, metrics, resamples=data.resamples)
    return {
        "systems": data.systems,
        "seeds": list(data.seeds),
        "prompts": len(data.prompts),
        "metrics": metrics,
        "cells": data.cells,
        "rows": len(data.rows),
        "notes": data.notes,
        "table": system_table(means, data.systems, metrics),
        "contrasts": [c.as_dict() for c in found],
        "holm_family": len([c for c in found if math.isfinite(c.p)]),
        "by_source": source_table(
            means, sources, data.systems, metrics, data.pairs, resamples=data.resamples
        ),
    }


# ----------------------------------------------------------------------------- HTML


def _fmt(v: Any, digits: int = 2) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "–"
    if isinstance(v, float):
        return f"{v:.{digits}f}" if abs(v) >= 1e-3 or v == 0 else f"{v:.2e}"
    return html.escape(str(v))


def _table(head: Sequence[str], body: Sequence[Sequence[Any]]) -> str:
    th = "".join(f"<th>{html.escape(h)}</th>" for h in head)
    trs = "".join("<tr>" + "".join(f"<td>{_fmt(c)}</td>" for c in row) + "</tr>" for row in body)
    return f"<table><thead><tr>{th}</tr></thead><tbody>{trs}</tbody></table>"


def _png_data(fig: Any) -> str:
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    FigureCanvasAgg(fig)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def _plots(data: ReportInput, summary: dict[str, Any]) -> list[str]:
    """Per metric: the per-prompt means of each system (box plot); one forest plot of the
    contrasts' mean differences with their CIs."""
    from matplotlib.figure import Figure

    means = prompt_means(data.rows)
    out = []
    for metric in data.metrics:
        fig = Figure(figsize=(1.2 + 1.1 * len(data.systems), 2.6))
        ax = fig.add_subplot()
        series = [
            [v for (s, m, _), v in means.items() if s == sys and m == metric]
            for sys in data.systems
        ]
        ax.boxplot([s or [math.nan] for s in series], showmeans=True)
        ax.set_xticks(range(1, len(data.systems) + 1), data.systems, fontsize=8)
        ax.set_title(f"{metric}: per-prompt means", fontsize=9)
        out.append(f'<img alt="{html.escape(metric)}" src="{_png_data(fig)}">')
    found = [c for c in summary["contrasts"] if c["mean_diff"] is not None]
    if found:
        fig = Figure(figsize=(6, 0.5 + 0.28 * len(found)))
        ax = fig.add_subplot()
        for y, c in enumerate(found):
            low = c["ci_low"] if c["ci_low"] is not None else c["mean_diff"]
            high = c["ci_high"] if c["ci_high"] is not None else c["mean_diff"]
            ax.plot([low, high], [y, y], color="0.3")
            ax.plot([c["mean_diff"]], [y], "o", color="C0")
        ax.axvline(0, color="0.6", lw=0.8)
        labels = [f"{c['a']}−{c['b']} {c['metric']}" for c in found]
        ax.set_yticks(range(len(found)), labels, fontsize=7)
        ax.set_title("paired mean differences, 95 % bootstrap CI", fontsize=9)
        out.append(f'<img alt="contrasts" src="{_png_data(fig)}">')
    return out


def _thumb_data(path: Path) -> str:
    from PIL import Image

    with Image.open(path) as img:
        img = img.convert("RGB")
        img.thumbnail((THUMB, THUMB))
        buf = io.BytesIO()
        img.save(buf, format="JPEG", quality=85)
    return "data:image/jpeg;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def _sheets(data: ReportInput) -> tuple[list[str], str]:
    """Per metric and system: the best and worst prompts, each with its first run's image.
    Each image is embedded once, as a CSS class the sheets reuse; returns (HTML, CSS)."""
    means = prompt_means(data.rows)
    classes: dict[Path, str] = {}
    out = []
    for metric in data.metrics:
        for system in data.systems:
            ranked = sorted(
                ((v, p) for (s, m, p), v in means.items() if s == system and m == metric),
                reverse=True,
            )
            if not ranked:
                continue
            ends = [("best", ranked[:SHEET_PROMPTS]), ("worst", ranked[::-1][:SHEET_PROMPTS])]
            cells = []
            for label, items in ends:
                for value, pid in items:
                    runs = [r for (p, s, r) in data.images if p == pid and s == system]
                    path = data.images.get((pid, system, min(runs))) if runs else None
                    css = "missing"
                    if path is not None and path.is_file():
                        css = classes.setdefault(path, f"t{len(classes)}")
                    text = html.escape(data.prompts[pid][0][:90])
                    cells.append(
                        f'<figure><div class="th {css}"></div><figcaption>'
                        f"<b>{label} {_fmt(value)}</b> {html.escape(pid)}<br>{text}"
                        "</figcaption></figure>"
                    )
            title = f"{html.escape(metric)} — {html.escape(system)}"
            out.append(f'<h3>{title}</h3><div class="sheet">{"".join(cells)}</div>')
    css = "\n".join(f".{c}{{background-image:url({_thumb_data(p)})}}" for p, c in classes.items())
    return out, css


CSS = """body{font:14px system-ui,sans-serif;margin:2em;max-width:1200px}
table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ccc;padding:2px 6px;
text-align:right}th{background:#eee}td:first-child{text-align:left}
.sheet{display:flex;flex-wrap:wrap;gap:6px}figure{margin:0;width:128px;font-size:10px}
.th{width:112px;height:112px;background:#eee center/contain no-repeat}img{max-width:100%}"""


def report_html(data: ReportInput, summary: dict[str, Any]) -> bytes:
    """The self-contained HTML report."""
    metrics = data.metrics
    sheets, thumbs = _sheets(data) if metrics else ([], "")
    parts = [
        "<!doctype html><html><head><meta charset='utf-8'><title>MatLoom bench</title>",
        f"<style>{CSS}\n{thumbs}</style></head><body><h1>MatLoom bench</h1>",
        f"<p>{len(data.prompts)} prompts × {len(data.systems)} systems × {len(data.seeds)} "
        f"runs (seeds {', '.join(map(str, data.seeds))}); cells: "
        + ", ".join(f"{k} {v}" for k, v in data.cells.items())
        + "</p>",
    ]
    parts += [f"<p class='note'>{html.escape(n)}</p>" for n in data.notes]
    parts.append("<h2>Means over prompts (of per-prompt run means)</h2>")
    table = summary["table"]
    parts.append(
        _table(
            ["metric", *[f"{s} (n)" for s in data.systems]],
            [
                [m, *[f"{_fmt(table[m][s]['mean'])} ({table[m][s]['n']})" for s in data.systems]]
                for m in metrics
            ],
        )
    )
    if summary["contrasts"]:
        parts.append(f"<h2>Paired differences (Holm over {summary['holm_family']} tests)</h2>")
        head = ["contrast", "metric", "n", "mean diff", "95 % CI", "W", "p", "p (Holm)"]
        body = [
            [
                f"{c['a']} − {c['b']}",
                c["metric"],
                c["n"],
                c["mean_diff"],
                f"[{_fmt(c['ci_low'])}, {_fmt(c['ci_high'])}]",
                c["wilcoxon_w"],
                c["p"],
                c["p_holm"],
            ]
            for c in summary["contrasts"]
        ]
        parts.append(_table(head, body))
    parts.append("<h2>Per source</h2>")
    for src, entry in summary["by_source"].items():
        parts.append(f"<h3>{html.escape(src)} ({entry['n']} prompts)</h3>")
        parts.append(
            _table(
                ["metric", *data.systems],
                [[m, *[entry["means"][m][s] for s in data.systems]] for m in metrics],
            )
        )
    if metrics:
        parts.append("<h2>Plots</h2>")
        parts += _plots(data, summary)
        parts.append("<h2>Best and worst prompts</h2>")
        parts += sheets
    parts.append("</body></html>")
    return "\n".join(parts).encode("utf-8")


def summary_json(summary: dict[str, Any]) -> bytes:
    return json.dumps(summary, indent=2, sort_keys=True, allow_nan=False).encode("utf-8")
