// The 3x3 tiling view: the map repeated, the centre tile framed by a line drawn in the gap
// around it (never over texels), plus the seam ratios from the maps header.
import type { MapsHeader } from "../api";
import { fmt, h } from "./dom";

/** Seam ratio above which a map's wrap edge is called out (the library's check uses 1.2). */
export const SEAM_LIMIT = 1.2;

/**
 * Draw `tile` 3x3 on `canvas` (sized to its box). `frame`: leave a gap of `gap` device pixels
 * between tiles and draw a 1-pixel line around the centre tile inside that gap; without it the
 * tiles touch, so seams show as they would on a surface.
 */
export function drawTiling(canvas: HTMLCanvasElement, tile: CanvasImageSource, tw: number, th: number, frame: boolean): void {
  const dpr = window.devicePixelRatio || 1;
  const cssW = canvas.clientWidth || 480;
  const W = Math.max(64, Math.round(cssW * dpr));
  const gap = frame ? Math.max(3, Math.round(3 * dpr)) : 0;
  const t = Math.floor((W - 2 * gap) / 3);
  const tH = Math.round((t * th) / tw);
  const H = 3 * tH + 2 * gap;
  if (canvas.width !== W || canvas.height !== H) {
    canvas.width = W;
    canvas.height = H;
  }
  const g = canvas.getContext("2d");
  if (!g) return;
  g.fillStyle = "#0b0c0e";
  g.fillRect(0, 0, W, H);
  g.imageSmoothingEnabled = t < tw; // shrink smoothly, enlarge as crisp texels
  for (let row = 0; row < 3; row++)
    for (let col = 0; col < 3; col++) g.drawImage(tile, 0, 0, tw, th, col * (t + gap), row * (tH + gap), t, tH);
  if (!frame) return;
  // The outline runs along the middle of the gap: texels of no tile are covered.
  const lw = Math.max(1, Math.round(dpr));
  const x0 = t + gap / 2;
  const y0 = tH + gap / 2;
  g.strokeStyle = "#ffb000";
  g.lineWidth = lw;
  g.strokeRect(x0, y0, t + gap, tH + gap);
}

/** The tileability line and a table of seam ratios (1 = as smooth as the interior). */
export function seamReport(header: MapsHeader): HTMLElement {
  const box = h("div", { class: "ins-seams" });
  if (!header.tileable) {
    box.append(
      h("div", { class: "ins-warn", text: "not tileable: the View is not tileable=True, so edges need not match" }),
    );
    return box;
  }
  box.append(h("div", { class: "ins-ok", text: "tileable (View tileable=True)" }));
  const seam = header.seam;
  if (!seam || Object.keys(seam).length === 0) {
    box.append(h("div", { class: "ins-dim", text: "no seam ratios in this reply" }));
    return box;
  }
  const table = h("table", { class: "ins-table" });
  table.append(h("tr", {}, h("th", { text: "map" }), h("th", { text: "seam ratio" })));
  for (const [name, v] of Object.entries(seam)) {
    const bad = typeof v === "number" && v > SEAM_LIMIT;
    table.append(
      h("tr", { class: bad ? "ins-bad" : null }, h("td", { text: name }), h("td", { text: typeof v === "number" ? fmt(v, 3) : String(v) })),
    );
  }
  box.append(table, h("div", { class: "ins-dim", text: `wrap-edge / interior difference; over ${SEAM_LIMIT} shows as a seam` }));
  return box;
}
