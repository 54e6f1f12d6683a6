// Preview shapes, sized at the material's physical scale: `span` is the View's width in world
// units (metres when the program states unit_m), so a tile of the maps is that big on the mesh.
// Tessellation is enough for the height map's displacement (the normal map carries the fine
// relief) but light enough for SwiftShader, where tiny triangles cost more than their pixels.
import {
  Box3,
  BufferGeometry,
  Float32BufferAttribute,
  Group,
  LatheGeometry,
  Mesh,
  PlaneGeometry,
  Sphere,
  SphereGeometry,
  Vector2,
  Vector3,
  type Material,
} from "three";
import { mergeGeometries } from "three/addons/utils/BufferGeometryUtils.js";

export const SHAPES = ["plane", "sphere", "cube", "cloth", "ball"] as const;
export type ShapeName = (typeof SHAPES)[number];
export const SHAPE_LABELS: Record<ShapeName, string> = {
  plane: "Plane",
  sphere: "Sphere",
  cube: "Cube",
  cloth: "Cloth",
  ball: "Shader ball",
};

export interface Shape {
  object: Group;
  /** Bounding sphere, for the camera. */
  center: Vector3;
  radius: number;
  /** The texture repeat that keeps the maps at their physical size on this mesh. */
  repeat: [number, number];
  /** Default camera azimuth/elevation in degrees. */
  view: [number, number];
  /** The material must render both faces (open or single-sheet meshes). */
  doubleSided: boolean;
  /** The surface closes on itself (sphere, cube, ball): the maps must wrap around even when
   * they are not tileable, so both sides of a seam sample the same texels and do not crack. */
  closed: boolean;
  /** Each mesh's geometry at full and at reduced detail (a quarter of the vertices), for the
   * cheap frames drawn on software GL while something moves: there the vertex work of a
   * finely tessellated mesh costs more than its pixels. */
  lod: { mesh: Mesh; fine: BufferGeometry; coarse: BufferGeometry }[];
}

/** Build `name` for maps spanning `span` x `span * aspect` world units. */
export function buildShape(
  name: ShapeName,
  span: number,
  aspect: number,
  material: Material,
  neutral: Material,
): Shape {
  const shape = buildDetail(name, span, aspect, material, neutral, 1);
  const coarse = buildDetail(name, span, aspect, material, neutral, 0.5);
  const meshes = (s: Shape) => s.object.children.filter((o): o is Mesh => o instanceof Mesh);
  const low = meshes(coarse);
  shape.lod = meshes(shape).map((mesh, i) => ({ mesh, fine: mesh.geometry, coarse: low[i].geometry }));
  return shape;
}

/** Show each mesh of `shape` at full or reduced detail. */
export function setDetail(shape: Shape, coarse: boolean): void {
  for (const l of shape.lod) l.mesh.geometry = coarse ? l.coarse : l.fine;
}

function buildDetail(
  name: ShapeName,
  span: number,
  aspect: number,
  material: Material,
  neutral: Material,
  detail: number,
): Shape {
  const group = new Group();
  const seg = (n: number) => Math.max(4, Math.round(n * detail));
  const add = (g: BufferGeometry, m: Material = material) => group.add(new Mesh(g, m));
  let repeat: [number, number] = [1, 1];
  let view: [number, number] = [90, 28];
  let doubleSided = false;
  const closed = name === "sphere" || name === "cube" || name === "ball";
  if (name === "plane") {
    add(plane(span, span * aspect, seg(128)));
    view = [90, 42];
  } else if (name === "sphere") {
    // Circumference = two spans: the maps repeat twice around, once from pole to pole.
    add(withUv1(new SphereGeometry(span / Math.PI, seg(128), seg(64))));
    repeat = [2, 1];
    view = [90, 15];
  } else if (name === "cube") {
    add(cube(span, seg(48)));
    view = [60, 28];
  } else if (name === "cloth") {
    add(cloth(span, seg(128)));
    view = [90, 32];
    doubleSided = true;
  } else {
    const parts = shaderBall(span, detail);
    add(parts.shell);
    add(parts.core);
    add(parts.base, neutral);
    repeat = [2, 1];
    view = [90, 18];
    doubleSided = true;
  }
  const bounds = new Box3().setFromObject(group).getBoundingSphere(new Sphere());
  const center = bounds.center;
  const radius = bounds.radius;
  return { object: group, center, radius, repeat, view, doubleSided, closed, lod: [] };
}

