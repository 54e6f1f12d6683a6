// Tiny DOM helpers shared by the inspector and the dialogs (no framework).

type Attrs = Record<string, string | number | boolean | null | undefined>;
type Child = Node | string | null | undefined | false;

/** Create an element: `h("div", {class: "x", "data-testid": "y"}, child, ...)`. */
export function h<K extends keyof HTMLElementTagNameMap>(
  tag: K,
  attrs: Attrs = {},
  ...children: Child[]
): HTMLElementTagNameMap[K] {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === null || v === undefined || v === false) continue;
    if (k === "text") el.textContent = String(v);
    else if (v === true) el.setAttribute(k, "");
    else el.setAttribute(k, String(v));
  }
  for (const c of children) if (c !== null && c !== undefined && c !== false) el.append(c);
  return el;
}

/** Add a <style> element once per id (each module injects its own CSS). */
export function injectStyle(id: string, css: string): void {
  if (document.getElementById(id)) return;
  const style = document.createElement("style");
  style.id = id;
  style.textContent = css;
  document.head.append(style);
}

/** A labelled control in a dense form row. */
export function field(label: string, control: HTMLElement, cls = "ins-field"): HTMLLabelElement {
  return h("label", { class: cls }, h("span", { text: label }), control);
}

/** Options for a <select>: [value, label] pairs. */
export function select(options: [string, string][], value?: string, attrs: Attrs = {}): HTMLSelectElement {
  const s = h("select", attrs);
  setOptions(s, options, value);
  return s;
}

export function setOptions(s: HTMLSelectElement, options: [string, string][], value?: string): void {
  s.replaceChildren(...options.map(([v, l]) => h("option", { value: v, text: l })));
  if (value !== undefined && options.some(([v]) => v === value)) s.value = value;
}

/** True while the element is laid out (its tab is shown). */
export function isShown(el: HTMLElement): boolean {
  return el.isConnected && el.getClientRects().length > 0;
}

/** Call `fn` whenever `el` becomes visible (a tab switched to it). */
export function onShown(el: HTMLElement, fn: () => void): void {
  if (typeof IntersectionObserver === "undefined") return;
  new IntersectionObserver((entries) => {
    if (entries.some((e) => e.isIntersecting)) fn();
  }).observe(el);
}

/** Format a number compactly (up to `digits` significant digits, no trailing noise). */
export function fmt(v: number, digits = 4): string {
  if (!Number.isFinite(v)) return String(v);
  if (v === 0) return "0";
  const a = Math.abs(v);
  if (a >= 1e5 || a < 1e-4) return v.toExponential(digits - 1);
  return String(Number(v.toPrecision(digits)));
}

/** A one-line message from anything thrown. */
export function errorText(err: unknown): string {
  if (err instanceof Error) return err.message;
  return String(err);
}

let lastSeq = 0;

/** A request number for a stream, increasing across page loads too: the server remembers the
 * newest `seq` of each stream and refuses older ones (409), so a reload must not restart at 1. */
export function nextSeq(): number {
  lastSeq = Math.max(lastSeq + 1, Date.now());
  return lastSeq;
}
