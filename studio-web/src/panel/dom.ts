// Tiny DOM helpers for the panel (no framework).

type Attr = string | number | boolean | null | undefined;
type Child = Node | string | null | undefined | false;

/** Create an element: `h("div", {class: "pn-card", "data-testid": "x"}, child, ...)`. */
export function h<K extends keyof HTMLElementTagNameMap>(
  tag: K,
  attrs: Record<string, Attr> = {},
  ...children: Child[]
): HTMLElementTagNameMap[K] {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === null || v === undefined || v === false) continue;
    el.setAttribute(k, v === true ? "" : String(v));
  }
  for (const c of children) if (c !== null && c !== undefined && c !== false) el.append(c);
  return el;
}

/** A small icon button with a tooltip (the title doubles as the accessible name). */
export function iconButton(icon: string, title: string, cls = "", onClick?: (e: MouseEvent) => void): HTMLButtonElement {
  const b = h("button", { type: "button", class: `pn-ib ${cls}`.trim(), title, "aria-label": title }, icon);
  if (onClick) b.addEventListener("click", onClick);
  return b;
}

/** Set an input's value only when it differs (keeps the caret and avoids needless events). */
export function setValue(input: HTMLInputElement, value: string): void {
  if (input.value !== value) input.value = value;
}

/** Set text only when it differs. */
export function setText(el: HTMLElement, text: string): void {
  if (el.textContent !== text) el.textContent = text;
}
