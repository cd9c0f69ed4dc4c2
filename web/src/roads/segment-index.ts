/**
 * Nearest-road queries: the road edges (node pairs) bucketed in a uniform grid by the cells
 * their bounding boxes cover, so that a click snaps to the road under it however far apart
 * that road's vertices are (a long straight road seen close up has none near the click).
 */
export class SegmentIndex {
  private readonly minX: number;
  private readonly minY: number;
  private readonly cell: number;
  private readonly cols: number;
  private readonly rows: number;
  private readonly cellStart: Uint32Array;
  private readonly items: Uint32Array;

  /**
   * `xy` holds x, y per node, `edges` node pairs (a, b, a, b, ...); both are kept by reference.
   */
  constructor(
    private readonly xy: Float64Array,
    private readonly edges: Uint32Array,
  ) {
    const count = edges.length / 2;
    let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
    let total = 0;
    for (let e = 0; e < count; e++) {
      const [x0, y0, x1, y1] = this.ends(e);
      minX = Math.min(minX, x0, x1);
      maxX = Math.max(maxX, x0, x1);
      minY = Math.min(minY, y0, y1);
      maxY = Math.max(maxY, y0, y1);
      total += Math.hypot(x1 - x0, y1 - y0);
    }
    if (count === 0) minX = minY = maxX = maxY = 0;
    const width = Math.max(maxX - minX, 1e-9);
    const height = Math.max(maxY - minY, 1e-9);
    // Cells about two mean edges wide, at most 1024 a side.
    this.cell = Math.max((2 * total) / Math.max(count, 1), Math.max(width, height) / 1024, 1e-9);
    this.minX = minX;
    this.minY = minY;
    this.cols = Math.floor(width / this.cell) + 1;
    this.rows = Math.floor(height / this.cell) + 1;
    // Two passes over the cells each edge's box covers: count, then fill.
    this.cellStart = new Uint32Array(this.cols * this.rows + 1);
    this.forCells((c) => this.cellStart[c + 1]!++);
    for (let c = 0; c < this.cols * this.rows; c++) this.cellStart[c + 1]! += this.cellStart[c]!;
    const fill = this.cellStart.slice(0, this.cols * this.rows);
    this.items = new Uint32Array(this.cellStart[this.cols * this.rows]!);
    this.forCells((c, e) => (this.items[fill[c]!++] = e));
  }

  /**
   * The road nearest to (x, y) within maxDistance: its edge, the point on it nearest to the
   * query, and that point's distance; null when none is that close.
   */
  nearest(x: number, y: number, maxDistance: number): { edge: number; x: number; y: number; distance: number } | null {
    const gx0 = this.clamp(Math.floor((x - maxDistance - this.minX) / this.cell), this.cols);
    const gx1 = this.clamp(Math.floor((x + maxDistance - this.minX) / this.cell), this.cols);
    const gy0 = this.clamp(Math.floor((y - maxDistance - this.minY) / this.cell), this.rows);
    const gy1 = this.clamp(Math.floor((y + maxDistance - this.minY) / this.cell), this.rows);
    let best: { edge: number; x: number; y: number; distance: number } | null = null;
    for (let gy = gy0; gy <= gy1; gy++)
      for (let gx = gx0; gx <= gx1; gx++) {
        const c = gy * this.cols + gx;
        for (let s = this.cellStart[c]!; s < this.cellStart[c + 1]!; s++) {
          const e = this.items[s]!;
          const [x0, y0, x1, y1] = this.ends(e);
          const dx = x1 - x0, dy = y1 - y0;
          const length2 = dx * dx + dy * dy;
          const t = length2 > 0 ? Math.min(1, Math.max(0, ((x - x0) * dx + (y - y0) * dy) / length2)) : 0;
          const px = x0 + t * dx, py = y0 + t * dy;
          const distance = Math.hypot(px - x, py - y);
          if (distance <= maxDistance && (!best || distance < best.distance)) best = { edge: e, x: px, y: py, distance };
        }
      }
    return best;
  }

  /** The edge's end nodes. */
  nodes(edge: number): [number, number] {
    return [this.edges[2 * edge]!, this.edges[2 * edge + 1]!];
  }

  private ends(e: number): [number, number, number, number] {
    const a = this.edges[2 * e]!, b = this.edges[2 * e + 1]!;
    return [this.xy[2 * a]!, this.xy[2 * a + 1]!, this.xy[2 * b]!, this.xy[2 * b + 1]!];
  }

  private forCells(visit: (cell: number, edge: number) => void): void {
    for (let e = 0; e < this.edges.length / 2; e++) {
      const [x0, y0, x1, y1] = this.ends(e);
      const gx0 = this.clamp(Math.floor((Math.min(x0, x1) - this.minX) / this.cell), this.cols);
      const gx1 = this.clamp(Math.floor((Math.max(x0, x1) - this.minX) / this.cell), this.cols);
      const gy0 = this.clamp(Math.floor((Math.min(y0, y1) - this.minY) / this.cell), this.rows);
      const gy1 = this.clamp(Math.floor((Math.max(y0, y1) - this.minY) / this.cell), this.rows);
      for (let gy = gy0; gy <= gy1; gy++) for (let gx = gx0; gx <= gx1; gx++) visit(gy * this.cols + gx, e);
    }
  }

  private clamp(value: number, size: number): number {
    return Math.min(Math.max(value, 0), size - 1);
  }
}
