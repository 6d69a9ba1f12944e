// The left image with the operator's ROI (drag) and optional point (click
// inside the ROI), in image pixels whatever the on-screen size.
const MIN_ROI = 8;  // SELECT_ROI w_px/h_px minimum

export class RoiCanvas {
  constructor(canvas, onChange) {
    this.canvas = canvas;
    this.onChange = onChange;
    this.image = null;  // ImageData
    this.roi = null;    // {x, y, w, h}
    this.click = null;  // {u, v}
    this.drag = null;
    canvas.addEventListener('mousedown', (e) => this.down(e));
    window.addEventListener('mousemove', (e) => this.move(e));
    window.addEventListener('mouseup', (e) => this.up(e));
  }

  setImage(imageData) {
    this.image = imageData;
    this.canvas.width = imageData.width;
    this.canvas.height = imageData.height;
    if (this.roi && (this.roi.x + this.roi.w > imageData.width || this.roi.y + this.roi.h > imageData.height))
      this.roi = this.click = null;
    this.draw();
    this.onChange();
  }

  clearClick() { this.click = null; this.draw(); this.onChange(); }

  pixel(e) {
    const r = this.canvas.getBoundingClientRect();
    const x = Math.floor((e.clientX - r.left) * this.canvas.width / r.width);
    const y = Math.floor((e.clientY - r.top) * this.canvas.height / r.height);
    return { x: Math.max(0, Math.min(this.canvas.width - 1, x)),
             y: Math.max(0, Math.min(this.canvas.height - 1, y)) };
  }

  down(e) {
    if (!this.image || e.button !== 0) return;
    e.preventDefault();
    this.drag = { start: this.pixel(e), now: this.pixel(e) };
  }

  move(e) {
    if (!this.drag) return;
    this.drag.now = this.pixel(e);
    this.draw();
  }

  up(e) {
    if (!this.drag) return;
    const { start } = this.drag;
    const end = this.pixel(e);
    this.drag = null;
    if (Math.abs(end.x - start.x) < 3 && Math.abs(end.y - start.y) < 3) {
      // A click: the optional point, which must lie inside the ROI.
      const r = this.roi;
      if (r && end.x >= r.x && end.x < r.x + r.w && end.y >= r.y && end.y < r.y + r.h)
        this.click = { u: end.x, v: end.y };
    } else {
      const roi = { x: Math.min(start.x, end.x), y: Math.min(start.y, end.y),
                    w: Math.abs(end.x - start.x) + 1, h: Math.abs(end.y - start.y) + 1 };
      if (roi.w >= MIN_ROI && roi.h >= MIN_ROI) { this.roi = roi; this.click = null; }
    }
    this.draw();
    this.onChange();
  }

  draw() {
    const ctx = this.canvas.getContext('2d');
    if (!this.image) return;
    ctx.putImageData(this.image, 0, 0);
    const lw = Math.max(1, this.canvas.width / 400);
    ctx.lineWidth = 2 * lw;
    if (this.roi) {
      ctx.strokeStyle = '#ffc800';
      ctx.strokeRect(this.roi.x, this.roi.y, this.roi.w, this.roi.h);
    }
    if (this.drag) {
      const a = this.drag.start, b = this.drag.now;
      ctx.setLineDash([6 * lw, 4 * lw]);
      ctx.strokeStyle = '#ffe680';
      ctx.strokeRect(Math.min(a.x, b.x), Math.min(a.y, b.y), Math.abs(b.x - a.x), Math.abs(b.y - a.y));
      ctx.setLineDash([]);
    }
    if (this.click) {
      const s = 8 * lw;
      ctx.strokeStyle = '#00e5ff';
      ctx.beginPath();
      ctx.moveTo(this.click.u - s, this.click.v); ctx.lineTo(this.click.u + s, this.click.v);
      ctx.moveTo(this.click.u, this.click.v - s); ctx.lineTo(this.click.u, this.click.v + s);
      ctx.stroke();
    }
  }
}
