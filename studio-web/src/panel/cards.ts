// A card's DOM: header (title, source line, layer buttons), the source text, its rows.
import type { Structure } from "../store";
import { h, iconButton, setText } from "./dom";
import type { LayerControls } from "./layers";
import type { CardSpec } from "./model";
import { fmtMetres, fmtNumber } from "./ranges";
import { ColourRow, NumberRow, type Row, type RowEnv } from "./rows";
import { AutoSeedRow, writtenSeedRow, type SeedOps } from "./seeds";

export interface CardEnv {
  rows: RowEnv;
  seeds: SeedOps;
  layers: LayerControls;
  collapsed: Set<string>;
}

function viewFacts(v: Structure["view"]): string[] {
  const w = v.x2 - v.x1;
  const ht = v.y2 - v.y1;
  const out = [`x ${fmtNumber(v.x1)} → ${fmtNumber(v.x2)}`, `y ${fmtNumber(v.y1)} → ${fmtNumber(v.y2)}`, `${fmtNumber(w)} × ${fmtNumber(ht)} units`];
  if (v.unit_m !== null && v.unit_m > 0) out.push(`1 unit = ${fmtMetres(v.unit_m)} (${fmtMetres(w * v.unit_m)} across)`);
  else out.push("scale not set");
  out.push(v.tileable ? "tileable" : "not tileable");
  return out;
}

export class CardView {
  readonly el: HTMLElement;
  private readonly title: HTMLElement;
  private readonly line: HTMLElement;
  private readonly text: HTMLElement;
  private readonly facts: HTMLElement;
  readonly rows = new Map<string, Row>();
  private readonly autoRows = new Map<string, AutoSeedRow>();
  private eye: HTMLButtonElement | null = null;
  private solo: HTMLButtonElement | null = null;

  constructor(
    public spec: CardSpec,
    view: Structure["view"],
    private readonly env: CardEnv,
  ) {
    const s = spec;
    const caret = iconButton("▾", "Collapse/expand", "pn-caret", () => this.toggle());
    const badge = h("span", { class: `pn-badge pn-badge-${s.kind}` }, s.kind === "layer" ? `L${s.index}` : s.kind === "define" ? "D" : s.kind === "view" ? "V" : "·");
    this.title = h("span", { class: "pn-title", title: s.title }, s.title);
    this.line = h("span", { class: "pn-line" }, s.line ? `:${s.line}` : "");
    const header = h("div", { class: "pn-card-head" }, caret, badge, this.title, this.line);
    this.text = h("div", { class: "pn-src", title: s.text }, s.text);
    this.facts = h("div", { class: "pn-facts" });
    const body = h("div", { class: "pn-body" }, s.text ? this.text : null, s.kind === "view" ? this.facts : null);
    this.el = h("section", { class: `pn-card pn-card-${s.kind}`, "data-card": s.key, "data-testid": `card-${s.key}` }, header, body);
    if (s.kind === "layer") {
      const handle = h("span", { class: "pn-handle", title: "Drag to reorder" }, "⠿");
      header.prepend(handle);
      const b = env.layers.buttons(s.index);
      this.eye = b.eye;
      this.solo = b.solo;
      header.append(b.el);
      env.layers.dragAndDrop(this.el, handle, s.index);
    }
    header.addEventListener("dblclick", (e) => {
      if ((e.target as HTMLElement).closest("button")) return;
      this.toggle();
    });
    for (const p of s.params) {
      const row =
        p.kind === "colour" && Array.isArray(p.value)
          ? new ColourRow(p, env.rows, s.prefix)
          : p.kind === "seed"
            ? writtenSeedRow(p, env.rows, s.prefix, env.seeds)
            : new NumberRow(p, env.rows, s.prefix);
      this.rows.set(p.address, row);
      body.append(row.el);
    }
    for (const seed of s.autoSeeds) {
      const row = new AutoSeedRow(seed, s.prefix, env.seeds);
      this.autoRows.set(seed.address, row);
      body.append(row.el);
    }
    if (!s.params.length && !s.autoSeeds.length && s.kind !== "view") {
      this.el.classList.add("pn-card-empty");
      this.text.title = `${s.text}\n(no literal to edit)`;
    }
    this.el.classList.toggle("pn-collapsed", env.collapsed.has(s.key));
    this.updateView(view);
  }

  private toggle(): void {
    const c = this.el.classList.toggle("pn-collapsed");
    if (c) this.env.collapsed.add(this.spec.key);
    else this.env.collapsed.delete(this.spec.key);
  }

  private updateView(view: Structure["view"]): void {
    if (this.spec.kind !== "view") return;
    this.facts.replaceChildren(...viewFacts(view).map((f) => h("span", { class: "pn-fact" }, f)));
  }

  /** Take a refreshed spec with the same addresses: texts and values in place. */
  update(spec: CardSpec, view: Structure["view"]): void {
    this.spec = spec;
    setText(this.title, spec.title);
    this.title.title = spec.title;
    setText(this.line, spec.line ? `:${spec.line}` : "");
    setText(this.text, spec.text);
    this.text.title = spec.text;
    for (const p of spec.params) this.rows.get(p.address)?.update(p);
    for (const s of spec.autoSeeds) this.autoRows.get(s.address)?.updateSeed(s);
    this.updateView(view);
  }

  /** Reflect the view-only layer state (hidden, solo). */
  showLayerState(hidden: number[], solo: number | null): void {
    if (this.spec.kind !== "layer") return;
    const i = this.spec.index;
    const off = hidden.includes(i) || (solo !== null && solo !== i);
    this.el.classList.toggle("pn-hidden", off);
    this.eye?.classList.toggle("pn-on", !hidden.includes(i));
    if (this.eye) this.eye.textContent = hidden.includes(i) ? "○" : "◉";
    this.solo?.classList.toggle("pn-on", solo === i);
  }

  /** Hide the rows that do not match the filter; returns whether anything shows. */
  filter(q: string): boolean {
    const all = [...this.rows.values(), ...this.autoRows.values()];
    const titleHit = q === "" || this.spec.title.toLowerCase().includes(q) || this.spec.key.toLowerCase().includes(q);
    let any = titleHit;
    for (const r of all) {
      const show = titleHit || r.matches(q);
      r.el.hidden = !show;
      any ||= show;
    }
    this.el.hidden = !any;
    return any;
  }
}
