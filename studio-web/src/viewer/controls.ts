// The 3D view's small overlay: shape, environment, background, exposure, key light, tiling and
// camera reset. Settings are remembered in localStorage between visits.
import { BUNDLED, type Background } from "./environment";
import { SHAPES, SHAPE_LABELS, type ShapeName } from "./shapes";

export interface ViewSettings {
  shape: ShapeName;
  env: string;
  background: Background;
  colour: string;
  exposure: number;
  lightAz: number;
  lightEl: number;
  light: number;
  tiles: number;
  /** The light/environment panel is open. */
  panel: boolean;
}

export const DEFAULTS: ViewSettings = {
  shape: "plane",
  env: "studio",
  background: "blur",
  colour: "#2b2d31",
  exposure: 1,
  lightAz: 140,
  lightEl: 40,
  light: 1.5,
  tiles: 1,
  panel: true,
};

const STORAGE_KEY = "matloom.viewer";

export function loadSettings(): ViewSettings {
  try {
    const raw = JSON.parse(localStorage.getItem(STORAGE_KEY) ?? "{}") as Partial<ViewSettings>;
    const s = { ...DEFAULTS, ...raw };
    if (!SHAPES.includes(s.shape)) s.shape = DEFAULTS.shape;
    if (!BUNDLED.some((e) => e.id === s.env)) s.env = DEFAULTS.env; // dropped files are not kept
    return s;
  } catch {
    return { ...DEFAULTS };
  }
}

export function saveSettings(s: ViewSettings): void {
  try {
    localStorage.setItem(STORAGE_KEY, JSON.stringify(s));
  } catch {
    /* storage unavailable: settings last for the page only */
  }
}

export interface Overlay {
  root: HTMLElement;
  /** Show a one-line message (an error or what the material cannot show); "" clears it. */
  message(text: string, error?: boolean): void;
  /** Add a dropped environment to the choices and select it. */
  addEnvironment(id: string, label: string): void;
  /** Enable the tiling control (tileable maps only). */
  setTileable(on: boolean): void;
  /** Select an environment in the list without firing change (e.g. after a failed load). */
  selectEnvironment(id: string): void;
}

export interface OverlayActions {
  changed(s: ViewSettings, what: keyof ViewSettings): void;
  reset(): void;
  openFile(file: File): void;
}

function el<K extends keyof HTMLElementTagNameMap>(tag: K, attrs: Record<string, string> = {}, text = ""): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text) e.textContent = text;
  return e;
}

export function buildOverlay(s: ViewSettings, act: OverlayActions): Overlay {
  const root = el("div", { class: "mlv-overlay" });
  const bar = el("div", { class: "mlv-bar" });
  const shape = select("viewer-shape", SHAPES.map((id) => [id, SHAPE_LABELS[id]]), s.shape);
  const reset = el("button", { type: "button", "data-testid": "viewer-reset", title: "Reset the camera" }, "Reset view");
  const more = el("button", { type: "button", class: "mlv-more", "data-testid": "viewer-settings", title: "Light and environment", "aria-expanded": String(s.panel) }, "⚙");
  bar.append(shape, reset, more);

  const panel = el("div", { class: "mlv-panel" });
  panel.hidden = !s.panel;
  const env = select("viewer-env", BUNDLED.map((e) => [e.id, e.label]), s.env);
  const open = el("option", { value: "__open" }, "Open .hdr/.exr…");
  env.append(open);
  const file = el("input", { type: "file", accept: ".hdr,.exr,.pic", hidden: "" });
  const bg = select("viewer-background", [["env", "Environment"], ["blur", "Blurred"], ["solid", "Colour"]], s.background);
  const colour = el("input", { type: "color", "data-testid": "viewer-bg-colour", value: s.colour, title: "Background colour" });
  const exposure = range("viewer-exposure", -3, 3, 0.05, Math.log2(s.exposure));
  const az = range("viewer-light-az", 0, 360, 1, s.lightAz);
  const elev = range("viewer-light-el", 0, 90, 1, s.lightEl);
  const light = range("viewer-light", 0, 6, 0.05, s.light);
  const tiles = select("viewer-tiles", [["1", "1×1"], ["2", "2×2"], ["3", "3×3"], ["4", "4×4"]], String(s.tiles));
  panel.append(
    row("Environment", env, file),
    row("Background", bg, colour),
    row("Exposure", exposure),
    row("Light azimuth", az),
    row("Light elevation", elev),
    row("Light", light),
    row("Tiles", tiles),
  );
  const note = el("div", { class: "mlv-note", "data-testid": "viewer-note" });
  root.append(bar, panel, note);

  const fire = (what: keyof ViewSettings) => act.changed(s, what);
  shape.addEventListener("change", () => {
    s.shape = shape.value as ShapeName;
    fire("shape");
  });
  reset.addEventListener("click", () => act.reset());
  more.addEventListener("click", () => {
    panel.hidden = !panel.hidden;
    s.panel = !panel.hidden;
    more.setAttribute("aria-expanded", String(s.panel));
    fire("panel");
  });
  env.addEventListener("change", () => {
    if (env.value === "__open") {
      env.value = s.env;
      file.click();
      return;
    }
    s.env = env.value;
    fire("env");
  });
  file.addEventListener("change", () => {
    const f = file.files?.[0];
    if (f) act.openFile(f);
    file.value = "";
  });
  bg.addEventListener("change", () => {
    s.background = bg.value as Background;
    fire("background");
  });
  colour.addEventListener("input", () => {
    s.colour = colour.value;
    s.background = "solid";
    bg.value = "solid";
    fire("colour");
  });
  exposure.addEventListener("input", () => {
    s.exposure = 2 ** Number(exposure.value);
    fire("exposure");
  });
  for (const [input, key] of [[az, "lightAz"], [elev, "lightEl"], [light, "light"]] as const) {
    input.addEventListener("input", () => {
      s[key] = Number(input.value);
      fire(key);
    });
  }
  tiles.addEventListener("change", () => {
    s.tiles = Number(tiles.value);
    fire("tiles");
  });

  return {
    root,
    message(text, error = false) {
      note.textContent = text;
      note.classList.toggle("mlv-error", error);
    },
    addEnvironment(id, label) {
      if (![...env.options].some((o) => o.value === id)) env.insertBefore(el("option", { value: id }, label), open);
      env.value = id;
    },
    setTileable(on) {
      tiles.disabled = !on;
      tiles.title = on ? "Repeat the maps on the mesh" : "The program is not tileable (View(..., tileable=True))";
    },
    selectEnvironment(id) {
      env.value = id;
    },
  };
}

function select(testid: string, options: [string, string][], value: string): HTMLSelectElement {
  const s = el("select", { "data-testid": testid });
  for (const [v, label] of options) s.append(el("option", { value: v }, label));
  s.value = value;
  return s;
}

function range(testid: string, min: number, max: number, step: number, value: number): HTMLInputElement {
  const r = el("input", { type: "range", "data-testid": testid, min: String(min), max: String(max), step: String(step) });
  r.value = String(value);
  return r;
}

function row(label: string, ...inputs: HTMLElement[]): HTMLElement {
  const r = el("label", { class: "mlv-row" });
  r.append(el("span", {}, label), ...inputs);
  return r;
}
