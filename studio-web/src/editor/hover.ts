// Hover docs: functions (signature and summary), keyword arguments (doc and range), layer
// methods, Define'd names (their definition), constants and statements.
import { hoverTooltip, type EditorView, type Tooltip } from "@codemirror/view";
import { innermostCall, scanTo } from "./scan";
import { defineNames, formatDefault, rangeText, signatureParts, type Vocab } from "./vocab";

function box(title: string, ...lines: (string | null | undefined | false)[]): HTMLElement {
  const dom = document.createElement("div");
  dom.className = "ml-hover";
  const h = document.createElement("div");
  h.className = "ml-hover-title";
  h.textContent = title;
  dom.appendChild(h);
  for (const l of lines) {
    if (!l) continue;
    const p = document.createElement("div");
    p.textContent = l;
    dom.appendChild(p);
  }
  return dom;
}

export function describe(vocab: Vocab, text: string, from: number, to: number): HTMLElement | null {
  const word = text.slice(from, to);
  if (scanTo(text, from).inCommentOrString) return null;
  if (text[from - 1] === ".") {
    const c = vocab.channels.get(word);
    if (!c) return null;
    const range = rangeText(c);
    return box(`.${c.name}(${c.args.join(", ")})`, c.doc, range && `range ${range}`);
  }
  if (/^\s*=(?!=)/.test(text.slice(to, to + 20))) {
    const call = innermostCall(scanTo(text, from).stack);
    const params = call?.name ? vocab.paramsOf(call.name, call.method) : null;
    const p = params?.find((q) => q.name === word);
    if (p && call?.name) {
      const range = rangeText(p);
      const dflt = formatDefault(p.default, p.default_text);
      return box(
        `${call.name}(${p.name}${p.required ? "" : dflt ? `=${dflt}` : ""})`,
        p.doc,
        [p.type, range && `range ${range}`, p.required && "required"].filter(Boolean).join(" · "),
      );
    }
  }
  const f = vocab.functions.get(word);
  if (f) {
    const sig = f.signature ?? `${f.name}(${signatureParts(f.name, f.params, false).join(", ")})`;
    return box(sig, f.doc ?? f.summary, f.returns && `returns ${f.returns}`, f.example && `e.g. ${f.example}`);
  }
  const statement = vocab.statementDoc(word);
  if (statement) return box(word, statement);
  if (vocab.constants.has(word)) return box(word, `constant = ${String(vocab.constants.get(word))}`);
  const at = defineNames(text).get(word);
  if (at !== undefined) {
    const lineStart = text.lastIndexOf("\n", at) + 1;
    const lineEnd = text.indexOf("\n", at);
    const line = text.slice(lineStart, lineEnd < 0 ? undefined : lineEnd).trim();
    return box(word, line.length > 200 ? line.slice(0, 200) + "…" : line);
  }
  return null;
}

export function matloomHover(vocab: Vocab) {
  return hoverTooltip((view: EditorView, pos: number, side): Tooltip | null => {
    const word = view.state.wordAt(pos);
    if (!word) return null;
    if ((word.from === pos && side < 0) || (word.to === pos && side > 0)) return null;
    const text = view.state.doc.toString();
    const dom = describe(vocab, text, word.from, word.to);
    if (!dom) return null;
    return { pos: word.from, end: word.to, above: true, create: () => ({ dom }) };
  });
}
