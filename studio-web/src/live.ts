// Live evaluation: every program or layer change is evaluated, a quick first pass (256 px)
// then full size (512 px), one request in flight per stream plus the latest pending, so a
// slider drag never queues up. Also refreshes the structure (/api/structure) for the panel.
// A panel edit's first pass is speculative: sent with the edit's values as /api/set goes out,
// it evaluates the text /api/set will return, so the slider step costs one round trip.
import { ApiError, type Maps } from "./api";
import type { Ctx } from "./ctx";
import type { Structure } from "./store";

export const PREVIEW_SIZE = 256;
export const FULL_SIZE = 512;
/** A drag's first pass: the 3D view draws it in small frames (about 48k pixels on software GL),
 * so 192 px maps show all it can; a quarter of the texels of 512, half of 256's. */
export const DRAG_PREVIEW_SIZE = 192;
/** A drag's first pass aims to come back within this, scaled from the last full pass's round
 * trip (a heavy program's drag preview is smaller, down to `DRAG_MIN_SIZE`). */
const DRAG_PASS_MS = 32;
const DRAG_MIN_SIZE = 128;

/** A drag's first-pass size: `DRAG_PREVIEW_SIZE`, or smaller (at least `DRAG_MIN_SIZE`) for a
 * program whose full pass is slow. */
export function dragSize(lastFullMs: number): number {
  return fittedSize(lastFullMs, DRAG_PASS_MS, DRAG_MIN_SIZE, DRAG_PREVIEW_SIZE);
}

/** Debounce of editor typing; panel drags and layer toggles go at once. */
const TYPING_DEBOUNCE_MS = 30;
/** When the last full pass came back faster than this, the first pass is skipped (except for a
 * slider drag: its first pass is a quarter of the work and what the 3D view shows first). */
const FAST_FULL_MS = 70;
/** After a panel edit the structure is refreshed once no further panel edit came for this long. */
const PANEL_STRUCTURE_MS = 350;
/** The first pass aims to come back within this, scaled from the last full pass's time. */
const FIRST_PASS_MS = 120;
/** The longest a drag's full pass waits for its first pass's frame to be presented. */
const PRESENT_WAIT_MS = 250;

/** First-pass size: 256 px, or smaller for a program whose full pass is slow, at least 64 px. */
export function previewSize(lastFullMs: number): number {
  return fittedSize(lastFullMs, FIRST_PASS_MS, 64, PREVIEW_SIZE);
}

/** The size whose pass should take about `budgetMs`, scaled from the last full pass's time
 * (which grows with the texels), in steps of 32 px within [lo, hi]; `hi` before any full pass. */
function fittedSize(lastFullMs: number, budgetMs: number, lo: number, hi: number): number {
  if (!Number.isFinite(lastFullMs) || lastFullMs <= 0) return hi;
  const fit = FULL_SIZE * Math.sqrt(budgetMs / lastFullMs);
  return Math.max(lo, Math.min(hi, Math.floor(fit / 32) * 32));
}

interface Job {
  /** A slider step: always send the quick first pass (the 3D view shows it while dragging). */
  drag: boolean;
  text: string;
  /** The server's hash of `text` (set by a panel edit), to match a speculative first pass. */
  sha: string | null;
  /** The speculation sent for the edit that made `text`, if any. */
  spec: Speculation | null;
  hidden: number[];
  solo: number | null;
}

export interface EvalInfo {
  pass: "preview" | "full";
  size: number;
  evalMs: number;
  roundTripMs: number;
}

/** A speculative first pass: the maps of what /api/set makes of `from` with some values. */
interface Speculation {
  from: string;
  /** The text generation it was sent in (typing, undo and loads start a new one). */
  generation: number;
  /** The evaluated text's hash once the maps came back (null while in flight or failed). */
  sha: string | null;
  /** The seq of its maps once shown. */
  seq: number | null;
  done: Promise<void>;
}

/** Runs at most one task at a time and keeps only the latest one waiting. */
class Latest<T> {
  private running = false;
  private next: T | null = null;
  constructor(
    private readonly run: (job: T, superseded: () => boolean) => Promise<void>,
    private readonly onIdle: () => void,
  ) {}

