// A small forward scanner of program text: which calls enclose a position, and the argument
// the position is in. Completion, signature help and hover share it.

export interface CallFrame {
  /** Callee name, or null for a bare parenthesis. */
  name: string | null;
  /** A layer method (`.basecolor(`) rather than a function. */
  method: boolean;
  /** Offset of the `(`. */
  open: number;
  /** Index of the argument the position is in (0-based). */
  argIndex: number;
  /** The keyword of the current argument (`mortar=` ...), or null when positional so far. */
  kw: string | null;
  /** Keywords already given in this call. */
  given: string[];
  /** Offset where the current argument starts (after `(` or `,`). */
  argStart: number;
}

export interface ScanResult {
  stack: CallFrame[];
  /** The position is inside a comment or a string. */
  inCommentOrString: boolean;
}

const IDENT = /[A-Za-z_\u00c0-\uffff][\w\u00c0-\uffff]*/y;
const NUMBER = /(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d*)?/y;

/** Scan `text` from the start up to `pos`. Programs are short; this is linear and cheap. */
export function scanTo(text: string, pos: number): ScanResult {
  const stack: CallFrame[] = [];
  let i = 0;
  let lastSig = ""; // previous significant token text
  let pendingName: string | null = null;
  let pendingMethod = false;
  while (i < pos) {
    const c = text[i];
    if (c === "#") {
      const nl = text.indexOf("\n", i);
      if (nl < 0 || nl >= pos) return { stack, inCommentOrString: true };
      i = nl + 1;
      continue;
    }
    if (c === '"' || c === "'") {
      const end = text.indexOf(c, i + 1);
      const nl = text.indexOf("\n", i + 1);
      const close = end >= 0 && (nl < 0 || end < nl) ? end : -1;
      if (close < 0 || close >= pos) {
        if (close < 0 && nl >= 0 && nl < pos) {
          i = nl + 1; // unterminated string: the lexer stops it at the line end
          continue;
        }
        return { stack, inCommentOrString: true };
      }
      i = close + 1;
      lastSig = "str";
      pendingName = null;
      continue;
    }
    if (/\s/.test(c)) {
      i++;
      continue;
    }
    IDENT.lastIndex = i;
    const id = IDENT.exec(text);
    if (id && !/\d/.test(c)) {
      const word = id[0];
      const end = Math.min(i + word.length, pos);
      const method = lastSig === ".";
      // Keyword argument: `name =` (not `==`), looking past the position only when the word ends before it.
      const after = text.slice(end, end + 40);
      if (end < pos && stack.length && /^\s*=(?!=)/.test(after) && !method) {
        const top = stack[stack.length - 1];
        top.kw = word;
        top.given.push(word);
      }
      pendingName = word;
      pendingMethod = method;
      lastSig = "id";
      i = end;
      continue;
    }
    NUMBER.lastIndex = i;
    const num = NUMBER.exec(text);
    if (num && (c !== "." || /\d/.test(text[i + 1] ?? ""))) {
      i += num[0].length;
      lastSig = "num";
      pendingName = null;
      continue;
    }
    if (c === "(") {
      const isCall = lastSig === "id" && pendingName !== null;
      stack.push({
        name: isCall ? pendingName : null,
        method: isCall && pendingMethod,
        open: i,
        argIndex: 0,
        kw: null,
        given: [],
        argStart: i + 1,
      });
    } else if (c === ")") {
      stack.pop();
    } else if (c === ",") {
      const top = stack[stack.length - 1];
      if (top) {
        top.argIndex++;
        top.kw = null;
        top.argStart = i + 1;
      }
    }
    pendingName = null;
    lastSig = c;
    i++;
  }
  return { stack, inCommentOrString: false };
}

/** The innermost call with a name (skipping bare parentheses). */
export function innermostCall(stack: CallFrame[]): CallFrame | null {
  for (let k = stack.length - 1; k >= 0; k--) if (stack[k].name !== null) return stack[k];
  return null;
}
