// The author box: a prompt runs `generate` (POST /api/generate) and the job's Server-Sent
// Events stream each round (score, preview, program), log lines, and the final program.
import type { Ctx } from "../ctx";
import { errorText, fmt, h } from "../inspector/dom";

interface RoundEvent {
  round: number;
  score?: number | null;
  text: string;
  preview_png_b64?: string | null;
}

export function authorBox(ctx: Ctx): HTMLElement {
  const modelOn = ctx.session.model;
  const useModel = h("input", { type: "checkbox", checked: modelOn, disabled: !modelOn, "data-testid": "author-model" });
  const mode = h("span", { class: "dlg-dim", "data-testid": "author-mode" });
  const showMode = () => {
    mode.textContent = useModel.checked
      ? "runs the configured model (LLM pipeline: rounds of write → render → critique)"
      : modelOn
        ? "runs the material library (offline); the configured model is off"
        : "runs the material library (offline): no model is configured on the server";
  };
  showMode();
  useModel.addEventListener("change", showMode);
  const prompt = h("textarea", {
    rows: 3,
    placeholder: "describe a material, e.g. “weathered red brick with dark mortar”",
    "data-testid": "author-prompt",
  });
  const run = h("button", { class: "dlg-primary", text: "Generate", "data-testid": "author-run" });
  const cancel = h("button", { text: "Cancel", disabled: true, "data-testid": "author-cancel" });
  const status = h("span", { class: "dlg-dim", "data-testid": "author-status" });
  const rounds = h("ul", { class: "dlg-rounds", "data-testid": "author-rounds" });
  const program = h("pre", { class: "dlg-pre", hidden: true, "data-testid": "author-program" });
  const use = h("button", { class: "dlg-primary", text: "Use this program", hidden: true, "data-testid": "author-use" });
  const log = h("pre", { class: "dlg-log", "data-testid": "author-log" });

  let job: string | null = null;
  let cancelling = false;
  let source: EventSource | null = null;
  let chosen = "";

  function show(text: string, label: string, item: HTMLElement | null): void {
    chosen = text;
    program.textContent = text;
    program.hidden = false;
    use.hidden = false;
    use.textContent = `Use ${label}`;
    for (const li of rounds.children) li.classList.toggle("dlg-sel", li === item);
  }

  function addLog(line: string): void {
    log.textContent += (log.textContent ? "\n" : "") + line;
    log.scrollTop = log.scrollHeight;
  }

  function finish(message: string, cls = "dlg-dim"): void {
    source?.close();
    source = null;
    job = null;
    cancelling = false;
    run.disabled = false;
    cancel.disabled = true;
    status.textContent = message;
    status.className = cls;
  }

  function addRound(r: RoundEvent): void {
    const score = typeof r.score === "number" ? ` · score ${fmt(r.score, 3)}` : "";
    const img = r.preview_png_b64 ? h("img", { src: `data:image/png;base64,${r.preview_png_b64}`, alt: `round ${r.round}` }) : h("img", { alt: "" });
    // The first comment says what it is (e.g. the library entry); else the first line of code.
    const lines = r.text.split("\n").map((l) => l.trim());
    const first = (lines.find((l) => l.startsWith("#")) ?? lines.find((l) => l) ?? "").replace(/^#\s*/, "");
    const li = h(
      "li",
      { class: "dlg-round", title: "show this round's program", "data-round": r.round },
      img,
      h("div", {}, h("div", { text: `round ${r.round}${score}` }), h("div", { class: "dlg-dim", text: first.slice(0, 90) })),
    );
    li.addEventListener("click", () => show(r.text, `round ${r.round}'s program`, li));
    rounds.append(li);
    rounds.scrollTop = rounds.scrollHeight;
    status.textContent = `round ${r.round}${score}`;
  }

  function listen(id: string): void {
    const es = ctx.api.events(id);
    source = es;
    const data = <T>(e: Event): T | null => {
      try {
        return JSON.parse((e as MessageEvent).data) as T;
      } catch {
        return null;
      }
    };
    es.addEventListener("round", (e) => {
      const r = data<RoundEvent>(e);
      if (r) addRound(r);
    });
    es.addEventListener("log", (e) => {
      const l = data<{ line: string }>(e);
      if (l) addLog(l.line);
    });
    es.addEventListener("done", (e) => {
      const d = data<{ text: string }>(e);
      finish("done", "dlg-ok");
      if (d?.text) show(d.text, "this program", null);
      use.textContent = "Use this program";
    });
    es.addEventListener("error", (e) => {
      // A server `error` event carries data; a dropped connection does not.
      const d = (e as MessageEvent).data ? data<{ error: string }>(e) : null;
      if (d) finish(d.error === "cancelled" ? "cancelled" : d.error, d.error === "cancelled" ? "dlg-dim" : "dlg-err");
      else if (source === es && cancelling) finish("cancelled");
      else if (es.readyState === EventSource.CLOSED && source === es) finish("the event stream closed", "dlg-err");
    });
  }

  run.addEventListener("click", async () => {
    const text = prompt.value.trim();
    if (!text) {
      status.textContent = "type a prompt first";
      status.className = "dlg-err";
      return;
    }
    source?.close();
    rounds.replaceChildren();
    log.textContent = "";
    program.hidden = use.hidden = true;
    run.disabled = true;
    status.textContent = "starting…";
    status.className = "dlg-dim";
    try {
      const r = await ctx.api.json<{ job: string }>("/api/generate", { prompt: text, model: useModel.checked });
      job = r.job;
      cancel.disabled = false;
      status.textContent = "running…";
      listen(r.job);
    } catch (err) {
      finish(errorText(err), "dlg-err");
    }
  });

  cancel.addEventListener("click", async () => {
    if (!job) return;
    const id = job;
    cancel.disabled = true;
    cancelling = true;
    status.textContent = "cancelling…";
    try {
      await ctx.api.json(`/api/jobs/${encodeURIComponent(id)}/cancel`, {});
    } catch (err) {
      addLog(`cancel: ${errorText(err)}`);
    }
    // The stream ends with `error` (cancelled) or `done`; stop waiting after a while anyway.
    setTimeout(() => job === id && finish("cancelled"), 5000);
  });

  use.addEventListener("click", () => {
    if (!chosen) return;
    ctx.store.setText(chosen, "author");
    ctx.history.commit("author");
    status.textContent = "program replaced (undo brings the old one back)";
    status.className = "dlg-ok";
  });

  return h(
    "div",
    { class: "dlg-box", "data-testid": "author-box" },
    h("h3", { text: "author (generate)" }),
    h("label", { class: "dlg-check" }, useModel, "use the configured model"),
    mode,
    prompt,
    h("div", { class: "dlg-row" }, run, cancel, status),
    rounds,
    program,
    h("div", { class: "dlg-row" }, use),
    log,
  );
}
