// The 3D view (issue 25, build item 4): the program's maps on a plane, sphere, cube, cloth or
// shader ball, under a bundled or dropped HDR environment, with orbit/zoom/pan and a small
// overlay for light, exposure, background and tiling. Draws only when something changed.
import type { Maps } from "../api";
import type { Ctx } from "../ctx";
import { buildOverlay, loadSettings, saveSettings, type ViewSettings } from "./controls";
import { Environments } from "./environment";
import { ensureHooks } from "./hooks";
import { MaterialBinder } from "./material";
import { ViewerScene } from "./scene";
import { buildShape, disposeShape, setDetail, type Shape } from "./shapes";
import { injectStyle } from "./style";
import { TexturePool } from "./textures";

export function mountViewer(el: HTMLElement, ctx: Ctx): void {
  injectStyle();
  ensureHooks();
  el.textContent = "";
  const root = document.createElement("div");
  root.className = "mlv-root";
  const canvas = document.createElement("canvas");
  canvas.dataset.testid = "viewer-canvas";
  canvas.tabIndex = 0;
  root.append(canvas);
  el.append(root);

  let view: ViewerScene;
  try {
    view = new ViewerScene(canvas);
  } catch (e) {
    const msg = document.createElement("div");
    msg.className = "mlv-fallback";
    msg.textContent = `The 3D view needs WebGL2, which this browser did not provide (${e instanceof Error ? e.message : e}).`;
    root.append(msg);
    return;
  }
  new Viewer(root, view, ctx);
}

class Viewer {
  private readonly pool: TexturePool;
  private readonly binder: MaterialBinder;
  private readonly envs: Environments;
  private readonly settings: ViewSettings = loadSettings();
  private readonly overlay;
  private shape: Shape | null = null;
  private span = 1;
  private aspect = 1;
  private tileable = false;

  constructor(
    private readonly root: HTMLElement,
    private readonly view: ViewerScene,
    ctx: Ctx,
  ) {
    this.pool = new TexturePool(view.maxAnisotropy(), view.floatLinear());
    this.binder = new MaterialBinder(this.pool);
    this.envs = new Environments(view.scene, () => view.requestRender());
    view.onCheap = (cheap) => {
      if (this.shape) setDetail(this.shape, cheap);
    };
    this.overlay = buildOverlay(this.settings, {
      changed: (s, what) => this.changed(s, what),
      reset: () => view.reset(),
      openFile: (f) => void this.openFile(f),
    });
    root.append(this.overlay.root);
    this.overlay.setTileable(false);
    this.setupDrop();

    const s = this.settings;
    view.setExposure(s.exposure);
    this.envs.setBackground(s.background, s.colour);
    void this.useEnv(s.env);
    this.rebuild(true);
    ctx.store.on("maps", (maps) => this.show(maps));
    if (view.software) ctx.presented = (seq) => view.presented(seq);
    // A slider step: frames stay cheap (software GL) until the drag pauses, then refine.
    ctx.store.on("text", ({ source }) => {
      if (source === "panel") view.edited();
    });
    ctx.store.on("status", ({ state }) => {
      if (state !== "busy") view.settle(); // no full pass is coming for a shown first pass
    });
    if (ctx.store.maps) this.show(ctx.store.maps);
  }

  /** New maps: bind them now, so that the next frame shows them. */
  private show(maps: Maps): void {
    const h = maps.header;
    const v = h.view;
    const unit = h.unit_m ?? v?.unit_m ?? 1;
    const w = v ? Math.abs(v.x2 - v.x1) : 0;
    const span = (w > 0 ? w : 1) * (unit > 0 ? unit : 1);
    const aspect = v && w > 0 ? Math.abs(v.y2 - v.y1) / w || 1 : h.height / h.width;
    this.binder.apply(maps);
    this.tileable = Boolean(h.tileable ?? v?.tileable);
    this.overlay.setTileable(this.tileable);
    if (span !== this.span || aspect !== this.aspect) {
      const ratio = span / this.span;
      this.span = span;
      this.aspect = aspect;
      this.rebuild(false);
      this.view.rescale(ratio);
      this.applyLight();
    } else {
      this.applyTiling();
    }
    this.overlay.message(this.binder.info.notes.join(" · "));
    this.view.markShown(h.seq, h.pass === "full");
  }

  private changed(s: ViewSettings, what: keyof ViewSettings): void {
    if (what === "shape") this.rebuild(true);
    else if (what === "env") void this.useEnv(s.env);
    else if (what === "background" || what === "colour") this.envs.setBackground(s.background, s.colour);
    else if (what === "exposure") this.view.setExposure(s.exposure);
    else if (what === "tiles") this.applyTiling();
    else if (what === "lightAz" || what === "lightEl" || what === "light") this.applyLight();
    if (!s.env.startsWith("file:")) saveSettings(s);
    else saveSettings({ ...s, env: "studio" });
    this.view.requestRender();
  }

  /** (Re)build the shape at the current span; `reframe` puts the camera at its default. */
  private rebuild(reframe: boolean): void {
    if (this.shape) {
      this.view.scene.remove(this.shape.object);
      disposeShape(this.shape);
    }
    const shape = buildShape(this.settings.shape, this.span, this.aspect, this.binder.material, this.binder.neutral);
    this.shape = shape;
    setDetail(shape, this.view.cheap);
    this.binder.setDoubleSided(shape.doubleSided);
    this.view.scene.add(shape.object);
    this.applyTiling();
    if (reframe) {
      this.view.frame(shape.center, shape.radius, shape.view[0], shape.view[1]);
      this.applyLight();
    }
    this.view.requestRender();
  }

  private applyTiling(): void {
    if (!this.shape) return;
    const tiles = this.tileable ? this.settings.tiles : 1;
    this.binder.setTiling(this.shape.repeat, tiles, this.tileable || this.shape.closed);
    this.view.requestRender();
  }

  private applyLight(): void {
    const s = this.settings;
    this.view.setLight(s.lightAz, s.lightEl, s.light);
  }

  private async useEnv(id: string): Promise<void> {
    try {
      await this.envs.use(id);
      this.overlay.message(this.binder.info.notes.join(" · "));
    } catch (e) {
      this.overlay.message(`environment: ${e instanceof Error ? e.message : String(e)}`, true);
    }
  }

  private async openFile(file: File): Promise<void> {
    try {
      const id = await this.envs.load(file);
      this.overlay.addEnvironment(id, file.name);
      this.settings.env = id;
      await this.useEnv(id);
    } catch (e) {
      this.overlay.selectEnvironment(this.settings.env);
      this.overlay.message(e instanceof Error ? e.message : String(e), true);
    }
  }

  private setupDrop(): void {
    const root = this.root;
    const hasFiles = (e: DragEvent) => Boolean(e.dataTransfer?.types.includes("Files"));
    root.addEventListener("dragover", (e) => {
      if (!hasFiles(e)) return;
      e.preventDefault();
      if (e.dataTransfer) e.dataTransfer.dropEffect = "copy";
      root.classList.add("mlv-drop");
    });
    root.addEventListener("dragleave", (e) => {
      if (e.target === root || !root.contains(e.relatedTarget as Node | null)) root.classList.remove("mlv-drop");
    });
    root.addEventListener("drop", (e) => {
      root.classList.remove("mlv-drop");
      const file = e.dataTransfer?.files[0];
      if (!file) return;
      e.preventDefault();
      void this.openFile(file);
    });
  }
}
