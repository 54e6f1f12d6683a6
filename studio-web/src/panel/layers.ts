// Layer cards' controls: show/hide and solo (UI only: the evaluation honours them), reorder
// (buttons and drag), duplicate and delete (POST /api/layers; undo through the history).
import type { Ctx } from "../ctx";
import { h, iconButton } from "./dom";
import type { Sender } from "./sender";

export type LayerOp = "move" | "duplicate" | "delete";

/** Where layer `x` (1-based) ends up after an operation on layer `i` among `n` (null: gone). */
export function remapIndex(x: number, op: LayerOp, i: number, n: number, to?: number): number | null {
  if (op === "delete") return x === i ? null : x > i ? x - 1 : x;
  if (op === "duplicate") return x > i ? x + 1 : x; // the copy sits right after the original
  const order = Array.from({ length: n }, (_, k) => k + 1);
  order.splice(i - 1, 1);
  order.splice((to ?? i) - 1, 0, i);
  return order.indexOf(x) + 1;
}

export class LayerControls {
  constructor(
    private readonly ctx: Ctx,
    private readonly sender: Sender,
    private readonly toast: (text: string, undo: boolean) => void,
  ) {}

  private count(): number {
    return this.ctx.store.structure?.layers.length ?? 0;
  }

  toggleHidden(index: number): void {
    const { store } = this.ctx;
    const hidden = store.hidden.includes(index) ? store.hidden.filter((x) => x !== index) : [...store.hidden, index].sort((a, b) => a - b);
    store.setLayers(hidden, store.solo);
  }

  toggleSolo(index: number): void {
    const { store } = this.ctx;
    store.setLayers(store.hidden, store.solo === index ? null : index);
  }

  /** Run a layer operation on the server, keep hide/solo on the same layers, commit one version. */
  op(op: LayerOp, index: number, to?: number): void {
    const n = this.count();
    if (op === "move" && (to === undefined || to === index || to < 1 || to > n)) return;
    void this.sender.run(async () => {
      const { api, store, history } = this.ctx;
      const body: Record<string, unknown> = { text: store.text, op, index };
      if (to !== undefined) body.to = to;
      const r = await api.json<{ text: string }>("/api/layers", body);
      const map = (x: number): number | null => remapIndex(x, op, index, n, to);
      const hidden = store.hidden.map(map).filter((x): x is number => x !== null);
      const solo = store.solo === null ? null : map(store.solo);
      if (JSON.stringify(hidden) !== JSON.stringify(store.hidden) || solo !== store.solo) store.setLayers(hidden, solo);
      store.setText(r.text, "panel");
      const what = op === "move" ? `move layer ${index} to ${to}` : `${op} layer ${index}`;
      history.commit(what);
      if (op === "delete") this.toast(`Deleted layer ${index}`, true);
    });
  }

  /** The header buttons of layer `index`. */
  buttons(index: number): { eye: HTMLButtonElement; solo: HTMLButtonElement; el: HTMLElement } {
    const eye = iconButton("◉", `Show/hide layer ${index} (view only)`, "pn-eye", () => this.toggleHidden(index));
    eye.dataset.testid = `layer-eye-${index}`;
    const solo = iconButton("S", `Solo layer ${index} (view only)`, "pn-solo", () => this.toggleSolo(index));
    solo.dataset.testid = `layer-solo-${index}`;
    const up = iconButton("↑", "Move up (earlier in the program, lower in the stack)", "pn-up", () => this.op("move", index, index - 1));
    up.dataset.testid = `layer-up-${index}`;
    up.disabled = index <= 1;
    const down = iconButton("↓", "Move down (later in the program, higher in the stack)", "pn-down", () => this.op("move", index, index + 1));
    down.dataset.testid = `layer-down-${index}`;
    down.disabled = index >= this.count();
    const dup = iconButton("⊕", `Duplicate layer ${index}`, "pn-dup", () => this.op("duplicate", index));
    dup.dataset.testid = `layer-dup-${index}`;
    const del = iconButton("✕", `Delete layer ${index} (undo restores it)`, "pn-del", () => this.op("delete", index));
    del.dataset.testid = `layer-delete-${index}`;
    del.disabled = this.count() <= 1;
    return { eye, solo, el: h("span", { class: "pn-lbtns" }, eye, solo, up, down, dup, del) };
  }

  /** Make a layer card draggable by its handle; dropping on another card moves the layer there. */
  dragAndDrop(card: HTMLElement, handle: HTMLElement, index: number): void {
    const MIME = "application/x-matloom-layer";
    handle.draggable = true;
    handle.addEventListener("dragstart", (e) => {
      e.dataTransfer?.setData(MIME, String(index));
      if (e.dataTransfer) e.dataTransfer.effectAllowed = "move";
      card.classList.add("pn-dragging");
    });
    handle.addEventListener("dragend", () => card.classList.remove("pn-dragging"));
    const clear = (): void => card.classList.remove("pn-drop-before", "pn-drop-after");
    const before = (e: DragEvent): boolean => {
      const r = card.getBoundingClientRect();
      return e.clientY < r.top + r.height / 2;
    };
    card.addEventListener("dragover", (e) => {
      if (!e.dataTransfer?.types.includes(MIME)) return;
      e.preventDefault();
      const b = before(e);
      card.classList.toggle("pn-drop-before", b);
      card.classList.toggle("pn-drop-after", !b);
    });
    card.addEventListener("dragleave", clear);
    card.addEventListener("drop", (e) => {
      clear();
      const s = Number(e.dataTransfer?.getData(MIME));
      if (!s) return;
      e.preventDefault();
      const t = index;
      const to = before(e) ? (s < t ? t - 1 : t) : s < t ? t : t + 1;
      if (to !== s) this.op("move", s, to);
    });
  }
}
