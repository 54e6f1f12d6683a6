// Test and benchmark hooks on window.matloomStudio (docs/studio-api.md, "Test hooks").

interface Shown {
  seq: number;
  t: number;
  /** The pixel ratio the frame was drawn at (below the page's: a cheap frame). */
  ratio?: number;
}

interface StudioHooks {
  frames?: number;
  lastShownAt?: Shown;
  lastRefinedAt?: Shown;
  [key: string]: unknown;
}

function hooks(): StudioHooks {
  const w = window as unknown as { matloomStudio?: StudioHooks };
  w.matloomStudio ??= {};
  w.matloomStudio.frames ??= 0;
  w.matloomStudio.lastRefinedAt ??= { seq: 0, t: 0 };
  return w.matloomStudio;
}

/** Count one drawn 3D frame. `newSeq`: it is the first frame showing maps `newSeq` (at any
 * resolution); `refinedSeq`: the first full-resolution frame showing full-pass maps `refinedSeq`. */
export function frameDrawn(newSeq: number | null, refinedSeq: number | null, ratio: number): void {
  const h = hooks();
  h.frames = (h.frames ?? 0) + 1;
  const t = performance.now();
  if (newSeq !== null) h.lastShownAt = { seq: newSeq, t, ratio };
  if (refinedSeq !== null) h.lastRefinedAt = { seq: refinedSeq, t, ratio };
}

export function ensureHooks(): void {
  hooks();
}
