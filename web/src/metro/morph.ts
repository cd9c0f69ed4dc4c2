/** A point in the map's frame units. */
export type Pt = [number, number];

/**
 * Everything of a metro map that moves between the geographic and the octilinear drawing, in
 * the map's frame units. Edges are in MetroLayers' edge order.
 */
export interface Geometry {
  stations: Map<string, Pt>;
  edges: Pt[][];
  pois: Map<string, Pt>;
  /** The warp mesh's rows and columns and the network's outline; empty when unknown. */
  grid: Pt[][];
  /** Per edge, its lines left to right along it (the layout's line order); absent: as listed. */
  orders?: (string[] | undefined)[];
}

export const easeInOutCubic = (t: number): number => (t < 0.5 ? 4 * t * t * t : 1 - (-2 * t + 2) ** 3 / 2);

const lerp = (a: Pt, b: Pt, t: number): Pt => [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];

/** Each vertex's share of the way along the polyline, 0 at the first and 1 at the last. */
function arcParameters(points: Pt[]): number[] {
  const out = [0];
  let total = 0;
  for (let i = 1; i < points.length; i++) {
    total += Math.hypot(points[i]![0] - points[i - 1]![0], points[i]![1] - points[i - 1]![1]);
    out.push(total);
  }
  // A polyline of length 0 (one station drawn twice) is parameterised by vertex count.
  return total > 0 ? out.map((length) => length / total) : out.map((_, i) => i / Math.max(1, points.length - 1));
}

/** The point a share u of the way along a polyline with parameters `params`. */
function pointAt(points: Pt[], params: number[], u: number): Pt {
  if (points.length === 1) return points[0]!;
  let lo = 0;
  let hi = params.length - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (params[mid]! <= u) lo = mid;
    else hi = mid;
  }
  const span = params[hi]! - params[lo]!;
  return lerp(points[lo]!, points[hi]!, span > 0 ? (u - params[lo]!) / span : 0);
}

/**
 * Both polylines sampled at the union of their vertices' arc-length parameters: the same
 * number of points, and each keeps every one of its own vertices (so the morph starts and ends
 * on the exact shapes: sharp octilinear bends, the full geographic track).
 */
export function pairPolylines(a: Pt[], b: Pt[]): [Pt[], Pt[]] {
  if (a.length === 0 || b.length === 0) return [b.length ? b : a, b.length ? b : a];
  const pa = arcParameters(a);
  const pb = arcParameters(b);
  const params = [...new Set([...pa, ...pb])].sort((x, y) => x - y);
  return [params.map((u) => pointAt(a, pa, u)), params.map((u) => pointAt(b, pb, u))];
}

/** Interpolates between two geometries; at(1) is the target itself. */
export class Morph {
  private readonly edgePairs: [Pt[], Pt[]][];
  private readonly gridPairs: [Pt[], Pt[]][] | null;

  constructor(
    private readonly from: Geometry,
    private readonly to: Geometry,
  ) {
    this.edgePairs = to.edges.map((target, i) => pairPolylines(from.edges[i] ?? target, target));
    // Meshes of another size (or none yet) are not morphed: the target's shows at once.
    this.gridPairs =
      from.grid.length === to.grid.length && to.grid.length > 0 ? to.grid.map((target, i) => pairPolylines(from.grid[i]!, target)) : null;
  }

  at(t: number): Geometry {
    if (t >= 1) return this.to;
    const points = (source: Map<string, Pt>, target: Map<string, Pt>) => {
      const out = new Map<string, Pt>();
      for (const [id, end] of target) {
        const start = source.get(id);
        out.set(id, start ? lerp(start, end, t) : end);
      }
      return out;
    };
    const polylines = (pairs: [Pt[], Pt[]][]) => pairs.map(([a, b]) => a.map((p, i) => lerp(p, b[i]!, t)));
    return {
      stations: points(this.from.stations, this.to.stations),
      pois: points(this.from.pois, this.to.pois),
      edges: polylines(this.edgePairs),
      grid: this.gridPairs ? polylines(this.gridPairs) : this.to.grid,
      orders: this.to.orders ?? this.from.orders,
    };
  }
}

/**
 * Where a point goes when the stations move from `from` to `to`: the inverse-distance weighted
 * move of the nearest stations. Keeps the view on the same place across a morph.
 */
export function carry(point: Pt, from: Map<string, Pt>, to: Map<string, Pt>, neighbours = 6): Pt {
  const near: { d2: number; move: Pt }[] = [];
  for (const [id, start] of from) {
    const end = to.get(id);
    if (!end) continue;
    near.push({ d2: (start[0] - point[0]) ** 2 + (start[1] - point[1]) ** 2, move: [end[0] - start[0], end[1] - start[1]] });
  }
  near.sort((a, b) => a.d2 - b.d2);
  let weight = 0;
  let dx = 0;
  let dy = 0;
  for (const { d2, move } of near.slice(0, neighbours)) {
    if (d2 < 1e-12) return [point[0] + move[0], point[1] + move[1]];
    const w = 1 / d2;
    weight += w;
    dx += w * move[0];
    dy += w * move[1];
  }
  return weight > 0 ? [point[0] + dx / weight, point[1] + dy / weight] : point;
}

/** [x0, y0, x1, y1] around the stations and POIs (null when there are none). */
export function geometryBounds(geometry: Geometry, withPois = true): [number, number, number, number] | null {
  let x0 = Infinity;
  let y0 = Infinity;
  let x1 = -Infinity;
  let y1 = -Infinity;
  const add = ([x, y]: Pt) => {
    x0 = Math.min(x0, x);
    y0 = Math.min(y0, y);
    x1 = Math.max(x1, x);
    y1 = Math.max(y1, y);
  };
  geometry.stations.forEach(add);
  if (withPois) geometry.pois.forEach(add);
  return x0 <= x1 ? [x0, y0, x1, y1] : null;
}
