// The panel's cards as data: which parameters and seeds each card holds, from a Structure.
import type { Param, Structure } from "../store";
import type { SeedInfo } from "./seeds";

export interface CardSpec {
  /** Stable across refreshes while the program's shape stays: "view", "define:NAME", "layer:N", "other". */
  key: string;
  kind: "view" | "define" | "layer" | "other";
  title: string;
  /** The source line (for defines and layers), shown small. */
  text: string;
  line: number;
  /** Layer index (1-based, bottom first) for layer cards. */
  index: number;
  /** Words the card's parameter labels start with (dropped from the row labels). */
  prefix: string;
  params: Param[];
  /** Automatic seeds (not written as literals) owned by this card. */
  autoSeeds: SeedInfo[];
}

/** `groutWidth` -> `grout width` (matloom.lang.params.words). */
export function words(name: string): string {
  return name
    .replace(/(?<=[a-z0-9])(?=[A-Z])/g, " ")
    .replace(/_/g, " ")
    .toLowerCase()
    .split(/\s+/)
    .filter(Boolean)
    .join(" ");
}

/** The card key that owns an address: `define:NAME...` -> `define:NAME`, `layer:N...` -> `layer:N`. */
export function ownerOf(address: string): string {
  const m = /^(define|layer):([A-Za-z0-9_]+)/.exec(address);
  if (m) return `${m[1]}:${m[2]}`;
  if (address.startsWith("view")) return "view";
  return "other";
}

export function cardsOf(s: Structure): CardSpec[] {
  const byAddress = new Map(s.params.map((p) => [p.address, p]));
  const used = new Set<string>();
  const take = (addresses: string[]): Param[] => {
    const out: Param[] = [];
    for (const a of addresses) {
      const p = byAddress.get(a);
      if (p && !used.has(a)) {
        used.add(a);
        out.push(p);
      }
    }
    return out;
  };
  const cards: CardSpec[] = [];
  const view: CardSpec = { key: "view", kind: "view", title: "View", text: "", line: 0, index: 0, prefix: "", params: [], autoSeeds: [] };
  cards.push(view);
  for (const d of s.defines) {
    cards.push({
      key: `define:${d.name}`,
      kind: "define",
      title: d.name,
      text: d.text,
      line: d.line,
      index: 0,
      prefix: words(d.name),
      params: take(d.params),
      autoSeeds: [],
    });
  }
  for (const l of s.layers) {
    cards.push({
      key: `layer:${l.index}`,
      kind: "layer",
      title: l.label,
      text: l.text,
      line: l.line,
      index: l.index,
      prefix: words(l.label),
      params: take(l.params),
      autoSeeds: [],
    });
  }
  mergeColourSlots(cards, s);
  const byKey = new Map(cards.map((c) => [c.key, c]));
  const other: CardSpec = { key: "other", kind: "other", title: "Other", text: "", line: 0, index: 0, prefix: "", params: [], autoSeeds: [] };
  // Parameters no card listed go to their owner's card by address, else to "Other".
  for (const p of s.params) {
    if (used.has(p.address)) continue;
    used.add(p.address);
    (byKey.get(ownerOf(p.address)) ?? other).params.push(p);
  }
  for (const seed of s.seeds) {
    if (byAddress.has(seed.address)) continue; // written: its row is the parameter's
    (byKey.get(ownerOf(seed.address)) ?? other).autoSeeds.push(seed);
  }
  if (other.params.length || other.autoSeeds.length) cards.push(other);
  return cards;
}

/** A colour slot (three Defines C_r, C_g, C_b, one colour parameter `define:C`) becomes one
 * card `define:C` in place of the three. */
function mergeColourSlots(cards: CardSpec[], s: Structure): void {
  for (const p of s.params) {
    const m = /^define:(\w+)$/.exec(p.address);
    if (!m || p.kind !== "colour") continue;
    const name = m[1];
    const parts = ["r", "g", "b"].map((c) => cards.findIndex((k) => k.key === `define:${name}_${c}`));
    if (parts.some((i) => i < 0)) continue;
    const [r, g, b] = parts.map((i) => cards[i]);
    const merged: CardSpec = {
      ...r,
      key: `define:${name}`,
      title: name,
      text: [r.text, g.text, b.text].join("  "),
      prefix: words(name),
      params: [...r.params, ...g.params, ...b.params],
      autoSeeds: [...r.autoSeeds, ...g.autoSeeds, ...b.autoSeeds],
    };
    cards[parts[0]] = merged;
    for (const gone of [g.key, b.key]) cards.splice(cards.findIndex((k) => k.key === gone), 1);
  }
}

/** What decides a rebuild: the cards and the addresses (and kinds) they hold. Values, labels,
 * ranges and texts update in place. */
export function signature(cards: CardSpec[]): string {
  return JSON.stringify(
    cards.map((c) => [c.key, c.params.map((p) => `${p.address}|${p.kind}`), c.autoSeeds.map((s) => s.address)]),
  );
}
