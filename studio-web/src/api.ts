// The studio's HTTP client: JSON calls and the binary maps format (docs/studio-api.md).

export class ApiError extends Error {
  constructor(
    message: string,
    readonly status: number,
    readonly body: Record<string, unknown> = {},
  ) {
    super(message);
  }
}

export interface MapInfo {
  name: string;
  dtype: "u8" | "f32";
  channels: number;
  offset: number;
  length: number;
}

export interface MapsHeader {
  width: number;
  height: number;
  seq: number;
  stream: string;
  pass: "preview" | "full";
  eval_ms: number;
  total_ms: number;
  view: { x1: number; y1: number; x2: number; y2: number; tileable: boolean; unit_m: number | null };
  unit_m: number | null;
  tileable: boolean;
  seam: Record<string, number> | null;
  maps: MapInfo[];
  /** With `values` in the request: the hash of the edited text evaluated (as /api/set's). */
  text_sha?: string;
  /** The emission map is an sRGB texture times this strength (0 when nothing glows). */
  emissive_scale?: number;
  /** Height min and max in coordinate units. */
  height_range?: [number, number];
}

/** Decoded maps: u8 maps as Uint8Array, f32 maps as Float32Array, row 0 = top. */
export interface Maps {
  header: MapsHeader;
  u8: Record<string, Uint8Array>;
  f32: Record<string, Float32Array>;
  channels: Record<string, number>;
}

export interface EvaluateRequest {
  text: string;
  size: number;
  stream?: string;
  seq?: number;
  hidden?: number[];
  solo?: number | null;
  channels?: string[];
  /** Which pass this is (the server may also tell by size). */
  pass?: "preview" | "full";
  /** Evaluate the text /api/set makes of `{text, values}` (the header gets its `text_sha`). */
  values?: Record<string, unknown>;
  /** Also render the lit preview. */
  lit?: boolean;
}

export function decodeMaps(buf: ArrayBuffer): Maps {
  const bytes = new Uint8Array(buf);
  const magic = String.fromCharCode(...bytes.subarray(0, 4));
  if (magic !== "MLMP") throw new ApiError("not a MatLoom maps reply", 0);
  const n = new DataView(buf).getUint32(4, true);
  const header = JSON.parse(new TextDecoder().decode(bytes.subarray(8, 8 + n))) as MapsHeader;
  const maps: Maps = { header, u8: {}, f32: {}, channels: {} };
  for (const m of header.maps) {
    maps.channels[m.name] = m.channels;
    if (m.dtype === "u8") maps.u8[m.name] = new Uint8Array(buf, m.offset, m.length);
    else maps.f32[m.name] = new Float32Array(buf, m.offset, m.length / 4);
  }
  return maps;
}

export class Api {
  constructor(readonly token: string) {}

  private headers(): Record<string, string> {
    return { "Content-Type": "application/json", "X-MatLoom-Token": this.token };
  }

  private async fail(r: Response): Promise<never> {
    let body: Record<string, unknown> = {};
    try {
      body = await r.json();
    } catch {
      /* not JSON */
    }
    throw new ApiError(String(body.error ?? r.statusText), r.status, body);
  }

  async json<T = Record<string, unknown>>(path: string, body?: unknown): Promise<T> {
    const r = await fetch(path, {
      method: body === undefined ? "GET" : "POST",
      headers: this.headers(),
      body: body === undefined ? undefined : JSON.stringify(body),
    });
    if (!r.ok) return this.fail(r);
    return (await r.json()) as T;
  }

  async blob(path: string, body: unknown): Promise<Blob> {
    const r = await fetch(path, { method: "POST", headers: this.headers(), body: JSON.stringify(body) });
    if (!r.ok) return this.fail(r);
    return r.blob();
  }

  /** Evaluate a program; rejects with ApiError status 409 when superseded by a newer seq. */
  async maps(req: EvaluateRequest, signal?: AbortSignal): Promise<Maps> {
    const r = await fetch("/api/evaluate", {
      method: "POST",
      headers: this.headers(),
      body: JSON.stringify(req),
      signal,
    });
    if (!r.ok) return this.fail(r);
    return decodeMaps(await r.arrayBuffer());
  }

  events(job: string): EventSource {
    return new EventSource(`/api/jobs/${encodeURIComponent(job)}/events?token=${encodeURIComponent(this.token)}`);
  }
}