  push(job: T): void {
    this.next = job;
    if (!this.running) void this.loop();
  }

  get busy(): boolean {
    return this.running || this.next !== null;
  }

  private async loop(): Promise<void> {
    this.running = true;
    try {
      while (this.next !== null) {
        const job = this.next;
        this.next = null;
        await this.run(job, () => this.next !== null);
      }
    } finally {
      this.running = false;
    }
    this.onIdle();
  }
}

export class Live {
  private seq = 0;
  private timer: ReturnType<typeof setTimeout> | undefined;
  private structureTimer: ReturnType<typeof setTimeout> | undefined;
  private lastFullMs = Infinity;
  private evaluator: Latest<Job>;
  private structurer: Latest<string>;
  private infoListeners: ((info: EvalInfo) => void)[] = [];
  /** The last evaluation succeeded (the status returns to `ready` only then). */
  private ok = true;
  /** The recent speculations, oldest first. */
  private specs: Speculation[] = [];
  private generation = 0;
  /** The program text as of the last `text` event. */
  private prevText: string;
  /** The newest seq whose maps were shown: an older answer arriving late is not shown. */
  private shownSeq = 0;

  constructor(
    private readonly ctx: Ctx,
    readonly stream = "main",
  ) {
    this.evaluator = new Latest((job, superseded) => this.evaluate(job, superseded), () => this.idle());
    this.structurer = new Latest((text, superseded) => this.structure(text, superseded), () => this.idle());
    const { store } = ctx;
    this.prevText = store.text;
    store.on("text", ({ text, source }) => {
      const before = this.prevText;
      this.prevText = text;
      if (source !== "panel") {
        this.generation += 1; // a speculation made before this change is outdated
        this.specs = [];
      }
      clearTimeout(this.timer);
      this.ctx.store.emit("status", { state: "busy" }); // at once, not after the debounce
      if (source === "editor") this.timer = setTimeout(() => this.kick(true), TYPING_DEBOUNCE_MS);
      else if (source === "panel") {
        // A drag: evaluate at once, refresh the structure only once the drag pauses, so the
        // structure request does not compete with the evaluation for the server's cores.
        const spec = this.specs.filter((s) => s.from === before && s.generation === this.generation).pop();
        this.kick(false, true, spec ?? null);
        clearTimeout(this.structureTimer);
        this.structureTimer = setTimeout(() => this.structurer.push(store.text), PANEL_STRUCTURE_MS);
      } else this.kick(true);
    });
    store.on("layers", () => {
      this.generation += 1; // a speculation was made with the other layers
      this.specs = [];
      this.kick(false);
    });
    store.on("speculate", ({ text, values }) => this.speculate(text, values));
  }

  /** Request the first pass of what /api/set makes of `{text, values}` now, in parallel with
   * the /api/set request; shown only while it is still the program's next or current text. */
  speculate(text: string, values: Record<string, unknown>): void {
    const { api, store } = this.ctx;
    const seq = (this.seq = Math.max(this.seq + 1, Date.now()));
    const spec: Speculation = { from: text, generation: this.generation, sha: null, seq: null, done: Promise.resolve() };
    this.specs = [...this.specs.slice(-3), spec];
    const req = {
      text,
      values,
      size: dragSize(this.lastFullMs),
      stream: `${this.stream}:speculative`,
      seq,
      hidden: [...store.hidden],
      solo: store.solo,
      pass: "preview" as const,
    };
    spec.done = api.maps(req).then(
      (maps) => {
        const sha = maps.header.text_sha ?? null;
        if (this.generation !== spec.generation) return; // typing, undo or a load came since
        if (store.text !== text && (sha === null || store.textSha !== sha)) return;
        spec.sha = sha;
        if (this.show(maps, "preview", req.size, performance.now())) spec.seq = maps.header.seq;
      },
      () => undefined, // superseded by a newer speculation, or the regular passes report it
    );
  }

  onInfo(fn: (info: EvalInfo) => void): void {
    this.infoListeners.push(fn);
  }

