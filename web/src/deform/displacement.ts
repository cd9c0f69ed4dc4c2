import { PointIndex } from '../roads/point-index';
import { SegmentIndex } from '../roads/segment-index';

const NEIGHBOURS = 8;

/**
 * The deformation as a displacement field between original and deformed node positions (frame
 * coordinates), interpolated by inverse distance weighting of the nearest nodes. It places things
 * defined on the original map (focus circles) on the deformed one, and back.
 */
export class Displacement {
  private deformedIndex?: PointIndex;
  private roads?: SegmentIndex;

  constructor(
    private readonly original: Float64Array,
    private readonly originalIndex: PointIndex,
    readonly deformed: Float64Array,
    /** The road edges as node pairs (RoadGraph.edges). */
    private readonly edges: Uint32Array,
  ) {}

  get identity(): boolean {
    return this.original === this.deformed;
  }

  /** Where an original point is drawn on the deformed map. */
  forward(x: number, y: number): [number, number] {
    if (this.identity) return [x, y];
    const [dx, dy] = this.shift(this.originalIndex, x, y);
    return [x + dx, y + dy];
  }

  /** The original point drawn at (x, y) of the deformed map (approximately). */
  inverse(x: number, y: number): [number, number] {
    if (this.identity) return [x, y];
    this.deformedIndex ??= new PointIndex(this.deformed);
    const [dx, dy] = this.shift(this.deformedIndex, x, y);
    return [x - dx, y - dy];
  }

  /** The node drawn nearest to (x, y) of the deformed map, within maxDistance frame units; -1 if none. */
  nearestDrawn(x: number, y: number, maxDistance: number): number {
    if (this.identity) return this.originalIndex.nearest(x, y, maxDistance);
    this.deformedIndex ??= new PointIndex(this.deformed);
    return this.deformedIndex.nearest(x, y, maxDistance);
  }

  /**
   * The road vertex at the end nearer to the point of the road drawn nearest to (x, y), within
   * maxDistance frame units of the road; -1 if no road is that close.
   */
  nearestRoadVertex(x: number, y: number, maxDistance: number): number {
    this.roads ??= new SegmentIndex(this.deformed, this.edges);
    const hit = this.roads.nearest(x, y, maxDistance);
    if (!hit) return -1;
    const [a, b] = this.roads.nodes(hit.edge);
    const d = (node: number) => Math.hypot(this.deformed[2 * node]! - hit.x, this.deformed[2 * node + 1]! - hit.y);
    return d(a) <= d(b) ? a : b;
  }

  private shift(index: PointIndex, x: number, y: number): [number, number] {
    const near = index.kNearest(x, y, NEIGHBOURS);
    let sx = 0;
    let sy = 0;
    let sw = 0;
    for (const { index: i, distance } of near) {
      if (distance < 1e-9) return [this.deformed[2 * i]! - this.original[2 * i]!, this.deformed[2 * i + 1]! - this.original[2 * i + 1]!];
      const w = 1 / (distance * distance);
      sx += w * (this.deformed[2 * i]! - this.original[2 * i]!);
      sy += w * (this.deformed[2 * i + 1]! - this.original[2 * i + 1]!);
      sw += w;
    }
    return sw > 0 ? [sx / sw, sy / sw] : [0, 0];
  }
}
