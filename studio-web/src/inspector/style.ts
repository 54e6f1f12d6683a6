// The inspector's and compare view's CSS (dark, dense), injected once.
import { injectStyle } from "./dom";

const CSS = `
.ins-root { display: flex; flex-direction: column; gap: 6px; padding: 6px; color: var(--fg, #d6d8dc);
  background: var(--bg, #16181c); font: 12px/1.35 var(--font-ui, system-ui, sans-serif); min-width: 0; }
.ins-bar { display: flex; flex-wrap: wrap; gap: 6px 10px; align-items: center; }
.ins-field { display: inline-flex; gap: 4px; align-items: center; color: var(--fg-dim, #9aa0a8); }
.ins-root select, .ins-root button, .ins-root input[type=number] { background: #23262c; color: inherit;
  border: 1px solid #363a42; border-radius: 3px; padding: 2px 6px; font: inherit; }
.ins-root button:hover:not(:disabled) { border-color: #5b8def; }
.ins-root button:disabled { opacity: .5; }
.ins-root h3 { margin: 6px 0 2px; font-size: 11px; font-weight: 600; text-transform: uppercase;
  letter-spacing: .06em; color: var(--fg-dim, #9aa0a8); }
.ins-canvas { display: block; width: 100%; max-width: 560px; aspect-ratio: 1; background: #0b0c0e;
  border: 1px solid #2a2d33; cursor: crosshair; touch-action: none; image-rendering: pixelated; }
.ins-tiling { display: block; width: 100%; max-width: 560px; background: #0b0c0e; border: 1px solid #2a2d33; }
.ins-hist { display: block; width: 100%; max-width: 560px; height: 72px; border: 1px solid #2a2d33; }
.ins-readout { font: 11px/1.4 var(--font-mono, ui-monospace, monospace); white-space: pre; min-height: 4.2em;
  background: #101215; border: 1px solid #2a2d33; padding: 3px 6px; max-width: 548px; overflow: hidden; }
.ins-dim { color: var(--fg-dim, #80868f); font-size: 11px; }
.ins-warn { color: #e0a040; }
.ins-ok { color: #6cc070; }
.ins-err { color: #ff6b6b; white-space: pre-wrap; }
.ins-table { border-collapse: collapse; font: 11px var(--font-mono, ui-monospace, monospace); }
.ins-table td, .ins-table th { padding: 1px 8px 1px 0; text-align: left; }
.ins-table th { color: var(--fg-dim, #80868f); font-weight: normal; }
.ins-bad td { color: #ff8a65; }
.ins-metrics { font: 12px var(--font-mono, ui-monospace, monospace); padding: 3px 6px; background: #101215;
  border: 1px solid #2a2d33; max-width: 548px; }
.ins-compare { cursor: ew-resize; }
`;

export function inspectorStyle(): void {
  injectStyle("ins-style", CSS);
}
