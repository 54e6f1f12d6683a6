// The channels the inspector can show and how each is read out of the decoded maps.
import type { Maps } from "../api";

/** How a channel's values are shown and read. */
export type Kind = "colour" | "normal" | "unit" | "angle" | "height" | "ior";

export interface ChannelDef {
  id: string;
  label: string;
  kind: Kind;
  /** The u8 map holding it and the component (orm packs AO, roughness, metallic). */
  u8?: { map: string; comp: number };
  /** The `MaterialMaps` field to request as float32 (`channels: [...]`; it comes back as
   * `raw:<field>`) for the exact value under the cursor. */
  raw?: string;
  /** The value where the program does not write the channel. */
  fallback?: number;
}

/** The 13 channels of the registry plus the derived normal and AO (registry order). */
export const CHANNELS: ChannelDef[] = [
  { id: "basecolor", label: "base colour", kind: "colour", u8: { map: "basecolor", comp: 0 }, raw: "basecolor_linear" },
  { id: "normal", label: "normal", kind: "normal", u8: { map: "normal", comp: 0 }, raw: "normal" },
  { id: "roughness", label: "roughness (ORM g)", kind: "unit", u8: { map: "orm", comp: 1 }, raw: "roughness" },
  { id: "metallic", label: "metallic (ORM b)", kind: "unit", u8: { map: "orm", comp: 2 }, raw: "metallic" },
  { id: "ao", label: "AO (ORM r)", kind: "unit", u8: { map: "orm", comp: 0 }, raw: "ao" },
  { id: "height", label: "height", kind: "height", raw: "height", fallback: 0 },
  { id: "emissive", label: "emissive", kind: "colour", u8: { map: "emissive", comp: 0 }, raw: "emissive_linear" },
  { id: "alpha", label: "alpha", kind: "unit", u8: { map: "alpha", comp: 0 }, raw: "alpha", fallback: 1 },
  { id: "sheen", label: "sheen", kind: "unit", u8: { map: "sheen", comp: 0 }, raw: "sheen", fallback: 0 },
  { id: "coat", label: "coat", kind: "unit", u8: { map: "coat", comp: 0 }, raw: "coat", fallback: 0 },
  {
    id: "transmission",
    label: "transmission",
    kind: "unit",
    u8: { map: "transmission", comp: 0 },
    raw: "transmission",
    fallback: 0,
  },
  {
    id: "subsurface",
    label: "subsurface",
    kind: "unit",
    u8: { map: "subsurface", comp: 0 },
    raw: "subsurface",
    fallback: 0,
  },
  {
    id: "anisotropy",
    label: "anisotropy",
    kind: "unit",
    u8: { map: "anisotropy", comp: 0 },
    raw: "anisotropy",
    fallback: 0,
  },
  {
    id: "anisotropy_angle",
    label: "anisotropy angle",
    kind: "angle",
    u8: { map: "anisotropy_angle", comp: 0 },
    raw: "anisotropy_angle",
    fallback: 0,
  },
  { id: "ior", label: "IOR", kind: "ior", raw: "ior", fallback: 1.5 },
];

export function channel(id: string): ChannelDef {
  return CHANNELS.find((c) => c.id === id) ?? CHANNELS[0];
}

/** One channel's data out of one maps reply: exact floats when there, else the 8-bit map. */
export interface Plane {
  def: ChannelDef;
  width: number;
  height: number;
  /** Components per texel in `u8` (3 for colours and the normal, else 1 after extraction). */
  comps: number;
  u8: Uint8Array | null;
  /** The exact values (3 per texel for colours and the normal, else 1). */
  f32: Float32Array | null;
  f32comps: number;
  /** Value range used for the grey display of a scalar ([0, 1] for unit channels). */
  lo: number;
  hi: number;
  /** False when the program does not write the channel (its map is constant, the default). */
  present: boolean;
}

/** The float map of a channel in a reply: the requested raw field, else the wire's own
 * float map of that name (height, ior). */
export function floats(maps: Maps, def: ChannelDef): Float32Array | null {
  return (def.raw && maps.f32[`raw:${def.raw}`]) || maps.f32[def.id] || null;
}

