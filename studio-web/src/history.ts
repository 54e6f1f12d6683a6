// Undo/redo of program versions across editor and panel edits, the session's version list, and
// permalinks (`#p=` + base64url(deflate-raw(text))).
import type { HistoryApi } from "./ctx";
import type { Source, Store } from "./store";

/** Typing pauses longer than this end an undo step. */
const TYPING_PAUSE_MS = 600;
/** Panel edits without an explicit commit end a step after this pause (and no pointer held). */
const PANEL_PAUSE_MS = 900;
const MAX_STEPS = 500;
const MAX_VERSIONS = 200;
/** Largest program a permalink may expand to (guards against a hostile fragment). */
const MAX_PERMALINK_CHARS = 2_000_000;

/** Version labels for the kinds of edit (the others are given by whoever commits). */
const LABELS: Record<string, string> = { editor: "typing", panel: "panel edit", author: "author" };

export interface Version {
  text: string;
  label: string;
  time: number;
}

export class History implements HistoryApi {
  private steps: string[] = [];
  private cur = -1;
  private list: Version[] = [];
  private timer: ReturnType<typeof setTimeout> | undefined;
  private pendingLabel = "edit";
  private pointerDown = false;
  private listeners: (() => void)[] = [];
  /** The text at the previous `text` event (the step boundary when the kind of edit changes). */
  private seen = "";

  constructor(private readonly store: Store) {
    store.on("text", ({ source }) => this.onText(source));
    window.addEventListener("pointerdown", () => (this.pointerDown = true), true);
    for (const ev of ["pointerup", "pointercancel"]) window.addEventListener(ev, () => (this.pointerDown = false), true);
  }

  /** Start the history at `text` (the opened program or a permalink). */
  reset(text: string, label: string): void {
    clearTimeout(this.timer);
    this.steps = [text];
    this.cur = 0;
    this.seen = text;
    this.list = [];
    this.addVersion(text, label);
    this.changed();
  }

  onChange(fn: () => void): () => void {
    this.listeners.push(fn);
    return () => this.listeners.splice(this.listeners.indexOf(fn), 1);
  }

  private changed(): void {
    for (const fn of [...this.listeners]) fn();
  }

  private dirty(): boolean {
    return this.cur >= 0 && this.store.text !== this.steps[this.cur];
  }

  private schedule(ms: number): void {
    clearTimeout(this.timer);
    this.timer = setTimeout(() => {
      // While a pointer is held (a drag) the panel commits at the drag's end.
      if (this.pendingLabel === "panel" && this.pointerDown) return;
      this.commit(this.pendingLabel);
    }, ms);
  }

  private onText(source: Source): void {
    const before = this.seen;
    this.seen = this.store.text;
    if (source === "history" || source === "load") return;
    if (this.pendingLabel !== source && this.cur >= 0 && before !== this.steps[this.cur]) {
      this.push(before, this.pendingLabel); // a different kind of edit starts a new step
    }
    this.pendingLabel = source;
    // Author results are one step each (at once, unless their box commits with a better label).
    this.schedule(source === "editor" ? TYPING_PAUSE_MS : source === "author" ? 0 : PANEL_PAUSE_MS);
    this.changed();
  }

  commit(label?: string): void {
    clearTimeout(this.timer);
    if (this.cur < 0) {
      this.reset(this.store.text, label ?? "start");
      return;
    }
    this.push(this.store.text, label ?? this.pendingLabel);
  }

  private push(text: string, label: string): void {
    if (text === this.steps[this.cur]) return;
    this.steps.splice(this.cur + 1);
    this.steps.push(text);
    if (this.steps.length > MAX_STEPS) this.steps.splice(0, this.steps.length - MAX_STEPS);
    this.cur = this.steps.length - 1;
    this.addVersion(text, label);
    this.changed();
  }

  private addVersion(text: string, label: string): void {
    label = LABELS[label] ?? label;
    const last = this.list[this.list.length - 1];
    if (last && last.text === text) return;
    this.list.push({ text, label, time: Date.now() });
    if (this.list.length > MAX_VERSIONS) this.list.splice(0, this.list.length - MAX_VERSIONS);
  }

  /** Mark the current text as a named version (e.g. "saved") without changing undo steps. */
  mark(label: string): void {
    this.commit(label);
    const last = this.list[this.list.length - 1];
    if (last && last.text === this.store.text) last.label = label;
    else this.addVersion(this.store.text, label);
    this.changed();
  }

  canUndo(): boolean {
    return this.cur > 0 || this.dirty();
  }

  canRedo(): boolean {
    return !this.dirty() && this.cur >= 0 && this.cur < this.steps.length - 1;
  }

  undo(): void {
    if (this.dirty()) this.commit(this.pendingLabel);
    if (this.cur <= 0) return;
    this.cur--;
    this.store.setText(this.steps[this.cur], "history");
    this.changed();
  }

  redo(): void {
    if (!this.canRedo()) return;
    this.cur++;
    this.store.setText(this.steps[this.cur], "history");
    this.changed();
  }

  versions(): Version[] {
    return [...this.list];
  }

  /** The shareable URL of the current program (the session token is left out). */
  async permalink(): Promise<string> {
    const code = await encodePermalink(this.store.text);
    const url = new URL(location.href);
    url.searchParams.delete("token");
    url.hash = `p=${code}`;
    return url.toString();
  }
}

async function pipe(data: Uint8Array, stream: CompressionStream | DecompressionStream, limit: number): Promise<Uint8Array> {
  const out = new Blob([data as BlobPart]).stream().pipeThrough(stream);
  const reader = out.getReader();
  const chunks: Uint8Array[] = [];
  let n = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    n += value.length;
    if (n > limit) {
      await reader.cancel();
      throw new Error("permalink too large");
    }
    chunks.push(value);
  }
  const all = new Uint8Array(n);
  let o = 0;
  for (const c of chunks) {
    all.set(c, o);
    o += c.length;
  }
  return all;
}

function toBase64Url(bytes: Uint8Array): string {
  let s = "";
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(s).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function fromBase64Url(code: string): Uint8Array {
  const b64 = code.replace(/-/g, "+").replace(/_/g, "/");
  const s = atob(b64 + "=".repeat((4 - (b64.length % 4)) % 4));
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}

export async function encodePermalink(text: string): Promise<string> {
  const raw = new TextEncoder().encode(text);
  return toBase64Url(await pipe(raw, new CompressionStream("deflate-raw"), Number.MAX_SAFE_INTEGER));
}

export async function decodePermalink(code: string): Promise<string> {
  const bytes = await pipe(fromBase64Url(code), new DecompressionStream("deflate-raw"), MAX_PERMALINK_CHARS * 4);
  return new TextDecoder("utf-8", { fatal: true }).decode(bytes);
}

/** The program in the URL fragment (`#p=...`), or null when there is none. */
export async function permalinkFromLocation(): Promise<string | null> {
  const m = /^#p=([A-Za-z0-9_-]+)$/.exec(location.hash);
  return m ? decodePermalink(m[1]) : null;
}
