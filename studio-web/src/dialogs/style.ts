// CSS of the export dialog, the author box and the edit-by-words box (dark, dense), injected once.
import { injectStyle } from "../inspector/dom";

const CSS = `
.dlg-root { display: flex; flex-wrap: wrap; gap: 10px; padding: 6px; color: var(--fg, #d6d8dc);
  background: var(--bg, #16181c); font: 12px/1.35 var(--font-ui, system-ui, sans-serif); align-items: flex-start; }
.dlg-box { flex: 1 1 300px; min-width: 260px; display: flex; flex-direction: column; gap: 6px;
  background: #1b1e23; border: 1px solid #2a2d33; border-radius: 4px; padding: 6px 8px; }
.dlg-box h3 { margin: 0; font-size: 11px; font-weight: 600; text-transform: uppercase; letter-spacing: .06em;
  color: var(--fg-dim, #9aa0a8); }
.dlg-grid { display: grid; grid-template-columns: max-content 1fr; gap: 4px 8px; align-items: center; }
.dlg-grid > span { color: var(--fg-dim, #9aa0a8); }
.dlg-row { display: flex; flex-wrap: wrap; gap: 6px; align-items: center; }
.dlg-root select, .dlg-root input[type=text], .dlg-root input[type=number], .dlg-root textarea, .dlg-root button {
  background: #23262c; color: inherit; border: 1px solid #363a42; border-radius: 3px; padding: 2px 6px; font: inherit; }
.dlg-root input[type=text], .dlg-root input[type=number] { min-width: 0; }
.dlg-root input:focus, .dlg-root textarea:focus, .dlg-root select:focus { outline: 1px solid #5b8def; border-color: #5b8def; }
.dlg-root textarea { resize: vertical; min-height: 3.2em; }
.dlg-root button:hover:not(:disabled) { border-color: #5b8def; }
.dlg-root button:disabled { opacity: .45; }
.dlg-root button.dlg-primary { background: #2d4f8e; border-color: #3d64ad; }
.dlg-grow { flex: 1 1 160px; }
.dlg-check { display: inline-flex; gap: 3px; align-items: center; margin-right: 6px; }
.dlg-dim { color: var(--fg-dim, #80868f); font-size: 11px; }
.dlg-err { color: #ff6b6b; white-space: pre-wrap; }
.dlg-ok { color: #6cc070; }
.dlg-warn { color: #e0a040; }
.dlg-files { margin: 0; padding: 0 0 0 14px; font: 11px/1.4 var(--font-mono, ui-monospace, monospace);
  max-height: 220px; overflow: auto; }
.dlg-pre { margin: 0; font: 11px/1.4 var(--font-mono, ui-monospace, monospace); white-space: pre; overflow: auto;
  max-height: 260px; background: #101215; border: 1px solid #2a2d33; padding: 3px 6px; }
.dlg-add { color: #7ed08a; }
.dlg-del { color: #ff8a80; }
.dlg-hunk { color: #7aa7ff; }
.dlg-rounds { list-style: none; margin: 0; padding: 0; display: flex; flex-direction: column; gap: 3px;
  max-height: 320px; overflow: auto; }
.dlg-round { display: flex; gap: 6px; align-items: center; padding: 2px; border: 1px solid transparent;
  border-radius: 3px; cursor: pointer; }
.dlg-round:hover, .dlg-round.dlg-sel { border-color: #3d64ad; background: #20242b; }
.dlg-round img { width: 48px; height: 48px; image-rendering: auto; background: #0b0c0e; flex: none; }
.dlg-log { margin: 0; font: 10.5px/1.35 var(--font-mono, ui-monospace, monospace); color: #9aa0a8; max-height: 140px;
  overflow: auto; white-space: pre-wrap; background: #101215; border: 1px solid #2a2d33; padding: 3px 6px; }
.dlg-table { border-collapse: collapse; font: 11px var(--font-mono, ui-monospace, monospace); }
.dlg-table td, .dlg-table th { padding: 1px 8px 1px 0; text-align: left; vertical-align: top; }
.dlg-table th { color: var(--fg-dim, #80868f); font-weight: normal; }
.dlg-render { max-width: 100%; border: 1px solid #2a2d33; }
`;

export function dialogStyle(): void {
  injectStyle("dlg-style", CSS);
}