export function disposeShape(shape: Shape): void {
  for (const l of shape.lod) {
    l.fine.dispose();
    l.coarse.dispose();
  }
}

/** three reads aoMap through `uv` (texture.channel 0) since r152; uv1 is kept for older paths. */
function withUv1(g: BufferGeometry): BufferGeometry {
  const uv = g.getAttribute("uv");
  if (uv) g.setAttribute("uv1", uv.clone());
  return g;
}

/** A horizontal plane facing +y; the top of the maps is away from the default camera. */
function plane(w: number, h: number, seg: number): BufferGeometry {
  const g = new PlaneGeometry(w, h, seg, Math.max(2, Math.round(seg * (h / w))));
  g.rotateX(-Math.PI / 2);
  return withUv1(g);
}

/** A cube of six subdivided faces, each showing the whole map. Normals on the edges and corners
 * point diagonally, so displacement moves both copies of an edge vertex the same way (with
 * tileable maps they also sample the same height): the edges do not crack open. */
function cube(side: number, seg: number): BufferGeometry {
  const h = side / 2;
  const faces: BufferGeometry[] = [];
  const turns: [number, number][] = [
    [0, 0], // front (+z)
    [0, Math.PI / 2], // right (+x)
    [0, Math.PI], // back
    [0, -Math.PI / 2], // left
    [-Math.PI / 2, 0], // top
    [Math.PI / 2, 0], // bottom
  ];
  for (const [rx, ry] of turns) {
    const f = new PlaneGeometry(side, side, seg, seg);
    f.translate(0, 0, h);
    if (rx) f.rotateX(rx);
    if (ry) f.rotateY(ry);
    faces.push(f);
  }
  const g = mergeGeometries(faces) ?? faces[0];
  const pos = g.getAttribute("position");
  const nor = g.getAttribute("normal");
  const eps = side * 1e-5;
  const n = new Vector3();
  for (let i = 0; i < pos.count; i++) {
    const x = pos.getX(i);
    const y = pos.getY(i);
    const z = pos.getZ(i);
    const ex = Math.abs(Math.abs(x) - h) < eps ? Math.sign(x) : 0;
    const ey = Math.abs(Math.abs(y) - h) < eps ? Math.sign(y) : 0;
    const ez = Math.abs(Math.abs(z) - h) < eps ? Math.sign(z) : 0;
    if (Math.abs(ex) + Math.abs(ey) + Math.abs(ez) >= 2) {
      n.set(ex, ey, ez).normalize();
      nor.setXYZ(i, n.x, n.y, n.z);
    }
  }
  for (const f of faces) f.dispose();
  return withUv1(g);
}

/** A square cloth draped over a round table: flat on top with a slight sag, bending over the
 * edge, then hanging in irregular folds whose depth takes up the extra fabric (a circle of
 * radius R with n folds of amplitude A is about 2 pi R (1 + (n A / R)^2 / 4) long); the corners
 * hang lowest. */
function cloth(span: number, seg: number): BufferGeometry {
  const g = new PlaneGeometry(span, span, seg, seg);
  const pos = g.getAttribute("position");
  const r0 = 0.22 * span; // table radius
  const b = 0.04 * span; // bend radius over the table's edge
  const arc = (b * Math.PI) / 2;
  const folds = 11;
  for (let i = 0; i < pos.count; i++) {
    const px = pos.getX(i);
    const pz = -pos.getY(i);
    const r = Math.hypot(px, pz);
    const theta = Math.atan2(pz, px);
    const s = Math.max(0, r - r0);
    let rho: number;
    let y: number;
    if (s < arc) {
      const a = s / b;
      rho = r0 + b * Math.sin(a);
      y = -b * (1 - Math.cos(a));
    } else {
      rho = r0 + b;
      y = -b - (s - arc);
    }
    if (r >= r0) {
      const excess = Math.max(0, (r0 + s) / rho - 1);
      const amp = ((2 * rho * Math.sqrt(excess)) / folds) * smooth(0, 0.12 * span, s);
      const vary = 0.75 + 0.25 * Math.sin(3 * theta + 1.7);
      const wave = Math.sin(folds * theta + 0.6 + 0.8 * Math.sin(2 * theta)) + 0.3 * Math.sin((2 * folds + 3) * theta + 2.1);
      rho += amp * vary * wave;
      y += 0.01 * span * Math.sin(folds * theta * 0.5 + 1.3) * smooth(0.1 * span, 0.3 * span, s);
    } else {
      y -= 0.006 * span * (1 - (r / r0) ** 2); // a little sag on the table top
    }
    const ux = r > 1e-9 ? px / r : 0;
    const uz = r > 1e-9 ? pz / r : 0;
    pos.setXYZ(i, ux * rho, y + 0.15 * span, uz * rho);
  }
  g.computeVertexNormals();
  return withUv1(g);
}

