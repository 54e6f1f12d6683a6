// The author tab: the generate box and, beside it, the edit-by-words box.
import type { Ctx } from "../ctx";
import { h } from "../inspector/dom";
import { editBox } from "./edit";
import { authorBox } from "./generate";
import { dialogStyle } from "./style";

export function mountAuthor(el: HTMLElement, ctx: Ctx): void {
  dialogStyle();
  el.replaceChildren(h("div", { class: "dlg-root" }, authorBox(ctx), editBox(ctx)));
}
