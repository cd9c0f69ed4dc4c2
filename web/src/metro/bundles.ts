import type { Pt } from './morph';

/**
 * Lines that share an edge drawn side by side: each line is its own stroke, moved sideways by
 * its place in the edge's order (left to right as seen travelling from the edge's first point
 * to its last, the server's line order), and joined to itself through the stations.
 */

/** Centre-to-centre distance of parallel lines on screen, px (the lines' stroke is a bit less). */
export const LINE_SPACING_PX = 4;
/** A mitre longer than this many offsets is cut to a straight join (sharp turns). */
const MITRE_LIMIT = 3;

export interface BundleEdge {
  from: string;
  to: string;
  points: Pt[];
  /** Line ids, left to right along `points`. */
  order: string[];
}

/** Unit left normal of a -> b in the map's frame (y down: left of east is north, -y). */
function leftNormal(a: Pt, b: Pt): Pt | null {
  const dx = b[0] - a[0];
  const dy = b[1] - a[1];
  const length = Math.hypot(dx, dy);
  return length > 0 ? [dy / length, -dx / length] : null;
}

/** The polyline moved `offset` frame units to its left, with mitred corners. */
export function offsetPolyline(points: Pt[], offset: number): Pt[] {
  if (offset === 0 || points.length < 2) return points;
  // Each segment's normal (a zero-length segment takes its neighbour's).
  const normals: (Pt | null)[] = [];
  for (let i = 1; i < points.length; i++) normals.push(leftNormal(points[i - 1]!, points[i]!));
  for (let i = 1; i < normals.length; i++) normals[i] ??= normals[i - 1]!;
  for (let i = normals.length - 2; i >= 0; i--) normals[i] ??= normals[i + 1]!;
  if (!normals[0]) return points;
  const out: Pt[] = [];
  for (let i = 0; i < points.length; i++) {
    const before = normals[Math.max(0, i - 1)]!;
    const after = normals[Math.min(normals.length - 1, i)]!;
    // The mitre: along the mean normal, long enough to keep the offset from both segments.
    const mx = before[0] + after[0];
    const my = before[1] + after[1];
    const cos = (mx * after[0] + my * after[1]) / (Math.hypot(mx, my) || 1);
    const p = points[i]!;
    if (cos > 1 / MITRE_LIMIT) {
      const length = offset / cos / (Math.hypot(mx, my) || 1);
      out.push([p[0] + mx * length, p[1] + my * length]);
    } else {
      // Too sharp to mitre (or a reversal): end one segment's offset and start the next one's.
      out.push([p[0] + before[0] * offset, p[1] + before[1] * offset], [p[0] + after[0] * offset, p[1] + after[1] * offset]);
    }
  }
  return out;
}

interface End {
  line: string;
  point: Pt;
  /** The direction of travel at this end, pointing into the node. */
  into: Pt;
}

/** Per line: its offset strokes along the edges, and its joins through the stations. */
export interface LinePieces {
  strokes: Map<string, Pt[][]>;
  joins: Map<string, Pt[][]>;
}

function push(map: Map<string, Pt[][]>, line: string, polyline: Pt[]): void {
  const list = map.get(line);
  if (list) list.push(polyline);
  else map.set(line, [polyline]);
}

/**
 * Every line's pieces: its offset strokes on each edge, and at each node where the line runs
 * on (two of its pieces end there) the join between them, mitred where the sides meet.
 * `spacing` is the distance between neighbouring lines in frame units.
 */
export function bundlePieces(edges: BundleEdge[], spacing: number): LinePieces {
  const pieces: LinePieces = { strokes: new Map(), joins: new Map() };
  const ends = new Map<string, End[]>(); // node -> the pieces' ends there
  const endAt = (node: string, end: End) => {
    const list = ends.get(node);
    if (list) list.push(end);
    else ends.set(node, [end]);
  };
  for (const edge of edges) {
    const n = edge.order.length;
    if (edge.points.length < 2) continue;
    edge.order.forEach((line, i) => {
      const polyline = offsetPolyline(edge.points, ((n - 1) / 2 - i) * spacing);
      push(pieces.strokes, line, polyline);
      const first = polyline[0]!;
      const last = polyline[polyline.length - 1]!;
      const second = polyline[1]!;
      const beforeLast = polyline[polyline.length - 2]!;
      endAt(edge.from, { line, point: first, into: [first[0] - second[0], first[1] - second[1]] });
      endAt(edge.to, { line, point: last, into: [last[0] - beforeLast[0], last[1] - beforeLast[1]] });
    });
  }
  for (const list of ends.values()) {
    const byLine = new Map<string, End[]>();
    for (const end of list) byLine.set(end.line, [...(byLine.get(end.line) ?? []), end]);
    for (const [line, two] of byLine) {
      if (two.length !== 2) continue; // a terminus, or a branch: the station symbol covers it
      const [a, b] = two as [End, End];
      if (Math.hypot(a.point[0] - b.point[0], a.point[1] - b.point[1]) < spacing * 1e-3) continue;
      const mitre = meet(a, b);
      push(pieces.joins, line, mitre ? [a.point, mitre, b.point] : [a.point, b.point]);
    }
  }
  return pieces;
}

/** Where the two ends' lines of travel meet, if near (a corner through the station). */
function meet(a: End, b: End): Pt | null {
  // a.point + s * a.into = b.point + t * b.into
  const det = a.into[0] * -b.into[1] - a.into[1] * -b.into[0];
  if (Math.abs(det) < 1e-12) return null;
  const rx = b.point[0] - a.point[0];
  const ry = b.point[1] - a.point[1];
  const s = (rx * -b.into[1] - ry * -b.into[0]) / det;
  const t = (a.into[0] * ry - a.into[1] * rx) / det;
  if (s < 0 || t < 0) return null;
  const p: Pt = [a.point[0] + s * a.into[0], a.point[1] + s * a.into[1]];
  const reach = Math.hypot(rx, ry);
  return Math.hypot(p[0] - a.point[0], p[1] - a.point[1]) <= MITRE_LIMIT * Math.max(reach, 1e-9) ? p : null;
}
