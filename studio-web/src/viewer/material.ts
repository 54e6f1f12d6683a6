// three's MeshPhysicalMaterial from the program's maps: every map is used, spatially varying
// wherever three has a map for it, else as the map's mean (docs/studio-api.md, wire format).
import { DoubleSide, FrontSide, MeshPhysicalMaterial, type Texture } from "three";
import type { Maps } from "../api";
import { packAnisotropy, packRgba, rangeF32, rangeU8, TexturePool, type Range } from "./textures";

/** MatLoom's lit preview coats with roughness 0.05 and sheens with roughness 0.5. */
const COAT_ROUGHNESS = 0.05;
const SHEEN_ROUGHNESS = 0.5;

/** What the material shows of the maps (for the overlay's one-line summary). */
export interface MaterialInfo {
  /** Maps given to three as textures. */
  textures: string[];
  /** Notes on what three cannot show as a map (e.g. "ior 1.53 (mean)"). */
  notes: string[];
}

export class MaterialBinder {
  readonly material = new MeshPhysicalMaterial({ color: 0x808080, roughness: 0.5 });
  /** The neutral grey of a shader ball's pedestal. */
  readonly neutral = new MeshPhysicalMaterial({ color: 0x3a3a3a, roughness: 0.55 });
  info: MaterialInfo = { textures: [], notes: [] };
  private key = "";
  private height: Range | null = null;
  private unit = 1;
  private tiles = 1;
  private repeat: [number, number] = [1, 1];

  constructor(private readonly pool: TexturePool) {}

  /** Bind the decoded maps (textures reused in place when the size is unchanged). */
  apply(maps: Maps): void {
    const { width: w, height: h } = maps.header;
    const m = this.material;
    const u8 = maps.u8;
    const ch = (name: string) => maps.channels[name] ?? 1;
    const rgba = (name: string, srgb: boolean) =>
      this.pool.rgba(name, w, h, srgb, (d) => packRgba(u8[name], ch(name), w, h, d));
    const notes: string[] = [];

    m.map = u8.basecolor ? rgba("basecolor", true) : null;
    m.normalMap = u8.normal ? rgba("normal", false) : null;
    const orm = u8.orm ? rgba("orm", false) : null;
    m.aoMap = m.roughnessMap = m.metalnessMap = orm; // AO = R, roughness = G, metallic = B
    m.roughness = orm ? 1 : 0.5;
    m.metalness = orm ? 1 : 0;

    // The server says how strong the emission is (0: nothing glows); else look at the map.
    const strength = maps.header.emissive_scale ?? 1;
    const lit = maps.header.emissive_scale !== undefined || (u8.emissive !== undefined && rangeU8(u8.emissive).max > 0);
    const glow = u8.emissive !== undefined && strength > 0 && lit;
    m.emissiveMap = glow ? rgba("emissive", true) : null;
    m.emissive.setScalar(glow ? 1 : 0);
    m.emissiveIntensity = glow ? strength : 1;

    const coat = this.scalarOrMap("coat", u8.coat, w, h);
    m.clearcoat = coat.value;
    m.clearcoatMap = coat.map;
    m.clearcoatRoughness = COAT_ROUGHNESS;

    const sheen = this.scalarOrMap("sheen", u8.sheen, w, h);
    m.sheen = sheen.value;
    m.sheenColorMap = sheen.map; // grey weight: sheen colour white x map
    m.sheenColor.setScalar(1);
    m.sheenRoughness = SHEEN_ROUGHNESS;

    const trans = this.scalarOrMap("transmission", u8.transmission, w, h);
    m.transmission = trans.value;
    m.transmissionMap = trans.map;
    m.thickness = 0;

    this.bindAnisotropy(maps, w, h);

    const ior = maps.f32.ior ? rangeF32(maps.f32.ior) : null;
    m.ior = Math.min(2.333, Math.max(1, ior ? ior.mean : 1.5));
    if (ior && ior.max - ior.min > 1e-4) notes.push(`ior ${m.ior.toFixed(2)} (mean; three has no IOR map)`);

    const alpha = u8.alpha ? rangeU8(u8.alpha) : null;
    const cut = alpha !== null && alpha.min < 1;
    const alphaVaries = alpha !== null && alpha.max - alpha.min > 0.5 / 255;
    m.alphaMap = alphaVaries ? this.pool.rgba("alpha", w, h, false, (d) => packRgba(u8.alpha, 1, w, h, d)) : null;
    m.opacity = alpha && !alphaVaries ? alpha.mean : 1;
    m.transparent = cut;

    if (u8.subsurface && rangeU8(u8.subsurface).max > 0) notes.push("subsurface not shown (three has none)");

    const hgt = maps.f32.height;
    const hr = maps.header.height_range;
    this.height = hgt ? (hr ? { min: hr[0], max: hr[1], mean: 0.5 * (hr[0] + hr[1]) } : rangeF32(hgt)) : null;
    const relief = this.height !== null && this.height.max - this.height.min > 1e-9;
    m.displacementMap = relief && hgt ? this.pool.float("height", hgt, w, h) : null;
    if (!relief) this.height = null;
    this.unit = maps.header.unit_m ?? maps.header.view?.unit_m ?? 1;
    this.updateTransforms();

    const textures = Object.entries({
      basecolor: m.map,
      normal: m.normalMap,
      orm,
      emissive: m.emissiveMap,
      coat: m.clearcoatMap,
      sheen: m.sheenColorMap,
      transmission: m.transmissionMap,
      anisotropy: m.anisotropyMap,
      alpha: m.alphaMap,
      height: m.displacementMap,
    })
      .filter(([, t]) => t !== null)
      .map(([name]) => name);
    this.info = { textures, notes };
    const key = `${textures.join(",")}|${m.transparent}`;
    if (key !== this.key) {
      this.key = key;
      m.needsUpdate = true;
    }
  }

