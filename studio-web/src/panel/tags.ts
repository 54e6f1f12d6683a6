// Small tags naming the output maps a parameter affects.

const SHORT: Record<string, string> = {
  basecolor: "colour",
  roughness: "rough",
  metallic: "metal",
  anisotropy: "aniso",
  anisotropy_angle: "aniso°",
  transmission: "trans",
  subsurface: "sss",
  emissive: "emit",
  alpha: "alpha",
  normal: "normal",
  height: "height",
};

/** At or above this many maps the tags read "all maps". */
const ALL = 12;
/** At most this many tags are shown; the rest count as "+N". */
const SHOWN = 3;

export function affectTags(affects: string[]): HTMLElement {
  const box = document.createElement("span");
  box.className = "pn-tags";
  box.title = affects.length ? `affects: ${affects.join(", ")}` : "affects no map";
  const add = (text: string, cls = ""): void => {
    const t = document.createElement("span");
    t.className = `pn-tag ${cls}`.trim();
    t.textContent = text;
    box.append(t);
  };
  if (affects.length >= ALL) add("all maps", "pn-tag-all");
  else {
    const n = affects.length <= SHOWN + 1 ? affects.length : SHOWN;
    for (const a of affects.slice(0, n)) add(SHORT[a] ?? a, `pn-tag-${a}`);
    if (affects.length > n) add(`+${affects.length - n}`, "pn-tag-more");
  }
  return box;
}
