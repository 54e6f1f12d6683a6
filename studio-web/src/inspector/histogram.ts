// A histogram of the shown channel (R, G, B overlaid for colours) with min / mean / max.
import { scalarAt, type Plane } from "./channels";
import { fmt } from "./dom";

const BINS = 128;

export interface HistStats {
  lo: number;
  hi: number;
  min: number;
  mean: number;
  max: number;
}

function bins(values: (i: number) => number, n: number, lo: number, hi: number): Uint32Array {
  const out = new Uint32Array(BINS);
  const span = hi - lo || 1;
  for (let i = 0; i < n; i++) {
    const v = values(i);
    if (!Number.isFinite(v)) continue;
    let b = Math.floor(((v - lo) / span) * BINS);
    b = b < 0 ? 0 : b >= BINS ? BINS - 1 : b;
    out[b]++;
  }
  return out;
}

/** Draw the histogram of `p` on `canvas`; returns its statistics (first component for colours). */
export function drawHistogram(canvas: HTMLCanvasElement, p: Plane): HistStats | null {
  const g = canvas.getContext("2d");
  if (!g) return null;
  const W = canvas.width;
  const H = canvas.height;
  g.fillStyle = "#101215";
  g.fillRect(0, 0, W, H);
  const n = p.width * p.height;
  if (!p.present || n === 0) return null;
  const series: { data: Uint32Array; colour: string }[] = [];
  let lo = p.lo;
  let hi = p.hi;
  let sum = 0;
  let min = Infinity;
  let max = -Infinity;
  if (p.u8 && p.comps >= 3) {
    lo = 0;
    hi = 255;
    const colours = ["rgba(255,80,80,0.6)", "rgba(80,220,80,0.6)", "rgba(90,140,255,0.6)"];
    for (let c = 0; c < 3; c++) {
      const u8 = p.u8;
      const comps = p.comps;
      series.push({ data: bins((i) => u8[i * comps + c], n, 0, 256), colour: colours[c] });
    }
    for (let i = 0; i < n; i++) {
      const v = p.u8[i * p.comps];
      sum += v;
      if (v < min) min = v;
      if (v > max) max = v;
    }
  } else {
    const get = (i: number) => scalarAt(p, i);
    series.push({ data: bins(get, n, lo, hi + (p.f32 ? 0 : 1e-9)), colour: "rgba(210,210,210,0.85)" });
    for (let i = 0; i < n; i++) {
      const v = get(i);
      if (!Number.isFinite(v)) continue;
      sum += v;
      if (v < min) min = v;
      if (v > max) max = v;
    }
  }
  let peak = 1;
  for (const s of series) for (const v of s.data) peak = Math.max(peak, v);
  g.globalCompositeOperation = "lighter";
  const bw = W / BINS;
  for (const s of series) {
    g.fillStyle = s.colour;
    for (let b = 0; b < BINS; b++) {
      // square-root scale: a flat area's spike does not flatten everything else
      const h = Math.sqrt(s.data[b] / peak) * (H - 2);
      g.fillRect(b * bw, H - h, Math.max(1, bw - 0.5), h);
    }
  }
  g.globalCompositeOperation = "source-over";
  return { lo, hi, min, mean: sum / n, max };
}

export function statsText(s: HistStats | null, colour: boolean): string {
  if (!s) return "";
  const unit = colour ? " (R, sRGB bytes)" : "";
  return `min ${fmt(s.min)} · mean ${fmt(s.mean)} · max ${fmt(s.max)}${unit} · axis ${fmt(s.lo)}…${fmt(s.hi)}`;
}
