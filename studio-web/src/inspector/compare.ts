// The compare tab: two versions of the program (from the session history) evaluated side by
// side under a split slider, a difference image, and SSIM / PSNR from POST /api/compare.
import { ApiError } from "../api";
import type { Ctx } from "../ctx";
import { channel, plane, toImage, type ChannelDef } from "./channels";
import { errorText, field, fmt, h, isShown, nextSeq, onShown, select, setOptions } from "./dom";
import { SplitView } from "./split";
import { inspectorStyle } from "./style";

/** The maps one can compare, by their wire names (as POST /api/compare takes them). */
const MAPS: [string, string][] = [
  ["basecolor", "base colour"],
  ["normal", "normal"],
  ["orm", "ORM (AO, roughness, metallic)"],
  ["height", "height"],
  ["emissive", "emissive"],
  ["alpha", "alpha"],
  ["sheen", "sheen"],
  ["coat", "coat"],
  ["transmission", "transmission"],
  ["subsurface", "subsurface"],
  ["anisotropy", "anisotropy"],
  ["anisotropy_angle", "anisotropy angle"],
  ["ior", "IOR"],
];

/** The packed ORM map shown as it travels (R AO, G roughness, B metallic). */
const ORM: ChannelDef = { id: "orm", label: "ORM", kind: "colour", u8: { map: "orm", comp: 0 } };

function mapDef(name: string): ChannelDef {
  const def = name === "orm" ? ORM : channel(name);
  return { ...def, raw: undefined }; // the wire's own maps: what /api/compare measures
}

interface Metrics {
  psnr: number | string | null;
  ssim: number | null;
  map: string;
}

function time(t: number): string {
  return new Date(t).toLocaleTimeString([], { hour: "2-digit", minute: "2-digit", second: "2-digit" });
}

function psnrText(p: Metrics["psnr"]): string {
  if (typeof p === "number" && Number.isFinite(p)) return `${p.toFixed(2)} dB`;
  return "∞ (identical)";
}

export function mountCompare(el: HTMLElement, ctx: Ctx): void {
  inspectorStyle();
  const selA = select([], undefined, { "data-testid": "compare-a" });
  const selB = select([], undefined, { "data-testid": "compare-b" });
  const map = select(MAPS, "basecolor", { "data-testid": "compare-map" });
  const size = select([["256", "256²"], ["512", "512²"]], "256");
  const diff = h("input", { type: "checkbox", "data-testid": "compare-diff" });
  const gain = select([["1", "×1"], ["4", "×4"], ["16", "×16"]], "4");
  const reload = h("button", { text: "↻ versions", title: "re-read the session's versions" });
  const run = h("button", { text: "Compare", "data-testid": "compare-run" });
  const canvas = h("canvas", { class: "ins-canvas ins-compare", width: 512, height: 512, "data-testid": "compare-canvas" });
  const metrics = h("div", { class: "ins-metrics", "data-testid": "compare-metrics", text: "—" });
  const status = h("div", { class: "ins-dim" });
  const root = h(
    "div",
    { class: "ins-root" },
    h("div", { class: "ins-bar" }, field("A", selA), field("B", selB), reload),
    h("div", { class: "ins-bar" }, field("map", map), field("size", size), field("difference", diff), field("gain", gain), run),
    canvas,
    metrics,
    status,
  );
  el.replaceChildren(root);
  const view = new SplitView(canvas);
  view.draw();

  /** The texts behind the options: the versions when listed, then the current text. */
  let texts: string[] = [];
  let seq = 0;
  let ranKey = "";

  function populate(): void {
    const versions = ctx.history.versions();
    const current = ctx.store.text;
    const opts: [string, string][] = versions.map((v, i) => [String(i), `#${i + 1} ${v.label || "version"} · ${time(v.time)}`]);
    opts.push([String(versions.length), "current text"]);
    // Default: the newest version that differs from the current text (A) vs the current (B).
    let prev = versions.length - 1;
    while (prev >= 0 && versions[prev].text === current) prev--;
    // Keep a version the user picked; "current text" follows the current text.
    const oldCurrent = String(texts.length - 1);
    const keep = (v: string) => (v && v !== oldCurrent && Number(v) < versions.length ? v : undefined);
    const keepA = keep(selA.value);
    const keepB = keep(selB.value);
    texts = [...versions.map((v) => v.text), current];
    setOptions(selA, opts, keepA ?? String(prev >= 0 ? prev : versions.length));
    setOptions(selB, opts, keepB ?? String(versions.length));
  }

  async function compare(force = false): Promise<void> {
    if (!isShown(root)) return;
    // "current text" (the last option) is read now: the editor sits beside this tab.
    const pick = (v: string) => (Number(v) === texts.length - 1 ? ctx.store.text : (texts[Number(v)] ?? ""));
    const a = pick(selA.value);
    const b = pick(selB.value);
    if (!a.trim() || !b.trim()) {
      status.textContent = "nothing to compare yet";
      return;
    }
    const key = JSON.stringify([a, b, map.value, size.value]);
    if (key === ranKey && !force) return;
    const my = (seq = nextSeq());
    const n = Number(size.value);
    const def = mapDef(map.value);
    status.textContent = "evaluating A and B…";
    status.className = "ins-dim";
    metrics.textContent = "…";
    try {
      const [ma, mb] = await Promise.all([
        ctx.api.maps({ text: a, size: n, stream: "compare-a", seq: my }),
        ctx.api.maps({ text: b, size: n, stream: "compare-b", seq: my }),
      ]);
      if (my !== seq) return;
      const pa = plane(ma, def);
      const pb = plane(mb, def);
      const lo = Math.min(pa.lo, pb.lo);
      const hi = Math.max(pa.hi, pb.hi);
      view.set(toImage(pa, lo, hi), toImage(pb, lo, hi));
      view.draw();
      ranKey = key;
      const st = view.stats;
      status.textContent = st
        ? `${a === b ? "same text · " : ""}max |Δ| ${st.max}/255 · ${fmt(st.changed * 100, 3)}% of texels differ`
        : "";
      const m = await ctx.api.json<Metrics>("/api/compare", { a, b, size: n, map: map.value });
      if (my !== seq) return;
      const ssim = typeof m.ssim === "number" ? m.ssim.toFixed(4) : "—";
      metrics.textContent = `${m.map}: SSIM ${ssim} · PSNR ${psnrText(m.psnr)}`;
    } catch (err) {
      if (my !== seq || (err instanceof ApiError && err.status === 409)) return;
      metrics.textContent = "—";
      status.textContent = errorText(err);
      status.className = "ins-err";
    }
  }

  for (const s of [selA, selB, map, size]) s.addEventListener("change", () => void compare());
  diff.addEventListener("change", () => {
    view.diff = diff.checked;
    view.draw();
  });
  gain.addEventListener("change", () => {
    view.gain = Number(gain.value);
    view.updateDiff();
    view.draw();
  });
  reload.addEventListener("click", () => {
    populate();
    void compare();
  });
  run.addEventListener("click", () => {
    populate();
    void compare(true);
  });
  ctx.history.onChange(() => {
    if (isShown(root)) populate();
  });
  onShown(root, () => {
    populate();
    void compare();
  });
  populate();
}
