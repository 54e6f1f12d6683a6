// The list of diagnostics under the editor: one `li` per diagnostic (data-line, data-col);
// clicking one puts the cursor there.
import type { Store, Diagnostic } from "../store";

export function mountDiagList(ul: HTMLUListElement, count: HTMLElement, store: Store, jump: (offset: number) => void): void {
  const render = (diags: Diagnostic[]): void => {
    ul.textContent = "";
    const errors = diags.filter((d) => d.severity !== "warning").length;
    const warnings = diags.length - errors;
    count.textContent = diags.length ? [errors && `${errors} error${errors > 1 ? "s" : ""}`, warnings && `${warnings} warning${warnings > 1 ? "s" : ""}`].filter(Boolean).join(", ") : "no problems";
    count.className = errors ? "diag-count has-errors" : warnings ? "diag-count has-warnings" : "diag-count";
    for (const d of diags) {
      const li = document.createElement("li");
      li.className = `diag diag-${d.severity === "warning" ? "warning" : "error"}`;
      li.dataset.line = String(d.line);
      li.dataset.col = String(d.col);
      li.dataset.code = d.code;
      li.tabIndex = 0;
      li.title = "go to " + d.line + ":" + d.col;
      const loc = document.createElement("span");
      loc.className = "diag-loc";
      loc.textContent = `${d.line}:${d.col}`;
      const code = document.createElement("span");
      code.className = "diag-code";
      code.textContent = d.code;
      const msg = document.createElement("span");
      msg.className = "diag-msg";
      msg.textContent = d.message;
      li.append(loc, code, msg);
      if (d.hint) {
        const hint = document.createElement("div");
        hint.className = "diag-hint";
        hint.textContent = d.hint;
        li.appendChild(hint);
      }
      const go = (): void => jump(d.from);
      li.addEventListener("click", go);
      li.addEventListener("keydown", (e) => {
        if (e.key === "Enter") go();
      });
      ul.appendChild(li);
    }
  };
  store.on("diagnostics", render);
  render(store.diagnostics);
}
