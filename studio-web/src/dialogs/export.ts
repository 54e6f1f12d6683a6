// The export dialog: the options of `matloom render` (size, bits, format, tileable, presets,
// unit, name) into a folder inside the opened one (POST /api/export), or as a zip download
// (POST /api/export.zip); the Blender flat / staged renders when Blender is available.
import type { Ctx } from "../ctx";
import { errorText, h } from "../inspector/dom";
import { mountBlender } from "./blender";
import { saveBlob } from "./download";
import { dialogStyle } from "./style";

/** `matloom render --format` choices, with what each writes. */
const FORMATS: [string, string][] = [
  ["png", "png — PNG maps (ior, height, emissive as float32 EXR)"],
  ["exr", "exr — every map as EXR"],
  ["png16", "png16 — png plus a 16-bit height16.png"],
];

interface ExportReply {
  folder: string;
  files: string[];
  manifest?: Record<string, unknown>;
}

function stem(path: string | null): string {
  if (!path) return "material";
  const base = path.split("/").pop() ?? path;
  return base.replace(/\.mat$/i, "") || "material";
}

function row(label: string, control: HTMLElement, title = ""): HTMLElement[] {
  return [h("span", { text: label, title }), control];
}

export function mountExport(el: HTMLElement, ctx: Ctx): void {
  dialogStyle();
  const name0 = stem(ctx.store.path ?? ctx.session.opened);
  const size = h("input", { type: "number", min: 1, max: 8192, step: 1, value: 512, list: "dlg-sizes", "data-testid": "export-size" });
  const sizes = h("datalist", { id: "dlg-sizes" }, ...[256, 512, 1024, 2048, 4096].map((n) => h("option", { value: n })));
  const bits = h("select", { "data-testid": "export-bits" }, h("option", { value: "8", text: "8" }), h("option", { value: "16", text: "16" }));
  const format = h("select", { "data-testid": "export-format" }, ...FORMATS.map(([v, l]) => h("option", { value: v, text: l })));
  const precision = h("select", { "data-testid": "export-exr-precision" }, h("option", { value: "half", text: "half" }), h("option", { value: "float", text: "float (32-bit)" }));
  const normal = h(
    "select",
    { "data-testid": "export-normal" },
    h("option", { value: "gl", text: "gl — OpenGL (+Y)" }),
    h("option", { value: "dx", text: "dx — DirectX (−Y)" }),
    h("option", { value: "both", text: "both" }),
  );
  const tileable = h("input", { type: "checkbox", "data-testid": "export-tileable" });
  const constants = h("input", { type: "checkbox", "data-testid": "export-constants" });
  const preview = h("input", { type: "checkbox", checked: true, "data-testid": "export-preview" });
  const unit = h("input", { type: "number", min: 1e-9, max: 1e9, step: "any", placeholder: "the program's", "data-testid": "export-unit" });
  const name = h("input", { type: "text", value: name0, "data-testid": "export-name" });
  const out = h("input", { type: "text", value: `renders/${name0}`, "data-testid": "export-out" });
  const presetBoxes = ctx.session.presets.map((p) => h("input", { type: "checkbox", value: p, "data-testid": `export-preset-${p}` }));
  const presets = h(
    "div",
    { class: "dlg-row" },
    ...presetBoxes.map((b) => h("label", { class: "dlg-check" }, b, b.value)),
  );
  if (!presetBoxes.length) presets.append(h("span", { class: "dlg-dim", text: "none offered by this server" }));
  const run = h("button", { class: "dlg-primary", text: "Export", "data-testid": "export-run" });
  const zip = h("button", { text: "Download zip", "data-testid": "export-zip" });
  const status = h("div", { class: "dlg-dim", "data-testid": "export-status" });
  const result = h("div", { "data-testid": "export-result" });

  const box = h(
    "div",
    { class: "dlg-box" },
    h("h3", { text: "export (matloom render)" }),
    h(
      "div",
      { class: "dlg-grid" },
      ...row("size", size, "square size in pixels"),
      ...row("format", format),
      ...row("bits", bits, "bit depth of every PNG map"),
      ...row("EXR", precision, "sample type of --format exr files"),
      ...row("normal", normal, "normal map convention(s)"),
      ...row("tileable", h("label", { class: "dlg-check" }, tileable, "repeat seamlessly with the View"), "make every map repeat seamlessly with the View (as View(..., tileable=True))"),
      ...row("constants", h("label", { class: "dlg-check" }, constants, "record constant maps as values"), "record constant maps in material.json instead of writing their files"),
      ...row("preview", h("label", { class: "dlg-check" }, preview, "write preview.png"), "also write preview.png, the quick shaded swatch"),
      ...row("presets", presets, "engine / interchange presets, each in its subfolder"),
      ...row("unit_m", unit, "metres per coordinate unit (blank: the program's View unit_m)"),
      ...row("name", name, "material name for preset files"),
      ...row("folder", out, "relative to the opened folder; MatLoom never touches files it did not write"),
    ),
    h("div", { class: "dlg-row" }, run, zip, status),
    result,
    sizes,
  );
  const root = h("div", { class: "dlg-root" }, box);
  if (ctx.session.blender) root.append(mountBlender(ctx));
  el.replaceChildren(root);

  const syncUnit = () => {
    const u = ctx.store.structure?.view.unit_m;
    unit.placeholder = u ? `the program's: ${u}` : "the program's (none)";
  };
  syncUnit();
  ctx.store.on("structure", syncUnit);
  const syncFormat = () => (precision.disabled = format.value !== "exr");
  syncFormat();
  format.addEventListener("change", syncFormat);

  function body(): Record<string, unknown> | null {
    const n = Number(size.value);
    if (!Number.isInteger(n) || n < 1 || n > 8192) {
      fail("size: a whole number of pixels, 1 to 8192");
      return null;
    }
    const u = unit.value.trim() === "" ? null : Number(unit.value);
    if (u !== null && !(u >= 1e-9 && u <= 1e9)) {
      fail("unit_m: metres per unit, 1e-9 to 1e9 (or blank for the program's)");
      return null;
    }
    return {
      text: ctx.store.text,
      size: n,
      bits: Number(bits.value),
      format: format.value,
      exr_precision: precision.value,
      normal: normal.value,
      constants: constants.checked,
      preview: preview.checked,
      tileable: tileable.checked,
      presets: presetBoxes.filter((b) => b.checked).map((b) => b.value),
      unit_m: u,
      name: name.value.trim() || name0,
    };
  }

  function fail(message: string): void {
    status.textContent = message;
    status.className = "dlg-err";
  }

  function busy(on: boolean, message = ""): void {
    run.disabled = zip.disabled = on;
    status.textContent = message;
    status.className = "dlg-dim";
  }

  run.addEventListener("click", async () => {
    const b = body();
    if (!b) return;
    const folder = out.value.trim();
    if (!folder) return fail("folder: name a folder inside the opened one");
    busy(true, "rendering…");
    result.replaceChildren();
    const t0 = performance.now();
    try {
      const r = await ctx.api.json<ExportReply>("/api/export", { ...b, out: folder });
      busy(false, `wrote ${r.files.length} files in ${((performance.now() - t0) / 1000).toFixed(1)} s`);
      status.className = "dlg-ok";
      const manifest = r.manifest
        ? h("details", {}, h("summary", { class: "dlg-dim", text: "manifest" }), h("pre", { class: "dlg-pre", text: JSON.stringify(r.manifest, null, 2) }))
        : null;
      result.replaceChildren(
        h("div", { class: "dlg-dim", text: `into ${r.folder}` }),
        h("ul", { class: "dlg-files" }, ...r.files.map((f) => h("li", { text: f }))),
        manifest ?? "",
      );
    } catch (err) {
      busy(false);
      fail(errorText(err));
    }
  });

  zip.addEventListener("click", async () => {
    const b = body();
    if (!b) return;
    busy(true, "rendering the zip…");
    try {
      const blob = await ctx.api.blob("/api/export.zip", b);
      saveBlob(blob, `${String(b.name)}.zip`);
      busy(false, `downloaded ${String(b.name)}.zip (${(blob.size / 1024).toFixed(0)} KiB)`);
      status.className = "dlg-ok";
    } catch (err) {
      busy(false);
      fail(errorText(err));
    }
  });
}
