// The editor's dark theme (colours follow app.css's variables).
import { EditorView } from "@codemirror/view";

export const editorTheme = EditorView.theme(
  {
    "&": { height: "100%", color: "var(--fg)", backgroundColor: "var(--bg-editor)", fontSize: "12.5px" },
    ".cm-scroller": { fontFamily: "var(--mono)", lineHeight: "1.55" },
    ".cm-content": { caretColor: "#ffcc00", padding: "6px 0" },
    ".cm-cursor, .cm-dropCursor": { borderLeftColor: "#ffcc00", borderLeftWidth: "2px" },
    "&.cm-focused": { outline: "none" },
    "&.cm-focused > .cm-scroller > .cm-selectionLayer .cm-selectionBackground, .cm-selectionBackground, ::selection":
      { backgroundColor: "#2c4466" },
    ".cm-activeLine": { backgroundColor: "#ffffff08" },
    ".cm-activeLineGutter": { backgroundColor: "#ffffff0d", color: "var(--fg)" },
    ".cm-gutters": { backgroundColor: "var(--bg-editor)", color: "#56607a", border: "none", borderRight: "1px solid var(--line)" },
    ".cm-lineNumbers .cm-gutterElement": { padding: "0 8px 0 10px", minWidth: "28px" },
    ".cm-matchingBracket, &.cm-focused .cm-matchingBracket": { backgroundColor: "#3a4a63", outline: "1px solid #5a6d8c" },
    ".cm-selectionMatch": { backgroundColor: "#33415580" },
    ".cm-tooltip": {
      backgroundColor: "var(--bg-pop)",
      color: "var(--fg)",
      border: "1px solid var(--line-strong)",
      borderRadius: "4px",
      boxShadow: "0 6px 24px #0009",
      fontSize: "12px",
    },
    ".cm-tooltip-autocomplete > ul": { fontFamily: "var(--mono)", maxHeight: "16em" },
    ".cm-tooltip-autocomplete > ul > li": { padding: "1px 8px 1px 4px" },
    ".cm-tooltip-autocomplete > ul > li[aria-selected]": { backgroundColor: "var(--accent-dim)", color: "#fff" },
    ".cm-completionDetail": { color: "var(--fg-dim)", fontStyle: "normal", marginLeft: "1em" },
    ".cm-completionMatchedText": { color: "#ffcb6b", textDecoration: "none", fontWeight: "600" },
    ".cm-completionInfo": { padding: "6px 8px", maxWidth: "360px" },
    ".cm-diagnostic": { padding: "4px 8px", borderLeftWidth: "3px" },
    ".cm-diagnostic-error": { borderLeftColor: "var(--err)" },
    ".cm-diagnostic-warning": { borderLeftColor: "var(--warn)" },
    ".cm-lintRange-error": {
      backgroundImage: "none",
      textDecoration: "underline wavy var(--err)",
      textUnderlineOffset: "3px",
      backgroundColor: "#ff537022",
    },
    ".cm-lintRange-warning": {
      backgroundImage: "none",
      textDecoration: "underline wavy var(--warn)",
      textUnderlineOffset: "3px",
    },
    ".cm-panels": { backgroundColor: "var(--bg-pop)", color: "var(--fg)" },
    ".cm-searchMatch": { backgroundColor: "#6b5a1e88" },
  },
  { dark: true },
);
