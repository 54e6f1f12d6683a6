// The 3D view's own styles (injected once, so the viewer needs nothing from app.css).

const CSS = `
.mlv-root { position: relative; width: 100%; height: 100%; min-height: 200px; overflow: hidden;
  background: #1d1f23; }
.mlv-root canvas { display: block; width: 100%; height: 100%; touch-action: none; outline: none; }
.mlv-root.mlv-drop::after { content: "Drop an .hdr or .exr environment"; position: absolute; inset: 8px;
  border: 2px dashed #8ab4f8; border-radius: 8px; display: flex; align-items: center;
  justify-content: center; color: #e8eaed; background: rgba(20, 24, 32, 0.6); pointer-events: none;
  font: 14px system-ui, sans-serif; }
.mlv-overlay { position: absolute; top: 8px; right: 8px; max-width: 270px; display: flex;
  flex-direction: column; align-items: flex-end; gap: 6px; font: 12px system-ui, sans-serif;
  color: #e8eaed; pointer-events: none; }
.mlv-overlay > * { pointer-events: auto; }
.mlv-bar { display: flex; gap: 4px; }
.mlv-overlay select, .mlv-overlay button { font: inherit; color: inherit; background: rgba(32, 34, 38, 0.85);
  border: 1px solid #4a4d55; border-radius: 4px; padding: 2px 6px; cursor: pointer; }
.mlv-overlay button:hover, .mlv-overlay select:hover { border-color: #8ab4f8; }
.mlv-panel { background: rgba(32, 34, 38, 0.85); border: 1px solid #4a4d55; border-radius: 6px;
  padding: 6px 8px; display: grid; gap: 4px; width: 250px; }
.mlv-panel[hidden] { display: none; }
.mlv-row { display: grid; grid-template-columns: 92px 1fr auto; align-items: center; gap: 6px; }
.mlv-row input[type=range] { width: 100%; margin: 0; }
.mlv-row input[type=color] { width: 28px; height: 20px; padding: 0; border: none; background: none; }
.mlv-row select { min-width: 0; }
.mlv-note { background: rgba(32, 34, 38, 0.75); border-radius: 4px; padding: 2px 6px; max-width: 260px; }
.mlv-note:empty { display: none; }
.mlv-note.mlv-error { color: #f28b82; }
.mlv-fallback { color: #e8eaed; font: 13px system-ui, sans-serif; padding: 16px; }
`;

export function injectStyle(): void {
  if (document.getElementById("mlv-style")) return;
  const s = document.createElement("style");
  s.id = "mlv-style";
  s.textContent = CSS;
  document.head.append(s);
}