  /** Evaluate the current program now (and refresh the structure when `structure`). */
  kick(structure = true, drag = false, spec: Speculation | null = null): void {
    const { store } = this.ctx;
    this.ctx.store.emit("status", { state: "busy" });
    this.evaluator.push({ drag, text: store.text, sha: store.textSha, spec, hidden: [...store.hidden], solo: store.solo });
    if (structure) this.structurer.push(store.text);
  }

  private idle(): void {
    if (!this.evaluator.busy && !this.structurer.busy && this.ok) this.ctx.store.emit("status", { state: "ready" });
  }

  /** Whether the speculative first pass evaluated `job`'s text (waits for it to land). */
  private async speculated(job: Job): Promise<boolean> {
    const spec = job.spec;
    if (!job.drag || job.sha === null || spec === null || spec.generation !== this.generation) return false;
    await spec.done;
    return spec.sha === job.sha && spec.generation === this.generation;
  }

  private show(maps: Maps, pass: "preview" | "full", size: number, t0: number): boolean {
    if (maps.header.seq < this.shownSeq) return false; // a newer answer is already shown
    this.shownSeq = maps.header.seq;
    const roundTripMs = performance.now() - t0;
    if (pass === "full") this.lastFullMs = roundTripMs;
    if (pass === "full") this.ctx.store.maps = maps;
    this.ctx.store.emit("maps", maps);
    for (const fn of this.infoListeners) fn({ pass, size, evalMs: maps.header.eval_ms, roundTripMs });
    return true;
  }

  /** On software GL, wait (bounded) until the frame showing a drag's first pass is presented,
   * so the full pass does not share the CPU with the rasteriser drawing it. */
  private async afterPresented(seq: number | null): Promise<void> {
    const gate = this.ctx.presented;
    if (!gate || seq === null) return;
    await Promise.race([gate(seq), new Promise<void>((r) => setTimeout(r, PRESENT_WAIT_MS))]);
  }

  private async evaluate(job: Job, superseded: () => boolean): Promise<void> {
    const speculated = await this.speculated(job);
    const skipPreview = (this.lastFullMs < FAST_FULL_MS && !job.drag) || speculated;
    const passes: ("preview" | "full")[] = skipPreview ? ["full"] : ["preview", "full"];
    let firstSeq = speculated && job.spec ? job.spec.seq : null;
    for (const pass of passes) {
      if (pass === "full" && job.drag) {
        await this.afterPresented(firstSeq);
        if (superseded()) return; // the drag went on: its next step's first pass comes first
      }
      if (pass === "full" && passes.length > 1 && superseded()) return; // a newer program waits
      const size = pass === "full" ? FULL_SIZE : job.drag ? dragSize(this.lastFullMs) : previewSize(this.lastFullMs);
      // Increasing across page loads too: the server keeps each stream's newest seq and answers
      // an older one with 409, so a reload must not start again at 1.
      const seq = (this.seq = Math.max(this.seq + 1, Date.now()));
      const t0 = performance.now();
      let maps: Maps;
      try {
        maps = await this.ctx.api.maps({
          text: job.text,
          size,
          stream: this.stream,
          seq,
          hidden: job.hidden,
          solo: job.solo,
          pass,
        });
      } catch (e) {
        if (e instanceof ApiError && e.status === 409) return; // superseded: normal
        this.ok = false;
        if (!superseded()) this.ctx.store.emit("status", { state: "error", message: oneLine(e) });
        return;
      }
      this.ok = true;
      if (this.show(maps, pass, size, t0) && pass === "preview") firstSeq = maps.header.seq;
    }
  }

  private async structure(text: string, superseded: () => boolean): Promise<void> {
    try {
      const s = await this.ctx.api.json<Structure>("/api/structure", { text });
      if (superseded() || text !== this.ctx.store.text) return;
      this.ctx.store.structure = s;
      this.ctx.store.emit("structure", s);
    } catch {
      /* a program that does not check has no structure; the diagnostics say why */
    }
  }
}

function oneLine(e: unknown): string {
  const msg = e instanceof Error ? e.message : String(e);
  return msg.split("\n")[0].slice(0, 200) || "evaluation failed";
}
