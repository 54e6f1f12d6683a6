// The three.js scene of the 3D view: WebGL2 renderer, camera, orbit controls, the key light, and
// on-demand rendering (a frame is drawn only when something changed or the controls move).
import {
  DirectionalLight,
  NeutralToneMapping,
  PerspectiveCamera,
  Scene,
  SRGBColorSpace,
  Vector3,
  WebGLRenderer,
} from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { frameDrawn } from "./hooks";

const FOV = 35;
/** How long after an orbit a software-GL view keeps drawing cheap frames (ms). */
const BUSY_MS = 400;
/** How long after the last program edit (a slider step) it does, before refining (ms). */
const EDIT_IDLE_MS = 250;
/** Pixels of a cheap frame on software GL (about 220 x 220): SwiftShader's time grows with the
 * pixels shaded, and this keeps a physical-material frame near 40 ms on two cores. */
const CHEAP_PIXELS = 48_000;

export class ViewerScene {
  readonly renderer: WebGLRenderer;
  readonly scene = new Scene();
  readonly camera = new PerspectiveCamera(FOV, 1, 0.01, 100);
  readonly controls: OrbitControls;
  readonly light = new DirectionalLight(0xffffff, 1);
  /** WebGL runs on a software rasteriser (SwiftShader, llvmpipe). */
  readonly software: boolean;
  /** The last frame's draw time in ms (render call only). */
  lastFrameMs = 0;
  private pending = false;
  private shownSeq: number | null = null;
  /** The maps on the material now: their seq, and whether they are a full pass. */
  private boundSeq = 0;
  private boundFull = false;
  private refinedSeq = 0;
  /** Full pixel ratio, and (software GL only) a cheaper one while things move. */
  private readonly ratio = Math.min(window.devicePixelRatio || 1, 2);
  private drawnRatio = 0;
  /** The last frame was a cheap one. */
  cheap = false;
  /** Called before a frame when it switches between cheap and full (reduced mesh detail). */
  onCheap: ((cheap: boolean) => void) | null = null;
  private dragging = false;
  private busyUntil = 0;
  private refine: ReturnType<typeof setTimeout> | undefined;
  private readonly resizer: ResizeObserver;
  private disposed = false;
  /** Who waits for the frame showing maps `seq` to be presented (see `presented`). */
  private waiters: { seq: number; resolve: () => void }[] = [];

  constructor(readonly canvas: HTMLCanvasElement) {
    this.software = isSoftwareGl();
    // A software rasteriser (SwiftShader on headless test machines) pays for every sample:
    // no MSAA and no anisotropic filtering there.
    this.renderer = new WebGLRenderer({ canvas, antialias: !this.software, powerPreference: "high-performance" });
    this.renderer.outputColorSpace = SRGBColorSpace;
    this.renderer.toneMapping = NeutralToneMapping;
    this.renderer.setPixelRatio(this.ratio);
    this.scene.add(this.light, this.light.target);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.enableDamping = true;
    this.controls.dampingFactor = 0.2;
    this.controls.screenSpacePanning = true;
    this.controls.addEventListener("start", () => (this.dragging = true));
    this.controls.addEventListener("end", () => {
      this.dragging = false;
      this.busy(); // the damped glide after a release
    });
    this.controls.addEventListener("change", () => {
      if (this.dragging) this.busy();
      this.requestRender();
    });
    this.resizer = new ResizeObserver(() => this.resize());
    this.resizer.observe(canvas.parentElement ?? canvas);
    this.resize();
  }

  /** Whether linear filtering of float textures is available (for the height map). */
  floatLinear(): boolean {
    return this.renderer.extensions.has("OES_texture_float_linear");
  }

  maxAnisotropy(): number {
    return this.software ? 1 : Math.min(4, this.renderer.capabilities.getMaxAnisotropy());
  }

  /** Resolves once a frame showing maps `seq` (or newer) has been presented: at the animation
   * frame after its draw. At once when the canvas is hidden (nothing will draw it). */
  presented(seq: number): Promise<void> {
    if (this.disposed || this.canvas.clientWidth === 0 || this.canvas.clientHeight === 0) return Promise.resolve();
    return new Promise((resolve) => this.waiters.push({ seq, resolve }));
  }

  /** Release the waiters for maps up to `seq` (all of them when `seq` is Infinity). */
  private release(seq: number): void {
    const ready = this.waiters.filter((w) => w.seq <= seq);
    if (!ready.length) return;
    this.waiters = this.waiters.filter((w) => w.seq > seq);
    for (const w of ready) w.resolve();
  }

  /** Draw a frame soon (at the next animation frame); repeated calls coalesce. */
  requestRender(): void {
    if (this.pending || this.disposed) return;
    this.pending = true;
    requestAnimationFrame(() => this.draw());
  }

  /** The next frame drawn is the first to show maps `seq`; `full`: they are the full-size pass.
   * On software GL a first pass is drawn cheaply and not refined (its full pass follows), and a
   * full pass too while edits go on; the full pass is then refined once they pause. */
  markShown(seq: number, full: boolean): void {
    this.shownSeq = seq;
    this.boundSeq = seq;
    this.boundFull = full;
    this.requestRender();
  }

  /** The program was just edited (a slider step): keep frames cheap until edits pause. */
  edited(): void {
    this.busy(EDIT_IDLE_MS);
  }

  /** Nothing more is coming for the shown maps (the evaluation failed or was superseded):
   * refine what is shown. */
  settle(): void {
    if (this.boundFull) return;
    this.boundFull = true;
    this.requestRender();
  }

