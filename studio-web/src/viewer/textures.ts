// GPU textures made from the decoded maps (row 0 = top), reused between evaluations.
//
// Every texture is flipped on the CPU while it is packed (row 0 of the maps = top of the image =
// v = 1 in three's UVs), so flipY stays false and the normal map's tangent frame keeps the
// OpenGL convention. A texture of the same name and size is updated in place (the fast path for
// slider drags); the pool keeps two sizes per name so the 256 px first pass and the full pass
// alternate without reallocating.
import {
  ClampToEdgeWrapping,
  DataTexture,
  FloatType,
  LinearFilter,
  LinearMipmapLinearFilter,
  NearestFilter,
  NoColorSpace,
  RedFormat,
  RepeatWrapping,
  RGBAFormat,
  SRGBColorSpace,
  UnsignedByteType,
  type Texture,
  type Wrapping,
} from "three";
import { PREVIEW_SIZE } from "../live";

/** Whether this machine stores a Uint32 little-endian (then RGBA packs one word per texel). */
const LITTLE_ENDIAN = new Uint8Array(new Uint32Array([1]).buffer)[0] === 1;

/** Fill `dst` (RGBA, rows flipped) from a source of `channels` bytes per pixel. */
export function packRgba(src: Uint8Array, channels: number, w: number, h: number, dst: Uint8Array): void {
  if (channels === 4) {
    for (let y = 0; y < h; y++) dst.set(src.subarray((h - 1 - y) * w * 4, (h - y) * w * 4), y * w * 4);
    return;
  }
  if (LITTLE_ENDIAN && dst.byteOffset % 4 === 0) {
    // One 32-bit store per texel (A = 255 in the top byte): about twice as fast at 512 px.
    const out = new Uint32Array(dst.buffer, dst.byteOffset, w * h);
    for (let y = 0; y < h; y++) {
      let s = (h - 1 - y) * w * channels;
      let d = y * w;
      if (channels === 3) {
        for (let x = 0; x < w; x++, s += 3, d++) out[d] = (src[s] | (src[s + 1] << 8) | (src[s + 2] << 16) | 0xff000000) >>> 0;
      } else {
        for (let x = 0; x < w; x++, s += channels, d++) out[d] = ((src[s] * 0x010101) | 0xff000000) >>> 0;
      }
    }
    return;
  }
  for (let y = 0; y < h; y++) {
    let s = (h - 1 - y) * w * channels;
    let d = y * w * 4;
    for (let x = 0; x < w; x++, s += channels, d += 4) {
      const one = channels < 3;
      dst[d] = src[s];
      dst[d + 1] = src[one ? s : s + 1];
      dst[d + 2] = src[one ? s : s + 2];
      dst[d + 3] = 255;
    }
  }
}

/** three's anisotropy map: RG = direction (cos, sin) 0.5-biased, B = strength (rows flipped).
 * `angle` holds MatLoom's brushing direction (0..255 = 0..180 degrees); the highlight stretches
 * across it, so three's direction is angle + 90 degrees. */
export function packAnisotropy(
  strength: Uint8Array,
  angle: Uint8Array | undefined,
  w: number,
  h: number,
  dst: Uint8Array,
): void {
  const cos = new Float32Array(256);
  const sin = new Float32Array(256);
  for (let i = 0; i < 256; i++) {
    const a = ((i / 255) * 180 + 90) * (Math.PI / 180);
    cos[i] = Math.cos(a) * 0.5 + 0.5;
    sin[i] = Math.sin(a) * 0.5 + 0.5;
  }
  for (let y = 0; y < h; y++) {
    let s = (h - 1 - y) * w;
    let d = y * w * 4;
    for (let x = 0; x < w; x++, s++, d += 4) {
      const a = angle ? angle[s] : 0;
      dst[d] = Math.round(cos[a] * 255);
      dst[d + 1] = Math.round(sin[a] * 255);
      dst[d + 2] = strength[s];
      dst[d + 3] = 255;
    }
  }
}

function flipFloat(src: Float32Array, w: number, h: number, dst: Float32Array): void {
  for (let y = 0; y < h; y++) dst.set(src.subarray((h - 1 - y) * w, (h - y) * w), y * w);
}

export interface Range {
  min: number;
  max: number;
  mean: number;
}