  /** The repeat that keeps the maps physical on the shape, times the user's tile count. */
  setTiling(repeat: [number, number], tiles: number, wrap: boolean): void {
    this.repeat = repeat;
    this.tiles = Math.max(1, tiles);
    this.pool.setRepeat(wrap);
    this.updateTransforms();
  }

  setDoubleSided(on: boolean): void {
    const side = on ? DoubleSide : FrontSide;
    if (this.material.side !== side) {
      this.material.side = side;
      this.material.needsUpdate = true;
    }
  }

  dispose(): void {
    this.material.dispose();
    this.neutral.dispose();
  }

  private updateTransforms(): void {
    const [rx, ry] = this.repeat;
    for (const t of this.pool.all()) t.repeat.set(rx * this.tiles, ry * this.tiles);
    // Height is in coordinate units: x unit_m for metres; a mesh showing `tiles` tiles is that
    // many times larger than the maps, so the relief shrinks with it.
    const scale = this.unit / this.tiles;
    const m = this.material;
    m.displacementScale = this.height ? scale : 0;
    m.displacementBias = this.height ? -0.5 * (this.height.min + this.height.max) * scale : 0;
  }

  /** A scalar when the map is uniform (cheaper shader), else the map with weight 1. */
  private scalarOrMap(name: string, src: Uint8Array | undefined, w: number, h: number): { value: number; map: Texture | null } {
    if (!src) return { value: 0, map: null };
    const r = rangeU8(src);
    if (r.max - r.min <= 0.5 / 255) return { value: r.mean, map: null };
    return { value: 1, map: this.pool.rgba(name, w, h, false, (d) => packRgba(src, 1, w, h, d)) };
  }

  private bindAnisotropy(maps: Maps, w: number, h: number): void {
    const m = this.material;
    const strength = maps.u8.anisotropy;
    const angle = maps.u8.anisotropy_angle;
    const s = strength ? rangeU8(strength) : null;
    if (!strength || !s || s.max === 0) {
      m.anisotropy = 0;
      m.anisotropyMap = null;
      return;
    }
    const a = angle ? rangeU8(angle) : { min: 0, max: 0, mean: 0 };
    if (s.max - s.min <= 0.5 / 255 && a.max - a.min <= 0.5 / 255) {
      m.anisotropy = s.mean;
      m.anisotropyRotation = ((a.mean * 180 + 90) * Math.PI) / 180; // highlight across the lines
      m.anisotropyMap = null;
      return;
    }
    m.anisotropy = 1;
    m.anisotropyRotation = 0;
    m.anisotropyMap = this.pool.rgba("anisotropy", w, h, false, (d) => packAnisotropy(strength, angle, w, h, d));
  }
}
