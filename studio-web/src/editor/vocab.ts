// The language registry as GET /api/vocab serves it, with lookups the editor parts share.

export interface VocabParam {
  name: string;
  type?: string;
  default?: unknown;
  doc?: string;
  low?: number | null;
  high?: number | null;
  required?: boolean;
  default_text?: string;
  constraint?: string;
  choices?: string[];
}

export interface VocabFunction {
  name: string;
  kind?: string;
  summary?: string;
  params: VocabParam[];
  returns?: string;
  doc?: string;
  example?: string;
  signature?: string;
}

export interface VocabChannel {
  name: string;
  method?: string;
  args: string[];
  low?: number | null;
  high?: number | null;
  doc?: string;
}

export interface VocabJson {
  functions?: VocabFunction[];
  constants?: { name: string; value: unknown }[];
  keywords?: string[];
  literals?: string[];
  statements?: { name: string; signature?: string; doc?: string }[];
  channels?: VocabChannel[];
  layer_methods?: (string | { name: string })[];
}

/** The statements of the language; always known, even when /api/vocab does not answer. */
const STATEMENTS: Record<string, string> = {
  View: "View(x1, y1, x2, y2): the rectangle of texture space that becomes the image",
  Define: "Define(name, expression): a named field or constant, referenced by its bare name",
  Material: "Material(Layer(...), ...): the last statement; its layers stack bottom first",
  Layer: "Layer(mask).channel(...)...: a mask and the channels it writes where the mask is 1",
};

export class Vocab {
  readonly functions = new Map<string, VocabFunction>();
  readonly channels = new Map<string, VocabChannel>();
  readonly constants = new Map<string, unknown>();
  readonly keywords = new Set<string>(Object.keys(STATEMENTS));
  readonly literals = new Set<string>(["True", "False", "None"]);
  /** Statements (View, Define, Material, Layer): their doc and the parameters of their signature. */
  readonly statements = new Map<string, { doc: string; signature: string; params: VocabParam[] }>();

  constructor(json: VocabJson = {}) {
    for (const f of json.functions ?? []) this.functions.set(f.name, { ...f, params: f.params ?? [] });
    for (const c of json.channels ?? []) {
      const name = (c.method ?? c.name).replace(/^\./, "").replace(/\($/, "");
      this.channels.set(name, { ...c, name, args: c.args ?? [] });
    }
    for (const m of json.layer_methods ?? []) {
      const name = (typeof m === "string" ? m : m.name).replace(/^\./, "").replace(/\($/, "");
      if (!this.channels.has(name)) this.channels.set(name, { name, args: [] });
    }
    for (const c of json.constants ?? []) this.constants.set(c.name, c.value);
    for (const l of json.literals ?? []) this.literals.add(l);
    for (const k of json.keywords ?? []) {
      if (this.literals.has(k)) continue;
      this.keywords.add(k);
    }
    for (const [name, doc] of Object.entries(STATEMENTS)) {
      this.statements.set(name, { doc, signature: doc.split(":")[0], params: [] });
    }
    for (const st of json.statements ?? []) {
      this.keywords.add(st.name);
      const signature = st.signature ?? st.name;
      this.statements.set(st.name, { doc: st.doc ?? "", signature, params: paramsOfSignature(signature) });
    }
  }

  statementDoc(name: string): string | null {
    const st = this.statements.get(name);
    return st ? (st.doc.startsWith(st.signature) ? st.doc : `${st.signature}: ${st.doc}`) : null;
  }

  /** Parameters of a callee: a function's params, or a channel's argument names. */
  paramsOf(name: string, method: boolean): VocabParam[] | null {
    if (method) {
      const c = this.channels.get(name);
      return c ? c.args.map((a) => ({ name: a, low: c.low, high: c.high, doc: c.doc })) : null;
    }
    const fn = this.functions.get(name);
    if (fn) return fn.params;
    const st = this.statements.get(name);
    return st && st.params.length ? st.params : null;
  }
}

/** `View(x1, y1, x2, y2, tileable=False)` -> its parameters (only simple names are kept). */
function paramsOfSignature(signature: string): VocabParam[] {
  const inner = /\((.*)\)/.exec(signature)?.[1] ?? "";
  const out: VocabParam[] = [];
  for (const part of inner.split(",")) {
    const m = /^\s*([A-Za-z_]\w*)\s*(?:=\s*(.*?))?\s*$/.exec(part);
    if (!m) return out;
    out.push({ name: m[1], required: m[2] === undefined, default_text: m[2], default: m[2] });
  }
  return out;
}

export function formatDefault(v: unknown, text?: string): string {
  if (text !== undefined && text !== null) return text;
  if (v === null || v === undefined) return "";
  if (typeof v === "string") return v;
  if (typeof v === "boolean") return v ? "True" : "False";
  return String(v);
}

export function rangeText(p: { low?: number | null; high?: number | null; constraint?: string }): string {
  if (p.constraint) return p.constraint;
  const lo = p.low ?? null;
  const hi = p.high ?? null;
  if (lo !== null && hi !== null) return `${lo} … ${hi}`;
  if (lo !== null) return `≥ ${lo}`;
  if (hi !== null) return `≤ ${hi}`;
  return "";
}

/** `Bricks(brick_width=1, brick_height=0.5, ...)`: the signature as text parts. */
export function signatureParts(name: string, params: VocabParam[], method: boolean): string[] {
  return params.map((p) =>
    method || p.required || (p.default_text ?? p.default) === undefined ? p.name : `${p.name}=${formatDefault(p.default, p.default_text)}`,
  );
}

/** Names a program defines: `Define(name, ...)`, with the offset of the name. */
export function defineNames(text: string): Map<string, number> {
  const out = new Map<string, number>();
  const re = /\bDefine\s*\(\s*([A-Za-z_]\w*)/g;
  for (let m = re.exec(text); m; m = re.exec(text)) {
    if (!out.has(m[1])) out.set(m[1], m.index + m[0].length - m[1].length);
  }
  return out;
}
