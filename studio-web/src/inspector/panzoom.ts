// Zoom (wheel, around the cursor) and pan (drag) of an image on a canvas; double-click resets.

export class PanZoom {
  scale = 1;
  ox = 0;
  oy = 0;
  private iw = 1;
  private ih = 1;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly redraw: () => void,
  ) {
    let drag: { x: number; y: number; ox: number; oy: number } | null = null;
    canvas.addEventListener("wheel", (e) => {
      e.preventDefault();
      const [cx, cy] = this.canvasPoint(e);
      const k = Math.exp(-e.deltaY * 0.0015);
      const s = Math.min(64, Math.max(this.fitScale() * 0.5, this.scale * k));
      this.ox = cx - ((cx - this.ox) * s) / this.scale;
      this.oy = cy - ((cy - this.oy) * s) / this.scale;
      this.scale = s;
      this.redraw();
    }, { passive: false });
    canvas.addEventListener("pointerdown", (e) => {
      if (e.button !== 0) return;
      const [x, y] = this.canvasPoint(e);
      drag = { x, y, ox: this.ox, oy: this.oy };
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener("pointermove", (e) => {
      if (!drag) return;
      const [x, y] = this.canvasPoint(e);
      this.ox = drag.ox + x - drag.x;
      this.oy = drag.oy + y - drag.y;
      this.redraw();
    });
    const end = () => (drag = null);
    canvas.addEventListener("pointerup", end);
    canvas.addEventListener("pointercancel", end);
    canvas.addEventListener("dblclick", () => {
      this.fit();
      this.redraw();
    });
  }

  /** The image's size; refits when it changed. */
  setImage(w: number, h: number): void {
    if (w === this.iw && h === this.ih) return;
    this.iw = w;
    this.ih = h;
    this.fit();
  }

  fitScale(): number {
    return Math.min(this.canvas.width / this.iw, this.canvas.height / this.ih);
  }

  fit(): void {
    this.scale = this.fitScale();
    this.ox = (this.canvas.width - this.iw * this.scale) / 2;
    this.oy = (this.canvas.height - this.ih * this.scale) / 2;
  }

  /** Event position in canvas pixels (the canvas may be shown scaled by CSS). */
  canvasPoint(e: MouseEvent): [number, number] {
    const r = this.canvas.getBoundingClientRect();
    return [((e.clientX - r.left) * this.canvas.width) / r.width, ((e.clientY - r.top) * this.canvas.height) / r.height];
  }

  /** The texel under an event, or null outside the image. */
  texel(e: MouseEvent): [number, number] | null {
    const [cx, cy] = this.canvasPoint(e);
    const x = Math.floor((cx - this.ox) / this.scale);
    const y = Math.floor((cy - this.oy) / this.scale);
    if (x < 0 || y < 0 || x >= this.iw || y >= this.ih) return null;
    return [x, y];
  }

  draw(g: CanvasRenderingContext2D, src: CanvasImageSource): void {
    g.fillStyle = "#0b0c0e";
    g.fillRect(0, 0, this.canvas.width, this.canvas.height);
    g.imageSmoothingEnabled = this.scale < 1;
    g.drawImage(src, this.ox, this.oy, this.iw * this.scale, this.ih * this.scale);
  }
}
