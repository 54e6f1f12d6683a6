// What every part of the page is given when it mounts.
import type { Api } from "./api";
import type { Store } from "./store";

export interface HistoryApi {
  /** Record the current text as a version (called on commit points: drag end, pause in typing). */
  commit(label?: string): void;
  undo(): void;
  redo(): void;
  canUndo(): boolean;
  canRedo(): boolean;
  versions(): { text: string; label: string; time: number }[];
  permalink(): Promise<string>;
  /** Called after every change of the steps or the version list; returns the unsubscribe. */
  onChange(fn: () => void): () => void;
}

export interface Ctx {
  api: Api;
  store: Store;
  history: HistoryApi;
  /** Set by the 3D view on software GL (SwiftShader, llvmpipe: the rasteriser runs on the same
   *  CPU cores as the server): resolves once the frame showing maps `seq` has been presented, or
   *  at once when nothing will draw it. Live waits on it before a drag's full pass, so the
   *  server's 512 px evaluation does not slow down the first frame. Absent on a GPU. */
  presented?: (seq: number) => Promise<void>;
  /** Session facts from GET /api/session. */
  session: {
    version: string;
    root: string;
    files: string[];
    opened: string | null;
    text: string;
    model: boolean;
    blender: boolean;
    presets: string[];
    limits: Record<string, number>;
  };
}

/** Each part exports one of these. */
export type Mount = (el: HTMLElement, ctx: Ctx) => void;
