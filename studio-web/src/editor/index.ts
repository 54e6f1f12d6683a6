// The code editor: CodeMirror 6 with the MatLoom mode, completion, signature help, hover docs,
// live diagnostics and format; kept in sync with the store both ways.
import { autocompletion, closeBrackets, closeBracketsKeymap, completionKeymap } from "@codemirror/autocomplete";
import { defaultKeymap, indentWithTab } from "@codemirror/commands";
import { bracketMatching, indentOnInput } from "@codemirror/language";
import { lintKeymap } from "@codemirror/lint";
import { highlightSelectionMatches, searchKeymap } from "@codemirror/search";
import { Annotation, EditorState, type ChangeSpec } from "@codemirror/state";
import {
  EditorView,
  drawSelection,
  highlightActiveLine,
  highlightActiveLineGutter,
  keymap,
  lineNumbers,
} from "@codemirror/view";
import type { Ctx } from "../ctx";
import { matloomCompletion } from "./complete";
import { matloomHover } from "./hover";
import { matloomHighlight, matloomLanguage } from "./language";
import { formatText, matloomLint } from "./lint";
import { signatureHelp } from "./signature";
import { editorTheme } from "./theme";
import type { Vocab } from "./vocab";

/** Marks a transaction that applies a change made elsewhere (panel, history, author). */
const External = Annotation.define<boolean>();
/** How long after the last panel edit (a slider step) the text shows it (see mountEditor). */
export const PANEL_TEXT_DELAY_MS = 120;

export interface Editor {
  view: EditorView;
  /** Put the cursor at a character offset and show it. */
  jumpTo(offset: number): void;
  /** Format the program; resolves to null when done, else the reason it was not. */
  format(): Promise<string | null>;
}

/** The smallest single change turning `a` into `b` (keeps the cursor and scroll steady). */
export function minimalChange(a: string, b: string): ChangeSpec & { from: number; to: number; insert: string } {
  let start = 0;
  const max = Math.min(a.length, b.length);
  while (start < max && a.charCodeAt(start) === b.charCodeAt(start)) start++;
  let endA = a.length;
  let endB = b.length;
  while (endA > start && endB > start && a.charCodeAt(endA - 1) === b.charCodeAt(endB - 1)) {
    endA--;
    endB--;
  }
  return { from: start, to: endA, insert: b.slice(start, endB) };
}

export function mountEditor(el: HTMLElement, ctx: Ctx, vocab: Vocab, onError: (message: string) => void): Editor {
  const { store } = ctx;
  let flushPending: () => void = () => undefined;
  const handFirst = (): boolean => {
    flushPending();
    return false;
  };
  const view = new EditorView({
    parent: el,
    state: EditorState.create({
      doc: store.text,
      extensions: [
        lineNumbers(),
        highlightActiveLineGutter(),
        highlightActiveLine(),
        drawSelection(),
        indentOnInput(),
        bracketMatching(),
        closeBrackets(),
        highlightSelectionMatches(),
        EditorState.tabSize.of(2),
        EditorView.lineWrapping,
        matloomLanguage(vocab),
        matloomHighlight,
        editorTheme,
        autocompletion({ override: [matloomCompletion(vocab)], filterStrict: true, icons: true }),
        signatureHelp(vocab),
        matloomHover(vocab),
        matloomLint(ctx),
        keymap.of([
          { key: "Shift-Alt-f", run: () => (void editor.format().then((e) => e && onError(e)), true) },
          ...closeBracketsKeymap,
          ...completionKeymap,
          ...searchKeymap,
          ...lintKeymap,
          indentWithTab,
          ...defaultKeymap,
        ]),
        EditorView.domEventHandlers({ keydown: handFirst, mousedown: handFirst, focus: handFirst, paste: handFirst }),
        EditorView.editorAttributes.of({ "data-testid": "editor" }),
        EditorView.contentAttributes.of({ "aria-label": "program text", spellcheck: "false" }),
        EditorView.updateListener.of((u) => {
          if (!u.docChanged || u.transactions.some((tr) => tr.annotation(External))) return;
          store.setText(u.state.doc.toString(), "editor");
        }),
      ],
    }),
  });

  // Panel edits (a slider drag) reach the text PANEL_TEXT_DELAY_MS after the last one: the text
  // need not redraw at every step of a drag, and without a GPU its repaint competes with the
  // quick first pass for the CPU. Any other change, or the user's hand on the editor, first
  // applies a waiting one, so typing never starts from an outdated text.
  let deferred: ReturnType<typeof setTimeout> | undefined;
  let waiting = false;
  const flush = (): void => {
    clearTimeout(deferred);
    if (!waiting) return;
    waiting = false;
    apply(store.text, "panel");
  };
  flushPending = flush;
  store.on("text", ({ text, source }) => {
    if (source === "editor") return;
    clearTimeout(deferred);
    if (source === "panel") {
      waiting = true;
      deferred = setTimeout(flush, PANEL_TEXT_DELAY_MS);
      return;
    }
    waiting = false;
    apply(text, source);
  });
  const apply = (text: string, source: string): void => {
    const current = view.state.doc.toString();
    if (current === text) return;
    const change = minimalChange(current, text);
    const fromHistory = source === "history";
    view.dispatch({
      changes: change,
      annotations: External.of(true),
      // Undo/redo puts the cursor at the change and shows it; other sources leave it mapped.
      ...(fromHistory ? { selection: { anchor: change.from + change.insert.length }, scrollIntoView: true } : {}),
    });
  };

  const editor: Editor = {
    view,
    jumpTo(offset: number) {
      flush();
      const pos = Math.max(0, Math.min(offset, view.state.doc.length));
      view.dispatch({ selection: { anchor: pos }, scrollIntoView: true, userEvent: "select" });
      view.focus();
    },
    async format() {
      flush();
      const before = view.state.doc.toString();
      ctx.history.commit();
      const text = await formatText(ctx, before);
      if (text instanceof Error) return `format: ${text.message}`;
      if (view.state.doc.toString() !== before) return "format: the program changed meanwhile";
      if (text === before) return null;
      view.dispatch({ changes: minimalChange(before, text), userEvent: "input.format" });
      ctx.history.commit("format");
      return null;
    },
  };
  return editor;
}
