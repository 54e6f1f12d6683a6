// The panel's CSS (class prefix `pn-`), injected once as a <style> element: the build copies
// app.css as is and does not bundle CSS imports.

const CSS = `
.pn-root{--pn-bg:var(--bg-pane,#1a1e24);--pn-card:#1f242c;--pn-head:#252b34;--pn-line:var(--line,#2a303a);
  --pn-fg:var(--fg,#d5dbe4);--pn-dim:var(--fg-dim,#8a94a6);--pn-acc:var(--accent,#4f8cff);--pn-warn:var(--warn,#e8b34b);
  --pn-err:var(--err,#ff5f72);--pn-tag:#2b3140;--pn-input:var(--bg-input,#10131a);
  --pn-mono:var(--mono,ui-monospace,Menlo,Consolas,monospace);
  display:flex;flex-direction:column;height:100%;min-height:0;background:var(--pn-bg);color:var(--pn-fg);
  font:12px/1.35 var(--sans,system-ui,sans-serif);}
.pn-root *{box-sizing:border-box}
.pn-bar{display:flex;gap:4px;align-items:center;padding:4px 6px;border-bottom:1px solid var(--pn-line);flex:none}
.pn-filter{flex:1;min-width:60px;background:var(--pn-input);color:var(--pn-fg);border:1px solid var(--pn-line);border-radius:3px;padding:2px 6px;font:inherit}
.pn-filter:focus{outline:none;border-color:var(--pn-acc)}
.pn-msg{flex:none;padding:2px 8px;font-size:11px;color:var(--pn-dim);min-height:0;white-space:nowrap;overflow:hidden;text-overflow:ellipsis}
.pn-msg:empty{display:none}
.pn-msg.pn-error{color:var(--pn-err)}.pn-msg.pn-warning{color:var(--pn-warn)}
.pn-scroll{flex:1;min-height:0;overflow:auto;padding:4px 4px 24px}
.pn-root.pn-stale .pn-card{opacity:.55;pointer-events:none}
.pn-root.pn-stale .pn-msg{color:var(--pn-warn)}
.pn-card{background:var(--pn-card);border:1px solid var(--pn-line);border-radius:4px;margin:0 0 4px}
.pn-card-head{display:flex;align-items:center;gap:4px;padding:2px 4px;background:var(--pn-head);border-radius:4px 4px 0 0;min-height:24px;user-select:none}
.pn-collapsed .pn-card-head{border-radius:4px}
.pn-collapsed .pn-body{display:none}
.pn-collapsed .pn-caret{transform:rotate(-90deg)}
.pn-title{font-weight:600;flex:1;min-width:0;overflow:hidden;text-overflow:ellipsis;white-space:nowrap}
.pn-line{color:var(--pn-dim);font:10px var(--pn-mono)}
.pn-badge{font:600 10px var(--pn-mono);padding:0 4px;border-radius:3px;background:#333a46;color:#b8c4d8}
.pn-badge-define{background:#2d3a2f;color:#9fd6a4}.pn-badge-layer{background:#3a3250;color:#c4b2f0}
.pn-badge-view{background:#213545;color:#8cc8f0}
.pn-handle{cursor:grab;color:var(--pn-dim);padding:0 2px}
.pn-ib{background:transparent;border:1px solid transparent;color:var(--pn-dim);border-radius:3px;font:12px/1 system-ui,sans-serif;
  min-width:20px;height:20px;padding:0 4px;cursor:pointer}
.pn-ib:hover:not(:disabled){background:#323844;color:var(--pn-fg);border-color:var(--pn-line)}
.pn-ib:disabled{opacity:.3;cursor:default}
.pn-ib.pn-on{color:var(--pn-acc)}
.pn-solo.pn-on{background:#2a3d5c}
.pn-del:hover:not(:disabled){color:var(--pn-err)}
.pn-caret{min-width:16px;padding:0;transition:transform .1s}
.pn-lbtns{display:flex;gap:1px}
.pn-card.pn-hidden .pn-body,.pn-card.pn-hidden .pn-title{opacity:.45}
.pn-card.pn-dragging{opacity:.5}
.pn-card.pn-drop-before{box-shadow:0 -2px 0 var(--pn-acc)}
.pn-card.pn-drop-after{box-shadow:0 2px 0 var(--pn-acc)}
.pn-body{padding:2px 6px 4px}
.pn-src{font:11px var(--pn-mono);color:var(--pn-dim);white-space:nowrap;overflow:hidden;text-overflow:ellipsis;padding:1px 0 3px}
.pn-facts{display:flex;flex-wrap:wrap;gap:3px 10px;color:var(--pn-dim);font-size:11px;padding:2px 0}
.pn-card-empty .pn-card-head{background:transparent}
.pn-card-empty .pn-body{padding-bottom:1px}
.pn-card-empty .pn-title{font-weight:500;color:#aab2bf}
.pn-empty{color:var(--pn-dim);font-style:italic;font-size:11px;padding:1px 0}
.pn-row{padding:2px 0;border-top:1px solid #262a31}
.pn-row:first-of-type{border-top:none}
.pn-head{display:flex;align-items:center;gap:6px;min-height:16px}
.pn-label{flex:1;min-width:0;overflow:hidden;text-overflow:ellipsis;white-space:nowrap;color:#c2c8d2;cursor:default}
.pn-tags{display:flex;gap:2px;flex:none}
.pn-tag{font-size:9px;line-height:13px;padding:0 4px;border-radius:6px;background:var(--pn-tag);color:#9aa6bb}
.pn-tag-all{background:#3a2f22;color:#e0b67a}.pn-tag-auto{background:#24382e;color:#8fd1a6}
.pn-ctl{display:flex;align-items:center;gap:6px;min-height:20px}
.pn-slider{flex:1;min-width:60px;height:14px;margin:0;accent-color:var(--pn-acc);cursor:ew-resize}
.pn-num{width:68px;flex:none;background:var(--pn-input);color:var(--pn-fg);border:1px solid var(--pn-line);border-radius:3px;
  padding:1px 4px;font:11px var(--pn-mono);text-align:right}
.pn-num:focus{outline:none;border-color:var(--pn-acc)}
.pn-k-seed .pn-num{width:92px}
.pn-unit{flex:none;width:44px;color:var(--pn-dim);font-size:10px;white-space:nowrap;overflow:hidden;text-overflow:ellipsis}
.pn-colour{width:44px;height:20px;padding:0 2px;border:1px solid var(--pn-line);border-radius:3px;background:var(--pn-input);cursor:pointer}
.pn-rgb,.pn-seedval{font:11px var(--pn-mono);color:var(--pn-dim);white-space:pre;flex:1}
.pn-toast{position:sticky;bottom:0;display:flex;gap:8px;align-items:center;justify-content:space-between;margin-top:6px;
  background:#2a303a;border:1px solid var(--pn-line);border-radius:4px;padding:4px 8px}
.pn-toast button{background:#3a4352;color:var(--pn-fg);border:1px solid #4a5466;border-radius:3px;font:inherit;padding:1px 8px;cursor:pointer}
`;

const ID = "pn-style";

export function injectStyle(doc: Document = document): void {
  if (doc.getElementById(ID)) return;
  const style = doc.createElement("style");
  style.id = ID;
  style.textContent = CSS;
  doc.head.append(style);
}
