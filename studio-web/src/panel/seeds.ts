// Seed chips: a written seed is a slider row with a reroll button; an automatic one (derived,
// not written in the program) shows its value with reroll and pin (write it down).
import type { Param, Structure } from "../store";
import { h, iconButton, setText } from "./dom";
import { NumberRow, shortLabel, type Row, type RowEnv } from "./rows";

export type SeedInfo = Structure["seeds"][number];

/** The seed operations the panel offers (POST /api/seeds). */
export interface SeedOps {
  reroll(address: string, label: string): void;
  pin(address: string, label: string): void;
}

/** A written seed: the number row plus a reroll button. */
export function writtenSeedRow(p: Param, env: RowEnv, prefix: string, ops: SeedOps): Row {
  const reroll = iconButton("⟳", `Reroll ${p.label}`, "pn-reroll", () => ops.reroll(p.address, p.label));
  reroll.dataset.testid = `reroll-${p.address}`;
  const row = new NumberRow(p, env, prefix, [reroll]);
  row.el.classList.add("pn-seed");
  return row;
}

/** An automatic seed (no literal to slide): its value, reroll and pin. */
export class AutoSeedRow implements Row {
  readonly el: HTMLElement;
  readonly param: Param;
  private readonly value: HTMLElement;
  private readonly label: HTMLElement;

  constructor(
    private seed: SeedInfo,
    private readonly prefix: string,
    ops: SeedOps,
  ) {
    this.param = {
      address: seed.address,
      value: seed.value,
      kind: "seed",
      low: 0,
      high: null,
      unit: null,
      label: seed.label,
      affects: [],
      line: 0,
      col: 0,
    };
    this.label = h("span", { class: "pn-label", title: `${seed.label}\n${seed.address}\nautomatic: derived, not written` }, `${shortLabel(seed.label, prefix)} seed`);
    this.value = h("span", { class: "pn-seedval", "data-testid": `value-${seed.address}` }, String(seed.value));
    const reroll = iconButton("⟳", `Reroll ${seed.label}`, "pn-reroll", () => ops.reroll(this.seed.address, this.seed.label));
    reroll.dataset.testid = `reroll-${seed.address}`;
    const pin = iconButton("pin", `Pin ${seed.label}: write the seed into the program`, "pn-pin", () => ops.pin(this.seed.address, this.seed.label));
    pin.dataset.testid = `pin-${seed.address}`;
    this.el = h(
      "div",
      { class: "pn-row pn-seed pn-auto", "data-address": seed.address },
      h("div", { class: "pn-head" }, this.label, h("span", { class: "pn-tags" }, seed.auto ? h("span", { class: "pn-tag pn-tag-auto" }, "auto") : null)),
      h("div", { class: "pn-ctl" }, this.value, reroll, seed.auto ? pin : null),
    );
  }

  update(_p: Param): void {
    /* seeds come through updateSeed */
  }

  updateSeed(s: SeedInfo): void {
    this.seed = s;
    setText(this.value, String(s.value));
    setText(this.label, `${shortLabel(s.label, this.prefix)} seed`);
  }

  matches(q: string): boolean {
    return this.seed.label.toLowerCase().includes(q) || this.seed.address.toLowerCase().includes(q) || "seed".includes(q);
  }
}
