// Live diagnostics: the checker (POST /api/check, debounced) as lint marks with message and
// hint, pushed to the store's `diagnostics` for the list under the editor.
import { linter, type Diagnostic as LintDiagnostic } from "@codemirror/lint";
import type { EditorView } from "@codemirror/view";
import type { Ctx } from "../ctx";
import type { Diagnostic } from "../store";

const DELAY_MS = 180;

export function toLint(d: Diagnostic, length: number): LintDiagnostic {
  let from = Math.max(0, Math.min(d.from ?? 0, length));
  let to = Math.max(from, Math.min(d.to ?? from, length));
  if (to === from) {
    if (to < length) to++;
    else if (from > 0) from--;
  }
  return {
    from,
    to,
    severity: d.severity === "warning" ? "warning" : "error",
    source: d.code,
    message: d.message,
    renderMessage: () => {
      const el = document.createElement("div");
      el.className = "ml-lint";
      const m = document.createElement("div");
      m.textContent = `${d.code}: ${d.message}`;
      el.appendChild(m);
      for (const [k, v] of [["expected", d.expected], ["hint", d.hint]] as const) {
        if (!v) continue;
        const p = document.createElement("div");
        p.className = "ml-lint-" + k;
        p.textContent = `${k}: ${v}`;
        el.appendChild(p);
      }
      return el;
    },
  };
}

/** The lint extension. Stale answers (the text moved on) are dropped by the linter itself. */
export function matloomLint(ctx: Ctx) {
  return linter(
    async (view: EditorView): Promise<LintDiagnostic[]> => {
      const text = view.state.doc.toString();
      let diags: Diagnostic[];
      try {
        const r = await ctx.api.json<{ ok: boolean; diagnostics: Diagnostic[] }>("/api/check", { text });
        diags = r.diagnostics ?? [];
      } catch (e) {
        diags = [];
        if (view.state.doc.toString() === text) {
          ctx.store.emit("status", { state: "error", message: `check failed: ${(e as Error).message}` });
        }
      }
      if (view.state.doc.toString() !== text) return [];
      ctx.store.diagnostics = diags;
      ctx.store.emit("diagnostics", diags);
      return diags.map((d) => toLint(d, text.length));
    },
    { delay: DELAY_MS },
  );
}

/** Format the program (POST /api/format, comments kept): the new text, or an Error saying why not. */
export async function formatText(ctx: Ctx, text: string): Promise<string | Error> {
  try {
    const r = await ctx.api.json<{ text: string }>("/api/format", { text });
    return r.text;
  } catch (e) {
    return e instanceof Error ? e : new Error(String(e));
  }
}
