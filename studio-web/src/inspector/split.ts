// The A/B split view: A left of a draggable divider, B right of it, or the difference image.

export interface DiffStats {
  /** Largest per-component difference, 0..255. */
  max: number;
  /** Fraction of texels with any component differing. */
  changed: number;
}

function toCanvas(img: ImageData): HTMLCanvasElement {
  const c = document.createElement("canvas");
  c.width = img.width;
  c.height = img.height;
  c.getContext("2d")?.putImageData(img, 0, 0);
  return c;
}

/** |A - B| per component times `gain`, and how much differs. */
export function difference(a: ImageData, b: ImageData, gain: number): { image: ImageData; stats: DiffStats } {
  const image = new ImageData(a.width, a.height);
  const d = image.data;
  let max = 0;
  let changed = 0;
  for (let i = 0; i < d.length; i += 4) {
    let any = false;
    for (let c = 0; c < 3; c++) {
      const v = Math.abs(a.data[i + c] - b.data[i + c]);
      if (v > max) max = v;
      if (v) any = true;
      d[i + c] = Math.min(255, v * gain);
    }
    d[i + 3] = 255;
    if (any) changed++;
  }
  return { image, stats: { max, changed: changed / (a.width * a.height) } };
}

export class SplitView {
  /** Divider position, 0..1 of the width. */
  split = 0.5;
  diff = false;
  gain = 4;
  private a: HTMLCanvasElement | null = null;
  private b: HTMLCanvasElement | null = null;
  private d: HTMLCanvasElement | null = null;
  private imgs: [ImageData, ImageData] | null = null;
  stats: DiffStats | null = null;

  constructor(private readonly canvas: HTMLCanvasElement) {
    let dragging = false;
    const move = (e: PointerEvent) => {
      const r = canvas.getBoundingClientRect();
      this.split = Math.min(1, Math.max(0, (e.clientX - r.left) / r.width));
      this.draw();
    };
    canvas.addEventListener("pointerdown", (e) => {
      if (this.diff) return;
      dragging = true;
      canvas.setPointerCapture(e.pointerId);
      move(e);
    });
    canvas.addEventListener("pointermove", (e) => dragging && move(e));
    canvas.addEventListener("pointerup", () => (dragging = false));
    canvas.addEventListener("pointercancel", () => (dragging = false));
  }

  set(a: ImageData, b: ImageData): void {
    this.imgs = [a, b];
    this.a = toCanvas(a);
    this.b = toCanvas(b);
    this.updateDiff();
  }

  updateDiff(): void {
    if (!this.imgs) return;
    const { image, stats } = difference(this.imgs[0], this.imgs[1], this.gain);
    this.d = toCanvas(image);
    this.stats = stats;
  }

  clear(): void {
    this.a = this.b = this.d = null;
    this.imgs = null;
    this.stats = null;
    this.draw();
  }

  draw(): void {
    const g = this.canvas.getContext("2d");
    if (!g) return;
    const W = this.canvas.width;
    const H = this.canvas.height;
    g.fillStyle = "#0b0c0e";
    g.fillRect(0, 0, W, H);
    if (!this.a || !this.b) return;
    g.imageSmoothingEnabled = this.a.width > W;
    if (this.diff && this.d) {
      g.drawImage(this.d, 0, 0, W, H);
      this.label(g, `|A − B| × ${this.gain}`, 6, "left");
      return;
    }
    const x = Math.round(this.split * W);
    const sx = (x / W) * this.a.width;
    if (x > 0) g.drawImage(this.a, 0, 0, sx, this.a.height, 0, 0, x, H);
    if (x < W) g.drawImage(this.b, sx, 0, this.b.width - sx, this.b.height, x, 0, W - x, H);
    g.fillStyle = "#ffb000";
    g.fillRect(x - 1, 0, 2, H);
    g.beginPath();
    g.arc(x, H / 2, 7, 0, Math.PI * 2);
    g.fill();
    this.label(g, "A", 6, "left");
    this.label(g, "B", W - 6, "right");
  }

  private label(g: CanvasRenderingContext2D, text: string, x: number, align: CanvasTextAlign): void {
    g.font = "bold 14px system-ui, sans-serif";
    g.textAlign = align;
    g.textBaseline = "top";
    g.fillStyle = "rgba(0,0,0,0.6)";
    const w = g.measureText(text).width + 8;
    g.fillRect(align === "left" ? x - 3 : x - w + 3, 4, w, 20);
    g.fillStyle = "#fff";
    g.fillText(text, x + (align === "left" ? 1 : -1), 7);
  }
}
