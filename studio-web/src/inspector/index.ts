// The inspector tab: any channel in 2D (zoom, pan), the value under the cursor, a histogram,
// and a 3x3 tiling view with the seam ratios. It evaluates the current text on its own stream
// ("inspector") so it can ask for the exact float values of the channel it shows.
import { ApiError, type Maps } from "../api";
import type { Ctx } from "../ctx";
import { CHANNELS, channel, hasFloats, plane, toImage, type Plane } from "./channels";
import { errorText, field, h, isShown, nextSeq, onShown, select } from "./dom";
import { drawHistogram, statsText } from "./histogram";
import { PanZoom } from "./panzoom";
import { describe } from "./readout";
import { inspectorStyle } from "./style";
import { drawTiling, seamReport } from "./tiling";

const SIZES = ["256", "512", "1024"];

export function mountInspector(el: HTMLElement, ctx: Ctx): void {
  inspectorStyle();
  const chan = select(
    CHANNELS.map((c) => [c.id, c.label]),
    "basecolor",
    { "data-testid": "inspector-channel", title: "channel" },
  );
  const size = select(
    SIZES.map((s) => [s, `${s}²`]),
    "512",
    { "data-testid": "inspector-size", title: "evaluation size" },
  );
  const frame = h("input", { type: "checkbox", checked: true, "data-testid": "tiling-frame" });
  const status = h("span", { class: "ins-dim", "data-testid": "inspector-status" });
  const canvas = h("canvas", { class: "ins-canvas", width: 560, height: 560, "data-testid": "inspector-canvas" });
  const readout = h("div", { class: "ins-readout", "data-testid": "inspector-value" });
  const hist = h("canvas", { class: "ins-hist", width: 512, height: 72, "data-testid": "inspector-histogram" });
  const stats = h("div", { class: "ins-dim" });
  const tiling = h("canvas", { class: "ins-tiling", width: 480, height: 480, "data-testid": "tiling-canvas" });
  const seams = h("div", { "data-testid": "tiling-seams" });
  const root = h(
    "div",
    { class: "ins-root" },
    h("div", { class: "ins-bar" }, field("channel", chan), field("size", size), status),
    canvas,
    readout,
    h("h3", { text: "histogram" }),
    hist,
    stats,
    h("h3", { text: "tiling 3×3" }),
    h("div", { class: "ins-bar" }, field("frame the centre tile (gap)", frame), h("span", { class: "ins-dim", text: "untick to see the tiles touch" })),
    tiling,
    seams,
  );
  el.replaceChildren(root);

  const g = canvas.getContext("2d");
  const offscreen = document.createElement("canvas");
  const view = new PanZoom(canvas, () => {
    paint();
    showReadout();
  });
  let maps: Maps | null = null;
  let shown: Plane | null = null;
  let seq = 0;
  let fetchedKey = "";
  let last: [number, number] | null = null;

  function paint(): void {
    if (!g || !shown) return;
    view.draw(g, offscreen);
  }

  function showReadout(): void {
    if (!shown || !maps) {
      readout.textContent = "";
      return;
    }
    if (!last) {
      const zoom = view.scale / view.fitScale();
      readout.textContent = `move over the image for the value under the cursor\nwheel: zoom · drag: pan · double-click: fit${zoom > 1.01 ? ` · zoom ×${zoom.toFixed(1)}` : ""}`;
      return;
    }
    const z = view.scale / view.fitScale();
    const zoom = z > 1.01 ? ` · zoom ×${z.toFixed(1)}` : "";
    const scale = maps.header.emissive_scale ?? 0;
    const lines = describe(shown, last[0], last[1], maps.header.unit_m, scale);
    lines[0] += zoom;
    readout.textContent = lines.join("\n");
  }

  function render(): void {
    if (!maps) return;
    shown = plane(maps, channel(chan.value));
    offscreen.width = shown.width;
    offscreen.height = shown.height;
    offscreen.getContext("2d")?.putImageData(toImage(shown), 0, 0);
    view.setImage(shown.width, shown.height);
    paint();
    showReadout();
    const hs = drawHistogram(hist, shown);
    stats.textContent = shown.present ? statsText(hs, shown.comps >= 3) : "the program does not write this channel";
    drawTiling(tiling, offscreen, shown.width, shown.height, frame.checked);
    seams.replaceChildren(seamReport(maps.header));
  }

  function request(): { key: string; channels: string[] } {
    const def = channel(chan.value);
    const channels = def.raw ? [def.raw] : [];
    const { text, hidden, solo } = ctx.store;
    return { key: JSON.stringify([text, size.value, channels, hidden, solo]), channels };
  }

  async function refresh(): Promise<void> {
    if (!isShown(root) || !ctx.store.text.trim()) return;
    const { key, channels } = request();
    if (key === fetchedKey) return;
    const my = (seq = nextSeq());
    status.textContent = "evaluating…";
    status.className = "ins-dim";
    try {
      const { text, hidden, solo } = ctx.store;
      const m = await ctx.api.maps({ text, size: Number(size.value), stream: "inspector", seq: my, hidden, solo, channels });
      if (my !== seq) return;
      maps = m;
      fetchedKey = key;
      const layers = hidden.length || solo !== null ? " · layers hidden/solo as in the panel" : "";
      status.textContent = `${m.header.width}×${m.header.height} · ${Math.round(m.header.eval_ms)} ms${layers}`;
      render();
    } catch (err) {
      if (my !== seq || (err instanceof ApiError && err.status === 409)) return;
      status.textContent = errorText(err);
      status.className = "ins-err";
    }
  }

  chan.addEventListener("change", () => {
    // At once from what is here (the 8-bit map), then the exact floats when they arrive.
    const def = channel(chan.value);
    if (maps && (hasFloats(maps, def) || def.u8)) render();
    else readout.textContent = "evaluating the exact values…";
    void refresh();
  });
  size.addEventListener("change", () => void refresh());
  frame.addEventListener("change", () => render());
  canvas.addEventListener("pointermove", (e) => {
    last = view.texel(e);
    showReadout();
  });
  canvas.addEventListener("pointerleave", () => {
    last = null;
    showReadout();
  });
  ctx.store.on("maps", () => void refresh());
  ctx.store.on("layers", () => void refresh());
  onShown(root, () => {
    void refresh();
    if (shown) drawTiling(tiling, offscreen, shown.width, shown.height, frame.checked);
  });
  if (typeof ResizeObserver !== "undefined") {
    new ResizeObserver(() => {
      if (shown) drawTiling(tiling, offscreen, shown.width, shown.height, frame.checked);
    }).observe(tiling);
  }
  void refresh();
}
