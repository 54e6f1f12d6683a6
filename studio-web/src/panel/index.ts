// The structured panel: View, Defines and Layers cards built from the program's structure
// (POST /api/structure), kept in sync both ways with the text. Edits go through the server's
// canonical printer (POST /api/set, /api/layers, /api/seeds) and come back as store text.
import type { Ctx } from "../ctx";
import type { Diagnostic, Structure } from "../store";
import { CardView } from "./cards";
import { h, iconButton } from "./dom";
import { LayerControls } from "./layers";
import { cardsOf, signature } from "./model";
import type { Value } from "./rows";
import { Sender } from "./sender";
import type { SeedOps } from "./seeds";
import { injectStyle } from "./style";

class Panel {
  private readonly root: HTMLElement;
  private readonly scroll: HTMLElement;
  private readonly msg: HTMLElement;
  private readonly filterBox: HTMLInputElement;
  private readonly sender: Sender;
  private readonly layers: LayerControls;
  private cards: CardView[] = [];
  private sig = "";
  private readonly collapsed = new Set<string>();
  private readonly origin = new Map<string, Value>();
  private readonly rerollAll: HTMLButtonElement;
  private msgTimer = 0;
  private toastEl: HTMLElement | null = null;
  private toastTimer = 0;
  private fetchTimer = 0;
  /** A pointer is held on one of the panel's controls (a drag): rebuilds wait for its end. */
  private gesture = false;
  private deferred: Structure | null = null;

  constructor(
    private readonly el: HTMLElement,
    private readonly ctx: Ctx,
  ) {
    injectStyle();
    this.sender = new Sender(ctx, (m, kind) => this.report(m, kind));
    this.layers = new LayerControls(ctx, this.sender, (t, undo) => this.toast(t, undo));
    this.filterBox = h("input", {
      type: "search",
      class: "pn-filter",
      placeholder: "Filter parameters…",
      "data-testid": "panel-filter",
      "data-pn-key": "filter",
      "aria-label": "Filter parameters",
    });
    this.filterBox.addEventListener("input", () => this.applyFilter());
    const rerollAll = (this.rerollAll = iconButton("⟳ seeds", "Reroll every seed", "pn-reroll-all", () => this.seedOp("reroll_all", undefined, "reroll all seeds")));
    rerollAll.dataset.testid = "seeds-reroll-all";
    const fold = iconButton("▾▸", "Collapse or expand every card", "pn-fold", () => this.foldAll());
    this.msg = h("div", { class: "pn-msg", "data-testid": "panel-msg", role: "status" });
    this.scroll = h("div", { class: "pn-scroll" });
    this.root = h("div", { class: "pn-root" }, h("div", { class: "pn-bar" }, this.filterBox, rerollAll, fold), this.msg, this.scroll);
    if (!el.closest('[data-testid="panel"]')) this.root.dataset.testid = "panel";
    el.replaceChildren(this.root);

    this.root.addEventListener("pointerdown", (e) => {
      if ((e.target as HTMLElement).closest("input")) this.gesture = true;
    });
    for (const ev of ["pointerup", "pointercancel"]) {
      window.addEventListener(ev, () => {
        this.gesture = false;
        // Let the control's own change event run first, then show the structure that waited.
        setTimeout(() => this.flush(), 0);
      });
    }

    const { store } = ctx;
    store.on("structure", (s) => this.render(s));
    store.on("layers", ({ hidden, solo }) => this.showLayers(hidden, solo));
    store.on("diagnostics", (d) => this.showDiagnostics(d));
    store.on("text", () => {
      if (!store.structure) this.fetchSoon();
    });
    if (store.structure) this.render(store.structure);
    else this.fetchSoon(0);
  }

  // ------------------------------------------------------------------ structure
  /** Fetch the structure ourselves when nobody has yet (on mount, before the first refresh). */
  private fetchSoon(delay = 400): void {
    clearTimeout(this.fetchTimer);
    this.fetchTimer = window.setTimeout(() => void this.fetchStructure(), delay);
  }

  private async fetchStructure(): Promise<void> {
    const { api, store } = this.ctx;
    const text = store.text;
    if (store.structure || !text.trim()) return;
    try {
      const s = await api.json<Structure>("/api/structure", { text });
      if (store.structure || store.text !== text) return;
      store.structure = s;
      this.render(s);
    } catch (e) {
      this.report(e instanceof Error ? e.message : String(e), "error");
    }
  }

  private flush(): void {
    const s = this.deferred;
    this.deferred = null;
    if (s && s === this.ctx.store.structure) this.render(s);
  }

  private render(s: Structure): void {
    this.root.classList.remove("pn-stale");
    this.rerollAll.disabled = s.seeds.length === 0;
    const specs = cardsOf(s);
    const sig = signature(specs);
    if (sig === this.sig && this.cards.length === specs.length) {
      specs.forEach((spec, i) => this.cards[i].update(spec, s.view));
    } else if (this.gesture) {
      this.deferred = s; // never rebuild the control being dragged
    } else {
      this.rebuild(specs, s);
      this.sig = sig;
    }
    this.showLayers(this.ctx.store.hidden, this.ctx.store.solo);
  }

