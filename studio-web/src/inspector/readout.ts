// The program's value under the cursor, in the channel's own units.
import { scalarAt, srgbToLinear, type Plane } from "./channels";
import { fmt } from "./dom";

function hex(r: number, g: number, b: number): string {
  return "#" + [r, g, b].map((v) => v.toString(16).padStart(2, "0")).join("");
}

/** Lines describing texel (x, y) of `p` (row 0 = top); `unitM` metres per coordinate unit,
 * `emissiveScale` the factor the 8-bit emission map is multiplied by (header `emissive_scale`). */
export function describe(p: Plane, x: number, y: number, unitM: number | null, emissiveScale = 0): string[] {
  const i = y * p.width + x;
  const where = `texel ${x}, ${y}`;
  const def = p.def;
  if (def.kind === "colour" && p.u8) {
    const [r, g, b] = [p.u8[i * p.comps], p.u8[i * p.comps + 1], p.u8[i * p.comps + 2]];
    const exact = p.f32 ? [p.f32[i * 3], p.f32[i * 3 + 1], p.f32[i * 3 + 2]] : null;
    const lin = (exact ?? [r, g, b].map(srgbToLinear)).map((c) => c.toFixed(4)).join(", ");
    const note = exact ? "" : "  (from the 8-bit sRGB)";
    const label = def.id === "emissive" ? "radiance (linear)" : "linear";
    return [where, `sRGB ${r}, ${g}, ${b}  ${hex(r, g, b)}${def.id === "emissive" && emissiveScale ? `  × ${fmt(emissiveScale)}` : ""}`, `${label} ${lin}${note}`];
  }
  if (def.kind === "normal" && p.u8) {
    const raw = [p.u8[i * p.comps], p.u8[i * p.comps + 1], p.u8[i * p.comps + 2]];
    const n = p.f32 ? [p.f32[i * 3], p.f32[i * 3 + 1], p.f32[i * 3 + 2]] : raw.map((c) => (c / 255) * 2 - 1);
    return [where, `n ${n.map((c) => c.toFixed(4)).join(", ")}  (OpenGL, +y up)`, `bytes ${raw.join(", ")}`];
  }
  if (!p.present) {
    const v = scalarAt(p, i);
    return [where, `not written by the program: ${Number.isNaN(v) ? "its default" : fmt(v)} everywhere`];
  }
  const v = scalarAt(p, i);
  const exact = p.f32 ? "" : "  (8-bit)";
  if (def.kind === "height") {
    const m = unitM ? `  = ${fmt(v * unitM)} m` : "  (no unit_m)";
    return [where, `height ${fmt(v, 5)} units${m}`];
  }
  if (def.kind === "angle") return [where, `${fmt(v, 4)}°${exact}`];
  return [where, `${def.id} ${fmt(v, 5)}${exact}`];
}
