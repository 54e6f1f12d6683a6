// Slider spans, steps and number formatting for the panel's parameters.
import type { Param } from "../store";

/** Seeds lie in [0, 2**31) (matloom.lang.seeds.SEED_LIMIT). */
export const SEED_MAX = 2 ** 31 - 1;

export interface Span {
  lo: number;
  hi: number;
  step: number;
  integer: boolean;
  /** Decimal places a value is rounded to (the step's). */
  decimals: number;
}

export function isInteger(p: Param): boolean {
  return p.kind === "count" || p.kind === "seed";
}

/** Decimal places of a power-of-ten step: 0.001 -> 3, 1 -> 0. */
function decimalsOf(step: number): number {
  return step >= 1 ? 0 : Math.min(10, Math.round(-Math.log10(step)));
}

function niceStep(width: number): number {
  if (!(width > 0) || !Number.isFinite(width)) return 0.001;
  return 10 ** Math.floor(Math.log10(width / 200));
}

/** The slider span of a parameter at value `v`: the registry range where it is bounded,
 * else a sensible span around the value ([0, 4v] for sizes and frequencies). The number
 * box is not bound by it. */
export function spanOf(p: Param, v: number): Span {
  const integer = isInteger(p);
  let lo = p.low;
  let hi = p.high;
  if (p.kind === "seed") {
    lo ??= 0;
    hi ??= Math.max(SEED_MAX, v);
  } else if (p.kind === "angle" && lo === null && hi === null) {
    lo = Math.min(-180, v);
    hi = Math.max(180, v);
  } else if (lo === null && hi === null) {
    const a = Math.abs(v);
    if ((p.kind === "size" || p.kind === "frequency") && v >= 0) {
      lo = 0;
      hi = v > 0 ? 4 * v : 1;
    } else {
      const w = a > 0 ? 2 * a : 1;
      lo = v - w;
      hi = v + w;
    }
  } else if (hi === null) {
    const l = lo as number;
    const d = v - l;
    hi = integer ? Math.max(l + 8, l + 2 * d) : d > 0 ? l + 4 * d : l + 1;
  } else if (lo === null) {
    const d = hi - v;
    lo = integer ? Math.min(hi - 8, hi - 2 * d) : d > 0 ? hi - 4 * d : hi - 1;
  }
  lo = Math.min(lo as number, v);
  hi = Math.max(hi as number, v);
  if (hi <= lo) hi = lo + 1;
  const step = integer ? 1 : niceStep(hi - lo);
  return { lo, hi, step, integer, decimals: integer ? 0 : decimalsOf(step) };
}

/** Round a slider value to its step's precision (no float noise in the program text). */
export function roundTo(v: number, s: Span): number {
  if (s.integer) return Math.round(v);
  return Number(v.toFixed(s.decimals));
}

/** A number as the number box shows it: the value's own digits, at most 6 significant. */
export function fmtNumber(v: number): string {
  if (Number.isInteger(v)) return String(v);
  return String(Number(v.toPrecision(6)));
}

/** Metres in the nearest friendly unit: 0.004 -> "4 mm", 0.25 -> "25 cm", 1.5 -> "1.5 m". */
export function fmtMetres(m: number): string {
  const a = Math.abs(m);
  if (a === 0) return "0 m";
  if (a < 0.001) return `${Number((m * 1e6).toPrecision(3))} µm`;
  if (a < 0.01) return `${Number((m * 1000).toPrecision(3))} mm`;
  if (a < 1) return `${Number((m * 100).toPrecision(3))} cm`;
  return `${Number(m.toPrecision(4))} m`;
}

const SHORT_UNITS: Record<string, string> = { units: "u", "cycles/unit": "/u", degrees: "°", "sRGB 0-255": "" };

/** The unit after a value: `text` short (a size with a known scale in metres, else the unit
 * abbreviated), `title` in full. */
export function unitText(p: Param, v: number, unitM: number | null): { text: string; title: string } {
  if (!p.unit || p.kind === "colour") return { text: "", title: "" };
  let m = p.metres ?? null;
  if (p.unit === "units" && unitM !== null && unitM > 0) m = v * unitM;
  const unit = p.unit === "units" ? "coordinate units" : p.unit;
  if (m !== null && m !== undefined) return { text: fmtMetres(m), title: `${unit} (= ${fmtMetres(m)})` };
  return { text: SHORT_UNITS[p.unit] ?? p.unit, title: unit };
}

/** sRGB 0-255 triple <-> "#rrggbb". */
export function rgbToHex(rgb: number[]): string {
  return (
    "#" +
    rgb
      .slice(0, 3)
      .map((c) => Math.max(0, Math.min(255, Math.round(c))).toString(16).padStart(2, "0"))
      .join("")
  );
}

export function hexToRgb(hex: string): [number, number, number] {
  const n = parseInt(hex.slice(1, 7), 16);
  return [(n >> 16) & 255, (n >> 8) & 255, n & 255];
}
