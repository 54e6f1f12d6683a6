// The edit-by-words box: POST /api/edit {text, request} -> the diff, the changed parameters and
// the locality report, with Apply; a refusal (422) shows why and what could be changed.
import { ApiError } from "../api";
import type { Ctx } from "../ctx";
import { errorText, h } from "../inspector/dom";

interface Change {
  address: string;
  label: string;
  before: unknown;
  after: unknown;
}

interface Report {
  mode?: string;
  edit?: { rule?: string; note?: string };
  changed?: Change[];
  warnings?: string[];
  ok?: boolean;
  locality?: { intended?: string[]; changed?: string[]; leaks?: string[]; size?: number };
}

interface EditReply {
  text: string;
  diff: string;
  report: Report;
}

function value(v: unknown): string {
  return typeof v === "string" ? v : JSON.stringify(v);
}

/** A unified diff with added / removed / hunk lines coloured. */
export function diffView(diff: string): HTMLElement {
  const pre = h("pre", { class: "dlg-pre", "data-testid": "edit-diff" });
  for (const line of diff.split("\n")) {
    const cls =
      line.startsWith("+++") || line.startsWith("---")
        ? "dlg-dim"
        : line.startsWith("+")
          ? "dlg-add"
          : line.startsWith("-")
            ? "dlg-del"
            : line.startsWith("@@")
              ? "dlg-hunk"
              : null;
    pre.append(h("span", { class: cls, text: line }), "\n");
  }
  return pre;
}

function changesTable(changes: Change[]): HTMLElement {
  if (!changes.length) return h("div", { class: "dlg-dim", text: "no parameter changed" });
  return h(
    "table",
    { class: "dlg-table", "data-testid": "edit-changes" },
    h("tr", {}, h("th", { text: "parameter" }), h("th", { text: "before" }), h("th", { text: "after" })),
    ...changes.map((c) =>
      h("tr", {}, h("td", { text: c.label ? `${c.label} (${c.address})` : c.address }), h("td", { text: value(c.before) }), h("td", { text: value(c.after) })),
    ),
  );
}

function localityView(r: Report): HTMLElement {
  const loc = r.locality ?? {};
  const list = (xs: string[] | undefined) => (xs && xs.length ? xs.join(", ") : "none");
  const leaks = loc.leaks ?? [];
  return h(
    "div",
    { "data-testid": "edit-locality" },
    h("div", { class: leaks.length ? "dlg-warn" : "dlg-ok", text: leaks.length ? `leaks into: ${list(leaks)}` : "local: only the intended maps changed" }),
    h("div", { class: "dlg-dim", text: `intended: ${list(loc.intended)} · changed: ${list(loc.changed)}${loc.size ? ` · at ${loc.size}²` : ""}` }),
  );
}

/** The parameters a refusal lists (strings or {address, label} objects). */
function refusedParams(body: Record<string, unknown>): string[] {
  const ps = body.parameters;
  if (!Array.isArray(ps)) return [];
  return ps.map((p) => {
    if (typeof p === "string") return p;
    const o = p as { address?: string; label?: string; kind?: string };
    return o.label ? `${o.address} (${o.label})` : String(o.address ?? JSON.stringify(p));
  });
}

export function editBox(ctx: Ctx): HTMLElement {
  const request = h("input", { type: "text", class: "dlg-grow", placeholder: "e.g. “wider grout”, “bluer glaze”, “rougher”", "data-testid": "edit-request" });
  const run = h("button", { class: "dlg-primary", text: "Edit", "data-testid": "edit-run" });
  const useModel = h("input", { type: "checkbox", checked: ctx.session.model, disabled: !ctx.session.model, "data-testid": "edit-model" });
  const status = h("span", { class: "dlg-dim", "data-testid": "edit-status" });
  const result = h("div", { "data-testid": "edit-result" });
  const apply = h("button", { class: "dlg-primary", text: "Apply", hidden: true, "data-testid": "edit-apply" });
  let pending: { from: string; to: string; request: string } | null = null;

  const go = async () => {
    const req = request.value.trim();
    if (!req) return;
    const from = ctx.store.text;
    run.disabled = true;
    apply.hidden = true;
    pending = null;
    status.textContent = "editing…";
    status.className = "dlg-dim";
    result.replaceChildren();
    try {
      const r = await ctx.api.json<EditReply>("/api/edit", { text: from, request: req, model: useModel.checked });
      const rep = r.report ?? {};
      const note = rep.edit?.note ? ` — ${rep.edit.note}` : "";
      status.textContent = `${rep.mode === "model" ? "model" : "offline rules"}${rep.edit?.rule ? ` (${rep.edit.rule})` : ""}${note}`;
      result.replaceChildren(
        changesTable(rep.changed ?? []),
        localityView(rep),
        ...(rep.warnings ?? []).map((w) => h("div", { class: "dlg-warn", text: w })),
        diffView(r.diff || "(no textual change)"),
      );
      pending = { from, to: r.text, request: req };
      apply.hidden = r.text === from;
    } catch (err) {
      status.textContent = "";
      if (err instanceof ApiError && err.status === 422) {
        const params = refusedParams(err.body);
        // The message ends with the same list; show it once, as its own line.
        const cut = params.length ? err.message.indexOf("; parameters it could change") : -1;
        result.replaceChildren(
          h("div", { class: "dlg-err", "data-testid": "edit-refused", text: cut > 0 ? err.message.slice(0, cut) : err.message }),
          params.length ? h("div", { class: "dlg-dim", text: `parameters it could change: ${params.join(", ")}` }) : "",
        );
      } else result.replaceChildren(h("div", { class: "dlg-err", text: errorText(err) }));
    } finally {
      run.disabled = false;
    }
  };
  run.addEventListener("click", () => void go());
  request.addEventListener("keydown", (e) => {
    if (e.key === "Enter") void go();
  });
  apply.addEventListener("click", () => {
    if (!pending) return;
    if (ctx.store.text !== pending.from) {
      status.textContent = "the program changed since this edit was made: run it again";
      status.className = "dlg-err";
      return;
    }
    ctx.store.setText(pending.to, "author");
    ctx.history.commit(`edit: ${pending.request}`);
    status.textContent = "applied (undo brings the old program back)";
    status.className = "dlg-ok";
    apply.hidden = true;
    pending = null;
  });

  return h(
    "div",
    { class: "dlg-box", "data-testid": "edit-box" },
    h("h3", { text: "edit by words" }),
    h(
      "div",
      { class: "dlg-row" },
      h("label", { class: "dlg-check" }, useModel, "use the configured model"),
      h("span", { class: "dlg-dim", text: ctx.session.model ? "" : "offline rules: no model is configured" }),
    ),
    h("div", { class: "dlg-row" }, request, run, apply),
    status,
    result,
  );
}