  /** On software GL, draw cheap frames (about CHEAP_PIXELS) for `ms` (orbiting, a drag), then
   * one full-resolution frame once things are still. A GPU draws every frame at full size. */
  private busy(ms = BUSY_MS): void {
    if (this.software) this.busyUntil = Math.max(this.busyUntil, performance.now() + ms);
  }

  /** Place the camera around `center` at `radius` (bounding sphere), azimuth/elevation in
   * degrees (azimuth 90 = on +z), and make that the reset position. */
  frame(center: Vector3, radius: number, az: number, el: number): void {
    const half = (Math.min(FOV, this.horizontalFov()) / 2) * (Math.PI / 180);
    const dist = (radius / Math.sin(half)) * 1.15;
    this.camera.near = dist / 100;
    this.camera.far = dist * 100;
    this.camera.updateProjectionMatrix();
    this.camera.position.copy(center).add(direction(az, el).multiplyScalar(dist));
    this.controls.target.copy(center);
    this.controls.minDistance = radius * 0.25;
    this.controls.maxDistance = dist * 8;
    this.controls.update();
    this.controls.saveState();
    this.requestRender();
  }

  /** Scale the camera and target about the origin (the object was resized by `ratio`). */
  rescale(ratio: number): void {
    this.camera.position.multiplyScalar(ratio);
    this.controls.target.multiplyScalar(ratio);
    this.camera.near *= ratio;
    this.camera.far *= ratio;
    this.camera.updateProjectionMatrix();
    this.controls.minDistance *= ratio;
    this.controls.maxDistance *= ratio;
    this.controls.position0.multiplyScalar(ratio);
    this.controls.target0.multiplyScalar(ratio);
    this.controls.update();
    this.requestRender();
  }

  reset(): void {
    this.controls.reset();
    this.requestRender();
  }

  /** Point the key light from azimuth/elevation (degrees), at `intensity`. */
  setLight(az: number, el: number, intensity: number): void {
    this.light.position.copy(this.controls.target).add(direction(az, el).multiplyScalar(10));
    this.light.target.position.copy(this.controls.target);
    this.light.intensity = intensity;
    this.light.visible = intensity > 0;
    this.requestRender();
  }

  setExposure(exposure: number): void {
    this.renderer.toneMappingExposure = exposure;
    this.requestRender();
  }

  dispose(): void {
    this.disposed = true;
    this.release(Infinity);
    clearTimeout(this.refine);
    this.resizer.disconnect();
    this.controls.dispose();
    this.renderer.dispose();
  }

  private horizontalFov(): number {
    const v = (FOV / 2) * (Math.PI / 180);
    return ((2 * Math.atan(Math.tan(v) * this.camera.aspect)) * 180) / Math.PI;
  }

  private resize(): void {
    const box = (this.canvas.parentElement ?? this.canvas).getBoundingClientRect();
    const w = Math.max(1, Math.floor(box.width));
    const h = Math.max(1, Math.floor(box.height));
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  /** The pixel ratio of a cheap frame: about CHEAP_PIXELS, at most half the full ratio. */
  private cheapRatio(): number {
    const area = Math.max(1, this.canvas.clientWidth * this.canvas.clientHeight);
    return Math.min(this.ratio * 0.5, Math.max(0.15, Math.sqrt(CHEAP_PIXELS / area)));
  }

  private draw(): void {
    this.pending = false;
    if (this.disposed || this.canvas.clientWidth === 0 || this.canvas.clientHeight === 0) {
      this.release(Infinity);
      return;
    }
    const moving = this.controls.update();
    const t0 = performance.now();
    const low = this.software && (t0 < this.busyUntil || !this.boundFull);
    const ratio = low ? this.cheapRatio() : this.ratio;
    if (low !== this.cheap) {
      this.cheap = low;
      this.onCheap?.(low);
    }
    if (ratio !== this.drawnRatio) {
      this.drawnRatio = ratio;
      this.renderer.setPixelRatio(ratio);
    }
    this.renderer.render(this.scene, this.camera);
    this.lastFrameMs = performance.now() - t0;
    const refined = !low && this.boundFull && this.boundSeq > this.refinedSeq;
    if (refined) this.refinedSeq = this.boundSeq;
    frameDrawn(this.shownSeq, refined ? this.boundSeq : null, ratio);
    if (this.shownSeq !== null && this.waiters.length) {
      const drawn = this.shownSeq;
      requestAnimationFrame(() => this.release(drawn)); // presented by the next frame
    }
    this.shownSeq = null;
    clearTimeout(this.refine);
    if (moving) this.requestRender();
    else if (low && this.boundFull) {
      // Refine once things are still (a first pass waits for its full pass instead).
      this.refine = setTimeout(() => this.requestRender(), Math.max(0, this.busyUntil - performance.now()) + 20);
    }
  }
}

/** Whether WebGL2 is rendered in software (probed on a throwaway context). */
function isSoftwareGl(): boolean {
  try {
    const gl = document.createElement("canvas").getContext("webgl2");
    if (!gl) return false;
    const info = gl.getExtension("WEBGL_debug_renderer_info");
    const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
    gl.getExtension("WEBGL_lose_context")?.loseContext();
    return /swiftshader|llvmpipe|softpipe|software|basic render/i.test(name);
  } catch {
    return false;
  }
}

/** Unit vector from azimuth/elevation in degrees (azimuth 0 = +x, 90 = +z; three's equirect). */
export function direction(az: number, el: number): Vector3 {
  const a = (az * Math.PI) / 180;
  const e = (el * Math.PI) / 180;
  return new Vector3(Math.cos(e) * Math.cos(a), Math.sin(e), Math.cos(e) * Math.sin(a));
}