function smooth(e0: number, e1: number, x: number): number {
  const t = Math.min(1, Math.max(0, (x - e0) / (e1 - e0)));
  return t * t * (3 - 2 * t);
}

/** The classic material-preview ball: a sphere shell with a cut ring and an open wedge over an
 * inner core, on a neutral pedestal. UVs follow the sphere's (azimuth, latitude). */
function shaderBall(span: number, detail: number): { shell: BufferGeometry; core: BufferGeometry; base: BufferGeometry } {
  const R = 0.36 * span;
  const inner = 0.9 * R;
  const lat = (d: number) => (d * Math.PI) / 180;
  const onSphere = (r: number, deg: number) => new Vector2(r * Math.cos(lat(deg)), r * Math.sin(lat(deg)));
  const arcPts = (r: number, from: number, to: number, steps: number) =>
    Array.from({ length: steps + 1 }, (_, i) => onSphere(r, from + ((to - from) * i) / steps));
  // Lower shell, all round: from the neck up to the cut ring, then into the groove.
  const n = (k: number) => Math.max(6, Math.round(k * detail));
  const lower = [...arcPts(R, -76, 2, n(70)), onSphere(inner, 2), ...arcPts(inner, 2, 12, 6)];
  // Upper shell with a wedge cut out toward the camera, showing the core.
  const upper = [onSphere(inner, 12), ...arcPts(R, 12, 90, n(70))];
  const lowerG = latheWithSphereUv(lower, 0, Math.PI * 2, R, n(128));
  const upperG = latheWithSphereUv(upper, Math.PI * 0.2, Math.PI * 1.5, R, n(128));
  const shell = mergeGeometries([lowerG, upperG]) ?? lowerG;
  lowerG.dispose();
  upperG.dispose();
  const core = withUv1(new SphereGeometry(0.8 * R, n(96), n(48)));
  const neckY = R * Math.sin(lat(-76));
  const neckR = R * Math.cos(lat(-76));
  const foot = neckY - 0.16 * span;
  const base = new LatheGeometry(
    [
      new Vector2(0, foot),
      new Vector2(0.3 * span, foot),
      new Vector2(0.31 * span, foot + 0.01 * span),
      new Vector2(0.31 * span, foot + 0.035 * span),
      new Vector2(0.29 * span, foot + 0.045 * span),
      new Vector2(neckR * 1.15, foot + 0.07 * span),
      new Vector2(neckR * 1.05, neckY - 0.01 * span),
      new Vector2(neckR * 0.95, neckY + 0.005 * span),
    ],
    n(96),
  );
  return { shell: withUv1(shell), core, base };
}

function latheWithSphereUv(points: Vector2[], phiStart: number, phiLength: number, R: number, round: number): BufferGeometry {
  const segs = Math.max(8, Math.round((round * phiLength) / (Math.PI * 2)));
  const g = new LatheGeometry(points, segs, phiStart, phiLength);
  const uv = g.getAttribute("uv");
  const pos = g.getAttribute("position");
  const out = new Float32Array(uv.count * 2);
  for (let i = 0; i < uv.count; i++) {
    const u = (phiStart + uv.getX(i) * phiLength) / (Math.PI * 2);
    const y = Math.max(-1, Math.min(1, pos.getY(i) / R));
    out[2 * i] = u;
    out[2 * i + 1] = 0.5 + Math.asin(y) / Math.PI;
  }
  g.setAttribute("uv", new Float32BufferAttribute(out, 2));
  return g;
}
