// The Blender renders (flat / staged) of the current program, shown only when the server
// found Blender (session.blender): POST /api/blender -> image/png.
import type { Ctx } from "../ctx";
import { errorText, h } from "../inspector/dom";
import { saveBlob } from "./download";

export function mountBlender(ctx: Ctx): HTMLElement {
  const status = h("span", { class: "dlg-dim" });
  const img = h("img", { class: "dlg-render", alt: "", "data-testid": "blender-image", hidden: true });
  const save = h("button", { text: "Save PNG", hidden: true });
  let last: { blob: Blob; mode: string } | null = null;
  let url = "";
  const buttons = (["flat", "staged"] as const).map((mode) => {
    const b = h("button", { text: `Blender ${mode}`, "data-testid": `blender-${mode}` });
    b.addEventListener("click", async () => {
      for (const x of buttons) x.disabled = true;
      status.textContent = `rendering ${mode} in Blender…`;
      status.className = "dlg-dim";
      try {
        const blob = await ctx.api.blob("/api/blender", { text: ctx.store.text, mode });
        if (url) URL.revokeObjectURL(url);
        url = URL.createObjectURL(blob);
        img.src = url;
        img.hidden = false;
        save.hidden = false;
        last = { blob, mode };
        status.textContent = `${mode} render`;
      } catch (err) {
        status.textContent = errorText(err);
        status.className = "dlg-err";
      } finally {
        for (const x of buttons) x.disabled = false;
      }
    });
    return b;
  });
  save.addEventListener("click", () => last && saveBlob(last.blob, `blender_${last.mode}.png`));
  return h(
    "div",
    { class: "dlg-box" },
    h("h3", { text: "Blender render" }),
    h("div", { class: "dlg-row" }, ...buttons, save, status),
    img,
  );
}
