// One row per parameter: a labelled slider with its number box, or a colour picker.
import type { Param } from "../store";
import { h, setText, setValue } from "./dom";
import { fmtNumber, hexToRgb, rgbToHex, roundTo, spanOf, unitText, type Span } from "./ranges";
import type { Sender, Value } from "./sender";
import { affectTags } from "./tags";

/** What a row needs from the panel. */
export interface RowEnv {
  sender: Sender;
  /** Metres per coordinate unit (the View's), when known. */
  unitM(): number | null;
  /** The value each parameter had when the panel first saw it (double-click the label resets). */
  origin: Map<string, Value>;
}

export type { Value } from "./sender";

export interface Row {
  readonly el: HTMLElement;
  readonly param: Param;
  /** Take a refreshed parameter (same address) without rebuilding; a row being edited keeps its value. */
  update(p: Param): void;
  /** Whether the row matches a filter query (lower case). */
  matches(q: string): boolean;
}

/** The label with the card's own name words dropped ("tile mask mortar width" in tileMask -> "mortar width"). */
export function shortLabel(label: string, prefix: string): string {
  if (prefix && label.startsWith(prefix + " ") && label.length > prefix.length + 1) return label.slice(prefix.length + 1);
  return label;
}

function head(p: Param, prefix: string, onReset: () => void): { el: HTMLElement; label: HTMLElement; tags: HTMLElement } {
  const label = h("span", { class: "pn-label", title: `${p.label}\n${p.address}\nline ${p.line}, col ${p.col}\ndouble-click: reset` }, shortLabel(p.label, prefix));
  label.addEventListener("dblclick", onReset);
  const tags = affectTags(p.affects);
  return { el: h("div", { class: "pn-head" }, label, tags), label, tags };
}

export class NumberRow implements Row {
  readonly el: HTMLElement;
  readonly slider: HTMLInputElement;
  readonly box: HTMLInputElement;
  private readonly unit: HTMLElement;
  private readonly label: HTMLElement;
  private tags: HTMLElement;
  private span: Span;
  private dragging = false;
  param: Param;

  constructor(
    p: Param,
    private readonly env: RowEnv,
    private readonly prefix: string,
    extra: HTMLElement[] = [],
  ) {
    this.param = p;
    const v = p.value as number;
    if (!env.origin.has(p.address)) env.origin.set(p.address, v);
    this.span = this.spanFor(v);
    this.slider = h("input", {
      type: "range",
      class: "pn-slider",
      "data-testid": `slider-${p.address}`,
      "data-pn-key": `slider:${p.address}`,
      "aria-label": p.label,
    });
    this.applySpan();
    this.slider.value = String(v);
    this.box = h("input", {
      type: "number",
      class: "pn-num",
      step: "any",
      "data-testid": `value-${p.address}`,
      "data-pn-key": `value:${p.address}`,
      "aria-label": `${p.label} value`,
      value: fmtNumber(v),
    });
    this.unit = h("span", { class: "pn-unit" });
    const hd = head(p, prefix, () => this.reset());
    this.label = hd.label;
    this.tags = hd.tags;
    this.el = h(
      "div",
      { class: `pn-row pn-k-${p.kind}`, "data-address": p.address },
      hd.el,
      h("div", { class: "pn-ctl" }, this.slider, this.box, this.unit, ...extra),
    );
    this.show(v);
    this.slider.addEventListener("input", () => this.onSlide());
    this.slider.addEventListener("change", () => this.onSlideEnd());
    this.slider.addEventListener("pointerdown", () => (this.dragging = true));
    for (const ev of ["pointerup", "pointercancel", "blur"]) this.slider.addEventListener(ev, () => (this.dragging = false));
    this.box.addEventListener("change", () => this.onBox());
    this.box.addEventListener("keydown", (e) => {
      if (e.key === "Escape") {
        this.box.value = fmtNumber(this.param.value as number);
        this.box.blur();
      }
    });
  }

  private spanFor(v: number): Span {
    const s = spanOf(this.param, v);
    // A size or frequency of exactly 0 is usually out of range (open bound): the slider stops one step above.
    const p = this.param;
    if (!s.integer && p.low === 0 && (p.kind === "size" || p.kind === "frequency") && v > 0) s.lo = s.step;
    return s;
  }

  private applySpan(): void {
    this.slider.min = String(this.span.lo);
    this.slider.max = String(this.span.hi);
    this.slider.step = String(this.span.step);
  }

  private show(v: number): void {
    setValue(this.box, fmtNumber(v));
    const u = unitText(this.param, v, this.env.unitM());
    setText(this.unit, u.text);
    this.unit.title = u.title;
  }