/** Is the exact float map of `def` already in this reply? */
export function hasFloats(maps: Maps, def: ChannelDef): boolean {
  return !def.raw || floats(maps, def) !== null;
}

/** The values of a scalar 8-bit map in its own units (angle: degrees). */
function fromByte(def: ChannelDef, b: number): number {
  return def.kind === "angle" ? (b / 255) * 180 : b / 255;
}

function extract(src: Uint8Array, stride: number, comp: number, n: number): Uint8Array {
  if (stride === 1 && comp === 0) return src;
  const out = new Uint8Array(n);
  for (let i = 0; i < n; i++) out[i] = src[i * stride + comp];
  return out;
}

function range(a: Float32Array): [number, number] {
  let lo = Infinity;
  let hi = -Infinity;
  for (let i = 0; i < a.length; i++) {
    const v = a[i];
    if (!Number.isFinite(v)) continue;
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  if (lo > hi) return [0, 1];
  return [lo, hi];
}

export function plane(maps: Maps, def: ChannelDef): Plane {
  const { width, height } = maps.header;
  const n = width * height;
  const vec = def.kind === "colour" || def.kind === "normal";
  const f32comps = vec ? 3 : 1;
  const fl = floats(maps, def);
  const f32 = fl && fl.length === n * f32comps ? fl : null;
  let u8: Uint8Array | null = null;
  let comps = 1;
  if (def.u8 && maps.u8[def.u8.map]) {
    const stride = maps.channels[def.u8.map] ?? 1;
    if (vec) {
      comps = stride;
      u8 = maps.u8[def.u8.map];
    } else {
      u8 = extract(maps.u8[def.u8.map], stride, def.u8.comp, n);
    }
  }
  let lo = 0;
  let hi = 1;
  if (def.kind === "angle") hi = 180;
  if ((def.kind === "height" || def.kind === "ior") && f32) [lo, hi] = range(f32);
  // Written by the program: the wire sends the optional 8-bit maps (and ior) only then; the
  // raw floats come whenever asked for (a constant default where not written).
  const present = Boolean(u8) || def.kind === "height" || (def.kind === "ior" && Boolean(maps.f32.ior));
  return { def, width, height, comps, u8, f32, f32comps, lo, hi, present };
}

/** The scalar value of texel i (NaN for colours), exact when the floats are there. */
export function scalarAt(p: Plane, i: number): number {
  if (p.f32 && p.f32comps === 1) return p.f32[i];
  if (p.u8 && p.comps === 1) return fromByte(p.def, p.u8[i]);
  if (p.def.fallback !== undefined && !p.u8) return p.def.fallback;
  return NaN;
}

/** RGBA pixels for display: colours as stored (sRGB), scalars as grey over [lo, hi]. */
export function toImage(p: Plane, lo = p.lo, hi = p.hi): ImageData {
  const n = p.width * p.height;
  const img = new ImageData(p.width, p.height);
  const d = img.data;
  if (p.u8 && p.comps >= 3) {
    for (let i = 0; i < n; i++) {
      d[i * 4] = p.u8[i * p.comps];
      d[i * 4 + 1] = p.u8[i * p.comps + 1];
      d[i * 4 + 2] = p.u8[i * p.comps + 2];
      d[i * 4 + 3] = 255;
    }
    return img;
  }
  const span = hi - lo || 1;
  for (let i = 0; i < n; i++) {
    let g: number;
    if (p.f32 && p.f32comps === 1) {
      const v = p.def.kind === "angle" ? ((p.f32[i] % 180) + 180) % 180 : p.f32[i];
      g = Math.round(((v - lo) / span) * 255);
    }
    else if (p.u8) g = p.def.kind === "angle" || p.def.kind === "unit" ? p.u8[i] : 0;
    else g = Math.round((((p.def.fallback ?? 0) - lo) / span) * 255);
    g = g < 0 ? 0 : g > 255 ? 255 : g;
    d[i * 4] = d[i * 4 + 1] = d[i * 4 + 2] = g;
    d[i * 4 + 3] = 255;
  }
  return img;
}

/** sRGB byte -> linear light (the exact sRGB transfer function). */
export function srgbToLinear(b: number): number {
  const c = b / 255;
  return c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4);
}
