// Sends the panel's edits to the server: one request in flight plus the latest values (a drag
// never queues), then one history commit per gesture. Discrete edits (layers, seeds) wait
// their turn behind a running drag.
import { ApiError } from "../api";
import type { Ctx } from "../ctx";

export type Value = number | number[];

/** A one-line report for the panel's message line. */
export type Report = (message: string, kind: "error" | "warning" | "info") => void;

function message(e: unknown): string {
  if (e instanceof ApiError) return e.message || `request failed (${e.status})`;
  return e instanceof Error ? e.message : String(e);
}

export class Sender {
  private pending: Record<string, Value> | null = null;
  private sending: Record<string, Value> | null = null;
  private commitLabel: string | null = null;
  private running: Promise<void> = Promise.resolve();
  private pumping = false;
  /** Bumped by every text change that is not the panel's (typing, undo/redo, a load): a reply
   *  or a value from before it must not land on the text after it, even an equal one (undo can
   *  restore exactly the text a drag's first request was sent with). */
  private generation = 0;

  constructor(
    private readonly ctx: Ctx,
    private readonly report: Report,
  ) {
    ctx.store.on("text", ({ source }) => {
      if (source === "panel") return;
      this.generation += 1;
      this.pending = null; // values of a gesture the user has just undone or typed over
      this.commitLabel = null; // nor a history version for it
    });
  }

  /** Whether a value for `address` is waiting or in flight (its row keeps its own value). */
  holds(address: string): boolean {
    return (this.pending !== null && address in this.pending) || (this.sending !== null && address in this.sending);
  }

  /** Set values (replacing any not yet sent for the same addresses). */
  set(values: Record<string, Value>): void {
    this.pending = { ...(this.pending ?? {}), ...values };
    if (!this.pumping) this.running = this.pump();
  }

  /** End a gesture: one history version once every value of it has landed. */
  commit(label: string): void {
    if (this.pumping) this.commitLabel = label;
    else this.ctx.history.commit(label);
  }

  /** Run a discrete edit after the current drag's requests; errors are reported. */
  run(job: () => Promise<void>): Promise<void> {
    const next = this.running.then(async () => {
      try {
        await job();
      } catch (e) {
        this.report(message(e), "error");
      }
    });
    this.running = next;
    return next;
  }

  private async pump(): Promise<void> {
    this.pumping = true;
    const { api, store } = this.ctx;
    try {
      while (this.pending !== null) {
        const values = this.pending;
        this.pending = null;
        this.sending = values;
        const sent = store.text;
        const generation = this.generation;
        try {
          const reply = api.json<{ text: string; warnings?: string[]; text_sha?: string }>("/api/set", {
            text: sent,
            values,
          });
          store.emit("speculate", { text: sent, values }); // Live evaluates the result meanwhile
          const r = await reply;
          // Someone else changed the program meanwhile (typing, undo): their text wins.
          if (store.text === sent && this.generation === generation) store.setText(r.text, "panel", r.text_sha ?? null);
          if (r.warnings && r.warnings.length) this.report(r.warnings.join("; "), "warning");
          else this.report("", "info");
        } catch (e) {
          this.report(message(e), "error");
        } finally {
          this.sending = null;
        }
      }
    } finally {
      this.pumping = false;
    }
    if (this.commitLabel !== null) {
      const label = this.commitLabel;
      this.commitLabel = null;
      this.ctx.history.commit(label);
    }
  }
}