  /** Build every card anew, keeping the scroll position and the focused control. */
  private rebuild(specs: ReturnType<typeof cardsOf>, s: Structure): void {
    const active = document.activeElement as HTMLElement | null;
    const key = active && this.root.contains(active) ? active.dataset.pnKey : undefined;
    const sel = active instanceof HTMLInputElement && active.type === "number" ? [active.selectionStart, active.selectionEnd] : null;
    const top = this.scroll.scrollTop;
    const outer = this.el.scrollTop;
    const env = {
      rows: { sender: this.sender, unitM: () => this.ctx.store.structure?.view.unit_m ?? s.view.unit_m, origin: this.origin },
      seeds: this.seedOps(),
      layers: this.layers,
      collapsed: this.collapsed,
    };
    this.cards = specs.map((spec) => new CardView(spec, s.view, env));
    this.scroll.replaceChildren(...this.cards.map((c) => c.el));
    if (this.toastEl) this.scroll.append(this.toastEl);
    this.applyFilter();
    this.scroll.scrollTop = top;
    this.el.scrollTop = outer;
    if (key && key !== "filter") {
      const again = this.root.querySelector<HTMLElement>(`[data-pn-key="${CSS.escape(key)}"]`);
      if (again) {
        again.focus({ preventScroll: true });
        if (sel && again instanceof HTMLInputElement) {
          try {
            again.setSelectionRange(sel[0], sel[1]);
          } catch {
            /* number inputs may not support selection */
          }
        }
      }
    }
  }

  // ------------------------------------------------------------------ state from others
  private showLayers(hidden: number[], solo: number | null): void {
    for (const c of this.cards) c.showLayerState(hidden, solo);
  }

  private showDiagnostics(d: Diagnostic[]): void {
    const errors = d.filter((x) => x.severity === "error");
    this.root.classList.toggle("pn-stale", errors.length > 0);
    if (errors.length) this.report(`The program has ${errors.length === 1 ? "an error" : `${errors.length} errors`}: the panel shows its last good version`, "warning");
    else if (this.msg.classList.contains("pn-warning") && this.msg.textContent?.startsWith("The program has")) this.report("", "info");
  }

  // ------------------------------------------------------------------ actions
  private seedOp(op: "reroll" | "reroll_all" | "pin", address: string | undefined, label: string): void {
    void this.sender.run(async () => {
      const { api, store, history } = this.ctx;
      const body: Record<string, unknown> = { text: store.text, op };
      if (address !== undefined) body.address = address;
      const r = await api.json<{ text: string; changed?: string[] }>("/api/seeds", body);
      store.setText(r.text, "panel");
      history.commit(label);
      this.report(r.changed && r.changed.length ? `${label}: ${r.changed.length} seed${r.changed.length === 1 ? "" : "s"} changed` : "", "info");
    });
  }

  private seedOps(): SeedOps {
    return {
      reroll: (address, label) => this.seedOp("reroll", address, `reroll ${label}`),
      pin: (address, label) => this.seedOp("pin", address, `pin ${label}`),
    };
  }

  private applyFilter(): void {
    const q = this.filterBox.value.trim().toLowerCase();
    for (const c of this.cards) c.filter(q);
  }

  private foldAll(): void {
    const keys = this.cards.map((c) => c.spec.key);
    const fold = keys.some((k) => !this.collapsed.has(k));
    for (const c of this.cards) {
      c.el.classList.toggle("pn-collapsed", fold);
      if (fold) this.collapsed.add(c.spec.key);
      else this.collapsed.delete(c.spec.key);
    }
  }

  private report(message: string, kind: "error" | "warning" | "info"): void {
    this.msg.textContent = message;
    this.msg.className = `pn-msg pn-${kind}`;
    this.msg.title = message;
    clearTimeout(this.msgTimer);
    if (kind === "info" && message) this.msgTimer = window.setTimeout(() => this.report("", "info"), 4000);
  }

  private toast(text: string, undo: boolean): void {
    this.toastEl?.remove();
    clearTimeout(this.toastTimer);
    const close = (): void => {
      this.toastEl?.remove();
      this.toastEl = null;
    };
    const btn = undo ? h("button", { type: "button", "data-testid": "panel-undo" }, "Undo") : null;
    btn?.addEventListener("click", () => {
      this.ctx.history.undo();
      close();
    });
    this.toastEl = h("div", { class: "pn-toast", role: "status" }, h("span", {}, text), btn);
    this.scroll.append(this.toastEl);
    this.toastTimer = window.setTimeout(close, 6000);
  }
}

/** Mount the structured panel into `el`. */
export function mountPanel(el: HTMLElement, ctx: Ctx): void {
  new Panel(el, ctx);
}
