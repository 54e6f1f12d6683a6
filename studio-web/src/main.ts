// Boots the studio: reads the session, restores a permalink, builds the layout and wires the
// parts (editor, panel, viewer, inspector, compare, export, author) to one store.
import { Api, ApiError } from "./api";
import type { Ctx } from "./ctx";
import { mountAuthor } from "./dialogs/author";
import { mountExport } from "./dialogs/export";
import { mountDiagList } from "./editor/diaglist";
import { mountEditor } from "./editor/index";
import { Vocab, type VocabJson } from "./editor/vocab";
import { History, permalinkFromLocation } from "./history";
import { mountCompare } from "./inspector/compare";
import { mountInspector } from "./inspector/index";
import { Live } from "./live";
import { mountPanel } from "./panel/index";
import { Store } from "./store";
import { mountViewer } from "./viewer/index";
import { mountLayout, showTab } from "./layout";

const TOKEN_KEY = "matloom-studio-token";

function $(id: string): HTMLElement {
  const el = document.getElementById(id);
  if (!el) throw new Error(`page is missing #${id}`);
  return el;
}

let toastTimer: ReturnType<typeof setTimeout> | undefined;
export function toast(message: string, error = false): void {
  const el = $("toast");
  el.textContent = message;
  el.className = error ? "toast error" : "toast";
  el.hidden = false;
  clearTimeout(toastTimer);
  toastTimer = setTimeout(() => (el.hidden = true), error ? 6000 : 2500);
}

function fatal(message: string): void {
  const el = $("fatal");
  el.textContent = message;
  el.hidden = false;
  const s = $("status");
  s.textContent = message.split("\n")[0];
  s.dataset.state = "error";
}

function token(): string {
  const q = new URLSearchParams(location.search).get("token");
  if (q) {
    try {
      localStorage.setItem(TOKEN_KEY, q);
    } catch {
      /* storage may be off */
    }
    return q;
  }
  try {
    return localStorage.getItem(TOKEN_KEY) ?? "";
  } catch {
    return "";
  }
}

function mountPart(name: string, fn: (el: HTMLElement, ctx: Ctx) => void, el: HTMLElement, ctx: Ctx): void {
  try {
    fn(el, ctx);
  } catch (e) {
    console.error(`studio: ${name} failed to mount`, e);
    el.textContent = `${name} failed to load: ${(e as Error).message}`;
  }
}