  private send(v: number): void {
    this.env.sender.set({ [this.param.address]: v });
  }

  private onSlide(): void {
    this.dragging = true;
    const v = roundTo(Number(this.slider.value), this.span);
    this.show(v);
    this.send(v);
  }

  private onSlideEnd(): void {
    this.dragging = false;
    const v = roundTo(Number(this.slider.value), this.span);
    this.env.sender.commit(`set ${this.param.label} = ${fmtNumber(v)}`);
  }

  private onBox(): void {
    const raw = this.box.value.trim();
    let v = Number(raw);
    if (raw === "" || !Number.isFinite(v)) {
      this.show(this.param.value as number);
      return;
    }
    if (this.span.integer) v = Math.round(v);
    this.setLocal(v);
    this.send(v);
    this.env.sender.commit(`set ${this.param.label} = ${fmtNumber(v)}`);
  }

  private setLocal(v: number): void {
    if (v < this.span.lo || v > this.span.hi) {
      this.span = this.spanFor(v);
      this.applySpan();
    }
    setValue(this.slider, String(v));
    this.show(v);
  }

  private reset(): void {
    const o = this.env.origin.get(this.param.address);
    if (typeof o !== "number" || o === this.param.value) return;
    this.setLocal(o);
    this.send(o);
    this.env.sender.commit(`reset ${this.param.label}`);
  }

  /** Whether the user is editing this row right now (its value must not jump). */
  private busy(): boolean {
    return this.dragging || this.env.sender.holds(this.param.address) || document.activeElement === this.box;
  }

  update(p: Param): void {
    this.param = p;
    this.label.title = `${p.label}\n${p.address}\nline ${p.line}, col ${p.col}\ndouble-click: reset`;
    setText(this.label, shortLabel(p.label, this.prefix));
    const tags = affectTags(p.affects);
    if (tags.title !== this.tags.title) {
      this.tags.replaceWith(tags);
      this.tags = tags;
    }
    if (this.busy()) return;
    this.setLocal(p.value as number);
  }

  matches(q: string): boolean {
    return this.param.label.toLowerCase().includes(q) || this.param.address.toLowerCase().includes(q);
  }
}

export class ColourRow implements Row {
  readonly el: HTMLElement;
  private readonly picker: HTMLInputElement;
  private readonly text: HTMLElement;
  private readonly label: HTMLElement;
  private picking = false;
  param: Param;

  constructor(
    p: Param,
    private readonly env: RowEnv,
    private readonly prefix: string,
  ) {
    this.param = p;
    const rgb = p.value as number[];
    if (!env.origin.has(p.address)) env.origin.set(p.address, [...rgb]);
    this.picker = h("input", {
      type: "color",
      class: "pn-colour",
      "data-testid": `colour-${p.address}`,
      "data-pn-key": `colour:${p.address}`,
      "aria-label": p.label,
      value: rgbToHex(rgb),
    });
    this.text = h("span", { class: "pn-rgb", "data-testid": `value-${p.address}` }, this.rgbText(rgb));
    const hd = head(p, prefix, () => this.reset());
    this.label = hd.label;
    this.el = h(
      "div",
      { class: "pn-row pn-k-colour", "data-address": p.address },
      hd.el,
      h("div", { class: "pn-ctl" }, this.picker, this.text),
    );
    this.picker.addEventListener("input", () => {
      this.picking = true;
      const c = hexToRgb(this.picker.value);
      setText(this.text, this.rgbText(c));
      this.env.sender.set({ [p.address]: c });
    });
    this.picker.addEventListener("change", () => {
      this.picking = false;
      this.env.sender.commit(`set ${this.param.label} = ${this.picker.value}`);
    });
  }

  private rgbText(rgb: number[]): string {
    return `${rgbToHex(rgb)}  ${rgb.map((c) => fmtNumber(Number(c.toFixed(1)))).join(", ")}`;
  }

  private reset(): void {
    const o = this.env.origin.get(this.param.address);
    if (!Array.isArray(o)) return;
    this.picker.value = rgbToHex(o);
    setText(this.text, this.rgbText(o));
    this.env.sender.set({ [this.param.address]: o });
    this.env.sender.commit(`reset ${this.param.label}`);
  }

  update(p: Param): void {
    this.param = p;
    setText(this.label, shortLabel(p.label, this.prefix));
    if (this.picking || this.env.sender.holds(p.address)) return;
    const rgb = p.value as number[];
    setValue(this.picker, rgbToHex(rgb));
    setText(this.text, this.rgbText(rgb));
  }

  matches(q: string): boolean {
    return this.param.label.toLowerCase().includes(q) || this.param.address.toLowerCase().includes(q);
  }
}
