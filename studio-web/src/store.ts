// The one state object of the page and its tiny event bus.
import type { Maps } from "./api";

export interface Diagnostic {
  code: string;
  severity: "error" | "warning";
  message: string;
  line: number;
  col: number;
  end_line: number;
  end_col: number;
  from: number;
  to: number;
  hint?: string | null;
  expected?: string | null;
}

export interface Param {
  address: string;
  value: number | number[];
  kind: string;
  low: number | null;
  high: number | null;
  unit: string | null;
  label: string;
  affects: string[];
  line: number;
  col: number;
  metres?: number | null;
}

export interface Structure {
  params: Param[];
  view: { x1: number; y1: number; x2: number; y2: number; tileable: boolean; unit_m: number | null };
  defines: { name: string; line: number; text: string; params: string[] }[];
  layers: { index: number; line: number; text: string; label: string; params: string[] }[];
  seeds: { address: string; value: number; auto: boolean; label: string }[];
}

/** Where a program change came from: the text editor, the panel, undo/redo, the author box. */
export type Source = "editor" | "panel" | "history" | "author" | "load";

export interface Events {
  text: { text: string; source: Source };
  /** The panel sent `values` for `text` to /api/set: Live may evaluate the result at once. */
  speculate: { text: string; values: Record<string, unknown> };
  maps: Maps;
  structure: Structure;
  diagnostics: Diagnostic[];
  status: { state: "ready" | "busy" | "error"; message?: string };
  layers: { hidden: number[]; solo: number | null };
}

type Handler<T> = (value: T) => void;

export class Store {
  text = "";
  /** The server's `text_sha` of `text` when the panel's /api/set reply set it, else null. */
  textSha: string | null = null;
  path: string | null = null;
  maps: Maps | null = null;
  structure: Structure | null = null;
  diagnostics: Diagnostic[] = [];
  hidden: number[] = [];
  solo: number | null = null;
  private handlers: { [K in keyof Events]?: Handler<Events[K]>[] } = {};

  on<K extends keyof Events>(event: K, fn: Handler<Events[K]>): () => void {
    const list = (this.handlers[event] ??= []) as Handler<Events[K]>[];
    list.push(fn);
    return () => list.splice(list.indexOf(fn), 1);
  }

  emit<K extends keyof Events>(event: K, value: Events[K]): void {
    for (const fn of [...((this.handlers[event] ?? []) as Handler<Events[K]>[])]) fn(value);
  }

  /** Change the program text (every part calls this; the others follow the `text` event). */
  setText(text: string, source: Source, sha: string | null = null): void {
    if (text === this.text) return;
    this.text = text;
    this.textSha = sha;
    this.emit("text", { text, source });
  }

  setLayers(hidden: number[], solo: number | null): void {
    this.hidden = hidden;
    this.solo = solo;
    this.emit("layers", { hidden, solo });
  }
}
