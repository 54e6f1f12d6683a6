// Completion: functions (with their one-line summary), the keyword arguments of the enclosing
// call, Define'd names, constants and statements, and layer methods after a `.`; filtered by
// the typed prefix (the editor's autocompletion runs with `filterStrict`: prefix matches only).
import type { Completion, CompletionContext, CompletionResult } from "@codemirror/autocomplete";
import type { EditorView } from "@codemirror/view";
import { innermostCall, scanTo, type CallFrame } from "./scan";
import { defineNames, formatDefault, rangeText, signatureParts, type Vocab } from "./vocab";

/** Insert `name()` with the cursor inside, unless a `(` already follows. */
function callApply(name: string) {
  return (view: EditorView, _c: Completion, from: number, to: number): void => {
    const next = view.state.sliceDoc(to, to + 1);
    const insert = next === "(" ? name : `${name}()`;
    view.dispatch({
      changes: { from, to, insert },
      selection: { anchor: from + name.length + (next === "(" ? 0 : 1) },
      userEvent: "input.complete",
    });
  };
}

function infoText(...lines: (string | null | undefined | false)[]): () => Node {
  return () => {
    const el = document.createElement("div");
    el.className = "ml-info";
    for (const l of lines) {
      if (!l) continue;
      const p = document.createElement("div");
      p.textContent = l;
      el.appendChild(p);
    }
    return el;
  };
}

function startsWith(label: string, prefix: string): boolean {
  return label.toLowerCase().startsWith(prefix.toLowerCase());
}

export function matloomCompletion(vocab: Vocab) {
  return (context: CompletionContext): CompletionResult | null => {
    const { state, pos } = context;
    const text = state.doc.toString();
    const scan = scanTo(text, pos);
    if (scan.inCommentOrString) return choiceCompletion(vocab, context, scan.stack);

    // Layer methods after a dot.
    const dot = context.matchBefore(/\.[A-Za-z_]\w*$|\.$/);
    if (dot && !/\d$/.test(state.sliceDoc(Math.max(0, dot.from - 1), dot.from))) {
      const prefix = dot.text.slice(1);
      const options: Completion[] = [];
      for (const c of vocab.channels.values()) {
        if (!startsWith(c.name, prefix)) continue;
        const range = rangeText(c);
        options.push({
          label: c.name,
          type: "method",
          detail: `(${c.args.join(", ")})`,
          info: infoText(c.doc, range && `range ${range}`),
          apply: callApply(c.name),
        });
      }
      return { from: dot.from + 1, options, validFor: /^\w*$/ };
    }

    const choices = choiceCompletion(vocab, context, scan.stack);
    if (choices) return choices;
    const word = context.matchBefore(/[A-Za-z_][\w]*$/);
    if (!word && !context.explicit) return null;
    const from = word ? word.from : pos;
    const prefix = word ? word.text : "";
    if (!prefix && !context.explicit) return null;
    if (word && /[\d.]/.test(state.sliceDoc(Math.max(0, from - 1), from))) return null;

    const options: Completion[] = [];
    const call = innermostCall(scan.stack);
    // Keyword arguments of the enclosing call, when at the start of an argument.
    if (call && !call.method) {
      const before = state.sliceDoc(call.argStart, from);
      const params = vocab.paramsOf(call.name ?? "", false);
      if (params && call.kw === null && /^\s*$/.test(before)) {
        for (const p of params) {
          if (call.given.includes(p.name) || !startsWith(p.name, prefix)) continue;
          const range = rangeText(p);
          const dflt = formatDefault(p.default, p.default_text);
          options.push({
            label: `${p.name}=`,
            type: "property",
            detail: [p.type, dflt && `= ${dflt}`].filter(Boolean).join(" "),
            info: infoText(p.doc, range && `range ${range}`),
            boost: 50,
          });
        }
      }
    }
    for (const f of vocab.functions.values()) {
      if (!startsWith(f.name, prefix)) continue;
      options.push({
        label: f.name,
        type: "function",
        detail: f.summary ? f.summary.split("\n")[0].slice(0, 80) : undefined,
        info: infoText(`${f.name}(${signatureParts(f.name, f.params, false).join(", ")})`, f.summary),
        apply: callApply(f.name),
      });
    }
    const defs = defineNames(text);
    for (const [name, at] of defs) {
      if (!startsWith(name, prefix) || (at <= pos && pos <= at + name.length)) continue;
      options.push({ label: name, type: "variable", detail: "Define", boost: 20 });
    }
    for (const [name, value] of vocab.constants) {
      if (startsWith(name, prefix)) options.push({ label: name, type: "constant", detail: String(value) });
    }
    for (const name of vocab.literals) {
      if (startsWith(name, prefix)) options.push({ label: name, type: "constant" });
    }
    const topLevel = scan.stack.length === 0;
    for (const k of vocab.keywords) {
      if (!startsWith(k, prefix)) continue;
      const statement = k !== "Layer";
      if (statement !== topLevel) continue;
      options.push({
        label: k,
        type: "keyword",
        info: infoText(vocab.statementDoc(k)),
        apply: callApply(k),
        boost: 10,
      });
    }
    if (!options.length) return null;
    return { from, options, validFor: /^\w*$/ };
  };
}

/** The choices of a string parameter (`output="mask"`), right after `=` or inside the quotes. */
function choiceCompletion(vocab: Vocab, context: CompletionContext, stack: CallFrame[]): CompletionResult | null {
  const m = context.matchBefore(/([A-Za-z_]\w*)\s*=\s*(["']?)(\w*)$/);
  const call = innermostCall(stack);
  if (!m || !call?.name) return null;
  const [, kw, quote, typed] = /([A-Za-z_]\w*)\s*=\s*(["']?)(\w*)$/.exec(m.text) ?? [];
  const p = vocab.paramsOf(call.name, call.method)?.find((q) => q.name === kw);
  if (!p?.choices?.length || (!quote && !typed && !context.explicit && !/=$/.test(m.text))) return null;
  const from = context.pos - typed.length - quote.length;
  const q = quote || '"';
  const options: Completion[] = p.choices.filter((c) => startsWith(c, typed)).map((c) => ({
    label: `${q}${c}${q}`,
    type: "enum",
    detail: c === formatDefault(p.default) ? "default" : undefined,
    apply: (view: EditorView, _c: Completion, f: number, t: number) => {
      const closing = view.state.sliceDoc(t, t + 1) === q ? 1 : 0;
      view.dispatch({ changes: { from: f, to: t + closing, insert: `${q}${c}${q}` }, userEvent: "input.complete" });
    },
  }));
  return options.length ? { from, options, filter: false } : null;
}
