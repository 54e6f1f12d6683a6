// Signature help: while the cursor is inside a call, a tooltip above the call shows its
// parameters with the active one highlighted, and that parameter's doc and range.
import { StateField, type EditorState, type Transaction } from "@codemirror/state";
import { showTooltip, type Tooltip } from "@codemirror/view";
import { innermostCall, scanTo } from "./scan";
import { rangeText, signatureParts, type Vocab } from "./vocab";

function el(tag: string, cls: string, text?: string): HTMLElement {
  const e = document.createElement(tag);
  e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
}

interface Help {
  tooltip: Tooltip;
  key: string;
}

function compute(state: EditorState, vocab: Vocab): Help | null {
  const sel = state.selection.main;
  if (!sel.empty) return null;
  const scan = scanTo(state.doc.toString(), sel.head);
  if (scan.inCommentOrString) return null;
  const call = innermostCall(scan.stack);
  if (!call || call.name === null) return null;
  const params = vocab.paramsOf(call.name, call.method);
  if (!params || !params.length) return null;
  let active = call.kw !== null ? params.findIndex((p) => p.name === call.kw) : call.argIndex;
  if (active >= params.length) active = -1;
  const parts = signatureParts(call.name, params, call.method);
  const name = call.name;
  const method = call.method;
  const tooltip: Tooltip = {
    pos: call.open,
    above: true,
    strictSide: false,
    arrow: false,
    create: () => {
      const dom = el("div", "ml-signature");
      const sig = el("div", "ml-sig-line");
      sig.appendChild(el("span", "ml-sig-name", (method ? "." : "") + name + "("));
      parts.forEach((p, k) => {
        if (k) sig.appendChild(document.createTextNode(", "));
        sig.appendChild(el("span", k === active ? "ml-sig-param ml-sig-active" : "ml-sig-param", p));
      });
      sig.appendChild(document.createTextNode(")"));
      dom.appendChild(sig);
      const p = active >= 0 ? params[active] : null;
      if (p) {
        const range = rangeText(p);
        const doc = el("div", "ml-sig-doc");
        doc.appendChild(el("b", "", p.name));
        doc.appendChild(document.createTextNode(` — ${p.doc ?? ""}${range ? `  (${range})` : ""}`));
        dom.appendChild(doc);
      } else {
        const f = method ? vocab.channels.get(name)?.doc : vocab.functions.get(name)?.summary;
        if (f) dom.appendChild(el("div", "ml-sig-doc", f));
      }
      return { dom };
    },
  };
  return { tooltip, key: `${call.open}:${name}:${active}` };
}

function userMoved(tr: Transaction): boolean {
  return ["input", "delete", "select", "undo", "redo"].some((e) => tr.isUserEvent(e));
}

/** The signature-help tooltip; shown after the user types or moves, hidden on other changes. */
export function signatureHelp(vocab: Vocab) {
  return StateField.define<Help | null>({
    create: () => null,
    update(value, tr) {
      if (!tr.docChanged && !tr.selection) return value;
      if (!userMoved(tr)) return null;
      const next = compute(tr.state, vocab);
      return value && next && value.key === next.key ? value : next;
    },
    provide: (f) => showTooltip.from(f, (v) => v?.tooltip ?? null),
  });
}
