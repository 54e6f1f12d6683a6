// Test and benchmark hooks on window.matloomStudio (docs/studio-api.md, "Test hooks").

interface StudioHooks {
  frames?: number;
  lastShownAt?: { seq: number; t: number };
  [key: string]: unknown;
}

function hooks(): StudioHooks {
  const w = window as unknown as { matloomStudio?: StudioHooks };
  w.matloomStudio ??= {};
  w.matloomStudio.frames ??= 0;
  return w.matloomStudio;
}

/** Count one drawn 3D frame; when it is the first frame showing maps `seq`, record when. */
export function frameDrawn(newSeq: number | null): void {
  const h = hooks();
  h.frames = (h.frames ?? 0) + 1;
  if (newSeq !== null) h.lastShownAt = { seq: newSeq, t: performance.now() };
}

export function ensureHooks(): void {
  hooks();
}