/** Min, max and mean of one channel of a u8 map, in 0..1. */
export function rangeU8(src: Uint8Array, channels = 1, channel = 0): Range {
  let min = 255;
  let max = 0;
  let sum = 0;
  for (let i = channel; i < src.length; i += channels) {
    const v = src[i];
    if (v < min) min = v;
    if (v > max) max = v;
    sum += v;
  }
  const n = Math.max(1, src.length / channels);
  return { min: min / 255, max: max / 255, mean: sum / n / 255 };
}

export function rangeF32(src: Float32Array): Range {
  let min = Infinity;
  let max = -Infinity;
  let sum = 0;
  for (let i = 0; i < src.length; i++) {
    const v = src[i];
    if (v < min) min = v;
    if (v > max) max = v;
    sum += v;
  }
  if (!Number.isFinite(min)) return { min: 0, max: 0, mean: 0 };
  return { min, max, mean: sum / src.length };
}


export class TexturePool {
  private readonly byName = new Map<string, DataTexture[]>();
  private wrap: Wrapping = RepeatWrapping;

  constructor(
    private readonly maxAnisotropy: number,
    private readonly floatLinear: boolean,
  ) {}

  /** An RGBA u8 texture `name` of size w x h, filled by `fill` (in place when it exists). */
  rgba(name: string, w: number, h: number, srgb: boolean, fill: (dst: Uint8Array) => void): DataTexture {
    const tex = this.get(name, w, h) ?? this.add(name, this.makeRgba(w, h, srgb));
    fill(tex.image.data as Uint8Array);
    tex.needsUpdate = true;
    return tex;
  }

  /** A single-channel float texture (for the vertex shader's displacement). */
  float(name: string, src: Float32Array, w: number, h: number): DataTexture {
    const tex = this.get(name, w, h) ?? this.add(name, this.makeFloat(w, h));
    flipFloat(src, w, h, tex.image.data as Float32Array);
    tex.needsUpdate = true;
    return tex;
  }

  /** Repeat the maps beyond [0, 1] (tileable maps, closed shapes) or clamp them to the edge
   * (a non-tileable map on an open sheet: no wrapped-around texels on its border). */
  setRepeat(on: boolean): void {
    const wrap = on ? RepeatWrapping : ClampToEdgeWrapping;
    if (wrap === this.wrap) return;
    this.wrap = wrap;
    for (const t of this.all()) {
      t.wrapS = t.wrapT = wrap;
      t.needsUpdate = true;
    }
  }

  /** Every live texture (to set the tiling repeat on all of them). */
  all(): Texture[] {
    return [...this.byName.values()].flat();
  }

  dispose(): void {
    for (const list of this.byName.values()) for (const t of list) t.dispose();
    this.byName.clear();
  }

  private get(name: string, w: number, h: number): DataTexture | undefined {
    const list = this.byName.get(name) ?? [];
    const i = list.findIndex((t) => t.image.width === w && t.image.height === h);
    if (i < 0) return undefined;
    const tex = list[i];
    list.splice(i, 1);
    list.unshift(tex); // most recently used first
    return tex;
  }

  private add(name: string, tex: DataTexture): DataTexture {
    const list = this.byName.get(name) ?? [];
    list.unshift(tex);
    while (list.length > 2) list.pop()?.dispose();
    this.byName.set(name, list);
    return tex;
  }

  private makeRgba(w: number, h: number, srgb: boolean): DataTexture {
    const tex = new DataTexture(new Uint8Array(w * h * 4), w, h, RGBAFormat, UnsignedByteType);
    tex.colorSpace = srgb ? SRGBColorSpace : NoColorSpace;
    tex.wrapS = tex.wrapT = this.wrap;
    tex.magFilter = LinearFilter;
    // The quick first pass (<= 256 px) skips mipmaps: building them on every update costs more
    // than the draw under software GL, and the full pass that follows has them.
    const mips = Math.max(w, h) > PREVIEW_SIZE;
    tex.minFilter = mips ? LinearMipmapLinearFilter : LinearFilter;
    tex.generateMipmaps = mips;
    tex.anisotropy = this.maxAnisotropy;
    tex.unpackAlignment = 4;
    return tex;
  }

  private makeFloat(w: number, h: number): DataTexture {
    const tex = new DataTexture(new Float32Array(w * h), w, h, RedFormat, FloatType);
    tex.wrapS = tex.wrapT = this.wrap;
    tex.magFilter = tex.minFilter = this.floatLinear ? LinearFilter : NearestFilter;
    tex.generateMipmaps = false;
    tex.unpackAlignment = 4;
    return tex;
  }
}