async function boot(): Promise<void> {
  const api = new Api(token());
  let session: Ctx["session"];
  try {
    session = await api.json<Ctx["session"]>("/api/session");
  } catch (e) {
    if (e instanceof ApiError && e.status === 403) {
      fatal("This page needs the session token.\nOpen the URL that `matloom studio` printed (it ends in ?token=...).");
    } else fatal(`Cannot reach the studio server: ${(e as Error).message}`);
    return;
  }
  const vocab = new Vocab(await api.json<VocabJson>("/api/vocab").catch(() => ({})));

  const store = new Store();
  store.path = session.opened;
  const history = new History(store);
  const ctx: Ctx = { api, store, history, session };
  const hooks = ((window as unknown as { matloomStudio?: Record<string, unknown> }).matloomStudio ??= {});
  Object.assign(hooks, { store, history, ctx, lastMapsSeq: 0 });
  hooks.frames ??= 0;
  hooks.lastShownAt ??= { seq: 0, t: 0 };

  // A permalink in the fragment wins over the session's text.
  let text = session.text ?? "";
  let label = session.opened ? "opened" : "start";
  try {
    const linked = await permalinkFromLocation();
    if (linked !== null) {
      text = linked;
      label = "permalink";
    }
  } catch (e) {
    toast(`The permalink could not be read: ${(e as Error).message}`, true);
  }
  store.setText(text, "load");
  history.reset(text, label);
  let savedText = session.opened && label !== "permalink" ? session.text : null;

  // Top bar.
  const status = $("status");
  store.on("status", ({ state, message }) => {
    status.dataset.state = state;
    status.textContent = state === "error" ? message || "error" : state;
    status.title = message ?? "";
  });
  const fileName = $("file-name");
  const dirty = $("dirty");
  const showFile = (): void => {
    fileName.textContent = store.path ?? "untitled";
    fileName.title = store.path ? `${session.root}/${store.path}` : "not saved yet";
    dirty.hidden = store.text === savedText;
    document.title = `${dirty.hidden ? "" : "● "}${store.path ?? "untitled"} — MatLoom studio`;
  };
  store.on("text", showFile);
  showFile();

  const undoBtn = $("undo") as HTMLButtonElement;
  const redoBtn = $("redo") as HTMLButtonElement;
  const syncButtons = (): void => {
    undoBtn.disabled = !history.canUndo();
    redoBtn.disabled = !history.canRedo();
  };
  history.onChange(syncButtons);
  store.on("text", syncButtons);
  syncButtons();
  undoBtn.addEventListener("click", () => history.undo());
  redoBtn.addEventListener("click", () => history.redo());

  const save = async (): Promise<void> => {
    let path = store.path;
    if (!path) {
      const name = window.prompt(`Save as (a .mat file inside ${session.root})`, "material.mat");
      if (!name) return;
      path = name.endsWith(".mat") ? name : `${name}.mat`;
    }
    const text = store.text;
    try {
      const r = await api.json<{ path: string; bytes: number }>("/api/save", { path, text });
      store.path = r.path;
      savedText = text;
      history.mark("saved");
      showFile();
      toast(`Saved ${r.path} (${r.bytes} bytes)`);
    } catch (e) {
      toast(`Save failed: ${(e as Error).message}`, true);
    }
  };
  $("save").addEventListener("click", () => void save());

  const permalink = async (): Promise<void> => {
    const url = await history.permalink();
    const hash = new URL(url).hash;
    if (location.hash !== hash) location.hash = hash;
    try {
      await navigator.clipboard.writeText(url);
      toast(`Permalink copied (${url.length} characters)`);
    } catch {
      toast("Permalink is in the address bar");
    }
  };
  $("permalink").addEventListener("click", () => void permalink());
  window.addEventListener("hashchange", () => {
    void permalinkFromLocation()
      .then((linked) => {
        if (linked === null || linked === store.text) return;
        history.commit();
        store.setText(linked, "load");
        history.commit("permalink");
      })
      .catch((e) => toast(`The permalink could not be read: ${(e as Error).message}`, true));
  });

  const evalMs = $("eval-ms");
  const live = new Live(ctx);
  live.onInfo(({ pass, size, evalMs: ms, roundTripMs }) => {
    evalMs.textContent = `${Math.round(ms)} ms · ${size}²${pass === "preview" ? " (first pass)" : ""}`;
    evalMs.title = `evaluation ${ms.toFixed(1)} ms, round trip ${roundTripMs.toFixed(1)} ms`;
  });
  store.on("maps", (maps) => {
    hooks.lastMapsSeq = maps.header.seq;
  });

  // Parts.
  const editor = mountEditor($("editor-host"), ctx, vocab, (message) => toast(message, true));
  mountDiagList($("diag-list") as HTMLUListElement, $("diag-count"), store, (at) => editor.jumpTo(at));
  $("format").addEventListener("click", () => void editor.format().then((e) => e && toast(e, true)));
  mountPart("panel", mountPanel, $("panel"), ctx);
  mountPart("viewer", mountViewer, $("pane-viewer"), ctx);
  mountPart("inspector", mountInspector, $("pane-inspector"), ctx);
  mountPart("compare", mountCompare, $("pane-compare"), ctx);
  mountPart("export", mountExport, $("pane-export"), ctx);
  mountPart("author", mountAuthor, $("pane-author"), ctx);
  mountLayout();
  hooks.editor = editor.view;
  hooks.showTab = showTab;

  // Keys: Ctrl+S saves; Ctrl+Z / Ctrl+Shift+Z / Ctrl+Y are the studio's undo/redo everywhere
  // except in plain text fields (their own undo).
  window.addEventListener(
    "keydown",
    (e) => {
      if (!(e.ctrlKey || e.metaKey) || e.altKey) return;
      const key = e.key.toLowerCase();
      if (key === "s") {
        e.preventDefault();
        e.stopPropagation();
        void save();
        return;
      }
      if (key !== "z" && key !== "y") return;
      const t = e.target as HTMLElement | null;
      const field = t instanceof HTMLTextAreaElement || (t instanceof HTMLInputElement && t.type !== "range" && t.type !== "checkbox");
      if (field) return;
      e.preventDefault();
      e.stopPropagation();
      if (key === "y" || e.shiftKey) history.redo();
      else history.undo();
    },
    true,
  );

  // Everything is listening: announce the program and evaluate it.
  store.emit("text", { text: store.text, source: "load" });
}

void boot().catch((e) => {
  console.error(e);
  fatal(`The studio failed to start: ${(e as Error).message}`);
});
