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
/** How long after the last change a software-GL view keeps drawing cheap frames (ms). */
const BUSY_MS = 400;

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
  /** Full pixel ratio, and (software GL only) a cheaper one while things move. */
  private readonly ratio = Math.min(window.devicePixelRatio || 1, 2);
  private lowRes = false;
  private dragging = false;
  private busyUntil = 0;
  private refine: ReturnType<typeof setTimeout> | undefined;
  private readonly resizer: ResizeObserver;
  private disposed = false;

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

  /** Draw a frame soon (at the next animation frame); repeated calls coalesce. */
  requestRender(): void {
    if (this.pending || this.disposed) return;
    this.pending = true;
    requestAnimationFrame(() => this.draw());
  }

  /** The next frame drawn is the first to show maps `seq` (for window.matloomStudio);
   * `preview`: the quick first pass of an evaluation. */
  markShown(seq: number, preview = false): void {
    // A first pass is drawn cheaply (its full pass follows at once); a full pass always at
    // full resolution, so what a test or a screenshot sees after it is the final image.
    if (preview) this.busy();
    else if (!this.dragging) this.busyUntil = 0;
    this.shownSeq = seq;
    this.requestRender();
  }

  /** On software GL, draw at half resolution for a moment (orbiting, a first pass) and redraw
   * at full resolution once things are still: a SwiftShader frame costs about 3x less. */
  private busy(): void {
    if (this.software) this.busyUntil = performance.now() + BUSY_MS;
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

  private draw(): void {
    this.pending = false;
    if (this.disposed || this.canvas.clientWidth === 0 || this.canvas.clientHeight === 0) return;
    const moving = this.controls.update();
    const t0 = performance.now();
    const low = t0 < this.busyUntil;
    if (low !== this.lowRes) {
      this.lowRes = low;
      this.renderer.setPixelRatio(low ? this.ratio * 0.5 : this.ratio);
    }
    this.renderer.render(this.scene, this.camera);
    this.lastFrameMs = performance.now() - t0;
    frameDrawn(this.shownSeq);
    this.shownSeq = null;
    if (moving) this.requestRender();
    else if (low) {
      clearTimeout(this.refine);
      this.refine = setTimeout(() => this.requestRender(), this.busyUntil - performance.now() + 20);
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
