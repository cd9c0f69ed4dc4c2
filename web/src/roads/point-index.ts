/**
 * Nearest-point queries over many 2D points (projected road nodes): a uniform grid of buckets,
 * searched ring by ring outwards from the query's cell.
 */
export class PointIndex {
  private readonly minX: number;
  private readonly minY: number;
  private readonly cell: number;
  private readonly cols: number;
  private readonly rows: number;
  private readonly cellStart: Uint32Array;
  private readonly items: Uint32Array;

  /** `xy` holds x, y per point; the index keeps a reference, so do not change it afterwards. */
  constructor(private readonly xy: Float64Array) {
    const count = xy.length / 2;
    let minX = Infinity;
    let minY = Infinity;
    let maxX = -Infinity;
    let maxY = -Infinity;
    for (let i = 0; i < count; i++) {
      const x = xy[2 * i]!;
      const y = xy[2 * i + 1]!;
      if (x < minX) minX = x;
      if (x > maxX) maxX = x;
      if (y < minY) minY = y;
      if (y > maxY) maxY = y;
    }
    if (count === 0) minX = minY = maxX = maxY = 0;
    const width = Math.max(maxX - minX, 1e-9);
    const height = Math.max(maxY - minY, 1e-9);
    // About two points per cell.
    this.cell = Math.max(Math.sqrt((width * height * 2) / Math.max(count, 1)), Math.max(width, height) / 1024, 1e-9);
    this.minX = minX;
    this.minY = minY;
    this.cols = Math.floor(width / this.cell) + 1;
    this.rows = Math.floor(height / this.cell) + 1;
    this.cellStart = new Uint32Array(this.cols * this.rows + 1);
    const cellOf = new Uint32Array(count);
    for (let i = 0; i < count; i++) {
      const c = this.cellIndex(xy[2 * i]!, xy[2 * i + 1]!);
      cellOf[i] = c;
      this.cellStart[c + 1]!++;
    }
    for (let c = 0; c < this.cols * this.rows; c++) this.cellStart[c + 1]! += this.cellStart[c]!;
    const fill = this.cellStart.slice(0, this.cols * this.rows);
    this.items = new Uint32Array(count);
    for (let i = 0; i < count; i++) this.items[fill[cellOf[i]!]!++] = i;
  }

  /** The point nearest to (x, y) no farther than maxDistance, or -1. */
  nearest(x: number, y: number, maxDistance = Infinity): number {
    const found = this.kNearest(x, y, 1, maxDistance);
    return found.length > 0 ? found[0]!.index : -1;
  }

  /** Up to k points nearest to (x, y) within maxDistance, nearest first. */
  kNearest(x: number, y: number, k: number, maxDistance = Infinity): { index: number; distance: number }[] {
    const best: { index: number; distance: number }[] = [];
    const cx = this.clamp(Math.floor((x - this.minX) / this.cell), this.cols);
    const cy = this.clamp(Math.floor((y - this.minY) / this.cell), this.rows);
    const maxRing = Math.max(this.cols, this.rows);
    for (let ring = 0; ring <= maxRing; ring++) {
      // Every point in rings beyond this one is at least ring × cell away.
      const reach = (ring - 1) * this.cell;
      if (reach > maxDistance || (best.length === k && best[k - 1]!.distance <= reach)) break;
      for (let gy = cy - ring; gy <= cy + ring; gy++) {
        if (gy < 0 || gy >= this.rows) continue;
        const edgeRow = gy === cy - ring || gy === cy + ring;
        for (let gx = cx - ring; gx <= cx + ring; gx += edgeRow ? 1 : 2 * ring || 1) {
          if (gx < 0 || gx >= this.cols) continue;
          const c = gy * this.cols + gx;
          for (let s = this.cellStart[c]!; s < this.cellStart[c + 1]!; s++) {
            const i = this.items[s]!;
            const distance = Math.hypot(this.xy[2 * i]! - x, this.xy[2 * i + 1]! - y);
            if (distance > maxDistance || (best.length === k && distance >= best[k - 1]!.distance)) continue;
            let at = best.length === k ? k - 1 : best.length;
            while (at > 0 && best[at - 1]!.distance > distance) {
              if (at < k) best[at] = best[at - 1]!;
              at--;
            }
            best[at] = { index: i, distance };
          }
        }
      }
    }
    return best;
  }

  private cellIndex(x: number, y: number): number {
    const gx = this.clamp(Math.floor((x - this.minX) / this.cell), this.cols);
    const gy = this.clamp(Math.floor((y - this.minY) / this.cell), this.rows);
    return gy * this.cols + gx;
  }

  private clamp(value: number, size: number): number {
    return value < 0 ? 0 : value >= size ? size - 1 : value;
  }
}
