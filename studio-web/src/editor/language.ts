// The MatLoom language mode: a stream tokenizer built at run time from the registry, and the
// highlight colours of the studio's dark theme.
import { HighlightStyle, StreamLanguage, syntaxHighlighting, type StringStream } from "@codemirror/language";
import type { Extension } from "@codemirror/state";
import { tags as t } from "@lezer/highlight";
import type { Vocab } from "./vocab";

interface State {
  /** The previous significant token was a `.`. */
  afterDot: boolean;
  /** 0: nothing; 1: just read `Define`; 2: read `Define(` (the next name is a definition). */
  define: 0 | 1 | 2;
}

export function matloomLanguage(vocab: Vocab): StreamLanguage<State> {
  return StreamLanguage.define<State>({
    name: "matloom",
    startState: () => ({ afterDot: false, define: 0 }),
    copyState: (s) => ({ ...s }),
    token(stream: StringStream, state: State): string | null {
      if (stream.eatSpace()) return null;
      const afterDot = state.afterDot;
      state.afterDot = false;
      const define = state.define;
      state.define = 0;
      if (stream.match(/^#.*/)) return "comment";
      if (stream.match(/^"[^"\n]*"?/) || stream.match(/^'[^'\n]*'?/)) return "string";
      if (stream.match(/^(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d*)?/)) return "number";
      const m = stream.match(/^[A-Za-z_\u00c0-\uffff][\w\u00c0-\uffff]*/) as RegExpMatchArray | null;
      if (m) {
        const word = m[0];
        if (afterDot) return vocab.channels.has(word) ? "propertyName" : "invalid";
        if (define === 2) return "variableName.definition";
        if (word === "Define") {
          state.define = 1;
          return "keyword";
        }
        if (vocab.keywords.has(word)) return "keyword";
        if (vocab.literals.has(word)) return "bool";
        if (vocab.constants.has(word)) return "atom";
        if (stream.match(/^\s*=(?!=)/, false)) return "attributeName";
        if (vocab.functions.has(word)) return "variableName.function";
        return "variableName";
      }
      const c = stream.next() ?? "";
      if (c === ".") {
        state.afterDot = true;
        return "punctuation";
      }
      if (c === "(") {
        if (define === 1) state.define = 2;
        return "paren";
      }
      if (c === ")") return "paren";
      if (c === ",") return "separator";
      if ("+-*/=".includes(c)) {
        if (c === "*") stream.eat("*");
        return "operator";
      }
      return "invalid";
    },
    languageData: {
      commentTokens: { line: "#" },
      closeBrackets: { brackets: ["(", '"'] },
    },
  });
}

export const matloomHighlight: Extension = syntaxHighlighting(
  HighlightStyle.define([
    { tag: t.comment, color: "#6a7686", fontStyle: "italic" },
    { tag: t.string, color: "#c3e88d" },
    { tag: t.number, color: "#f5a97f" },
    { tag: t.keyword, color: "#c792ea", fontWeight: "600" },
    { tag: [t.bool, t.atom], color: "#ff9cac" },
    { tag: t.function(t.variableName), color: "#82aaff" },
    { tag: t.definition(t.variableName), color: "#ffcb6b", fontWeight: "600" },
    { tag: t.variableName, color: "#e6d28a" },
    { tag: t.propertyName, color: "#89ddff" },
    { tag: t.attributeName, color: "#9fb4c8" },
    { tag: t.operator, color: "#89ddff" },
    { tag: [t.paren, t.separator, t.punctuation], color: "#8f9bb0" },
    { tag: t.invalid, color: "#ff5370", textDecoration: "underline wavy" },
  ]),
);
