import type { RoadContext } from '../api/types';
import type { Frame } from '../map/projection';
import { PointIndex } from './point-index';

/** Fill colours per area kind, drawn in this order (later over earlier). */
const AREA_STYLE: [kind: string, fill: string][] = [
  ['farmland', '#eef0d5'],
  ['residential', '#ece6df'],
  ['industrial', '#e9e1e8'],
  ['grass', '#dcefc9'],
  ['forest', '#c3dfae'],
  ['park', '#cdebb0'],
  ['sea', '#aad3df'],
  ['water', '#aad3df'],
  ['building', '#d9d0c9'],
];
/** Strokes per line kind, widths in CSS pixels. */
const LINE_STYLE: Record<string, { color: string; width: number; dash?: number[] }> = {
  river: { color: '#7fb6d0', width: 3 },
  canal: { color: '#7fb6d0', width: 2.2 },
  stream: { color: '#94c4d9', width: 1.2 },
  railway: { color: '#8a8a8a', width: 1.4, dash: [6, 3] },
};
const PLACE_FONT: Record<string, string> = {
  city: '600 16px system-ui, sans-serif',
  town: '600 14px system-ui, sans-serif',
  suburb: '500 13px system-ui, sans-serif',
  village: '500 12.5px system-ui, sans-serif',
  island: 'italic 500 12.5px system-ui, sans-serif',
};
const SMALL_PLACE_FONT = '500 11.5px system-ui, sans-serif';
/** Areas smaller than this many simplification tolerances across (a few device pixels) are not drawn. */
const MIN_AREA_PX = 4;
/** Road nodes whose displacement a context vertex follows (inverse distance weights). */
const NEIGHBOURS = 4;

interface Shape {
  kind: string;
  /** Offsets into the positions (vertex indices) where each ring or line starts; the last is its end. */
  starts: number[];
}

/**
 * The context layers of a road network (sea, water, land use, buildings, rivers, railways,
 * place names) in frame coordinates, warped with the roads: every vertex follows the
 * displacement of its NEIGHBOURS nearest road nodes, weighted by inverse squared distance. The
 * neighbours and weights are found once per network, so a new set of road positions costs one
 * weighted sum per vertex (Liechtenstein: ~60,000 vertices, ~1 ms). Where roads are dense this
 * is the grid's own smooth map; far from every road (open sea) the shift of the nearest roads.
 */
export class ContextLayer {
  private readonly original: Float64Array;
  private readonly neighbours: Int32Array;
  private readonly weights: Float64Array;
  private readonly areas: Shape[] = [];
  private readonly lines: (Shape & { tunnel: boolean })[] = [];
  private readonly places: { kind: string; name: string; rank: number; vertex: number }[] = [];
  /** Vertex positions at the last warp (the original ones until then). */
  positions: Float64Array;

  constructor(context: RoadContext, frame: Frame, roadNodes: Float64Array, roadIndex: PointIndex) {
    const xy: number[] = [];
    const add = (flat: number[]) => {
      for (let i = 0; i + 1 < flat.length; i += 2) xy.push(...frame.project([flat[i]!, flat[i + 1]!]));
    };
    for (const area of context.areas) {
      const starts: number[] = [];
      for (const ring of area.rings) {
        starts.push(xy.length / 2);
        add(ring);
      }
      starts.push(xy.length / 2);
      this.areas.push({ kind: area.kind, starts });
    }
    for (const line of context.lines) {
      const start = xy.length / 2;
      add(line.points);
      this.lines.push({ kind: line.kind, starts: [start, xy.length / 2], tunnel: line.tunnel === true });
    }
    for (const place of [...context.places].sort((a, b) => a.rank - b.rank)) {
      this.places.push({ kind: place.kind, name: place.name, rank: place.rank, vertex: xy.length / 2 });
      add(place.pos);
    }
    this.original = new Float64Array(xy);
    this.positions = this.original;
    const count = this.original.length / 2;
    this.neighbours = new Int32Array(count * NEIGHBOURS).fill(-1);
    this.weights = new Float64Array(count * NEIGHBOURS);
    if (roadNodes.length === 0) return;
    for (let v = 0; v < count; v++) {
      const near = roadIndex.kNearest(this.original[2 * v]!, this.original[2 * v + 1]!, NEIGHBOURS);
      let sum = 0;
      near.forEach(({ index, distance }, k) => {
        const w = 1 / Math.max(distance * distance, 1e-12);
        this.neighbours[v * NEIGHBOURS + k] = index;
        this.weights[v * NEIGHBOURS + k] = w;
        sum += w;
      });
      for (let k = 0; k < NEIGHBOURS; k++) this.weights[v * NEIGHBOURS + k]! /= sum || 1;
    }
  }

  get vertexCount(): number {
    return this.original.length / 2;
  }

  /** Moves every vertex with the roads: `deformed` against `original` road node positions. */
  warp(originalRoads: Float64Array, deformedRoads: Float64Array): void {
    if (originalRoads === deformedRoads) {
      this.positions = this.original;
      return;
    }
    const out = new Float64Array(this.original.length);
    const count = this.original.length / 2;
    for (let v = 0; v < count; v++) {
      let dx = 0;
      let dy = 0;
      for (let k = 0; k < NEIGHBOURS; k++) {
        const n = this.neighbours[v * NEIGHBOURS + k]!;
        if (n < 0) break;
        const w = this.weights[v * NEIGHBOURS + k]!;
        dx += w * (deformedRoads[2 * n]! - originalRoads[2 * n]!);
        dy += w * (deformedRoads[2 * n + 1]! - originalRoads[2 * n + 1]!);
      }
      out[2 * v] = this.original[2 * v]! + dx;
      out[2 * v + 1] = this.original[2 * v + 1]! + dy;
    }
    this.positions = out;
  }

  /**
   * Fill paths per area kind and stroke paths per line kind at the current positions, for a zoom
   * where `tolerance` frame units are a fraction of a device pixel: vertices closer than that to
   * the last one kept are left out, and so are areas whose box is under MIN_AREA_PX tolerances
   * across (Liechtenstein seen whole: its 9,000 buildings are dots, and filling them is what a
   * drag would wait for).
   */
  buildPaths(tolerance: number): { fills: [string, Path2D][]; strokes: [string, Path2D][] } {
    const xy = this.positions;
    const t2 = tolerance * tolerance;
    const minSize = MIN_AREA_PX * tolerance;
    const ring = (from: number, to: number, closed: boolean, into: Path2D) => {
      let lastX = xy[2 * from]!;
      let lastY = xy[2 * from + 1]!;
      into.moveTo(lastX, lastY);
      for (let i = from + 1; i < to; i++) {
        const x = xy[2 * i]!;
        const y = xy[2 * i + 1]!;
        const dx = x - lastX;
        const dy = y - lastY;
        if (dx * dx + dy * dy < t2 && !(i === to - 1 && !closed)) continue;
        into.lineTo(x, y);
        lastX = x;
        lastY = y;
      }
      if (closed) into.closePath();
    };
    const bigEnough = (from: number, to: number) => {
      let x0 = Infinity;
      let y0 = Infinity;
      let x1 = -Infinity;
      let y1 = -Infinity;
      for (let i = from; i < to; i++) {
        const x = xy[2 * i]!;
        const y = xy[2 * i + 1]!;
        if (x < x0) x0 = x;
        if (x > x1) x1 = x;
        if (y < y0) y0 = y;
        if (y > y1) y1 = y;
      }
      return x1 - x0 >= minSize || y1 - y0 >= minSize;
    };
    const fills: [string, Path2D][] = AREA_STYLE.map(([kind]) => [kind, new Path2D()]);
    const fillOf = new Map(fills);
    for (const area of this.areas) {
      const target = fillOf.get(area.kind);
      const starts = area.starts;
      if (!target || starts.length < 2 || starts[1]! - starts[0]! < 3 || !bigEnough(starts[0]!, starts[1]!)) continue;
      for (let r = 0; r + 1 < starts.length; r++)
        if (starts[r + 1]! - starts[r]! >= 3 && (r === 0 || bigEnough(starts[r]!, starts[r + 1]!))) ring(starts[r]!, starts[r + 1]!, true, target);
    }
    const strokes: [string, Path2D][] = Object.keys(LINE_STYLE).map((kind) => [kind, new Path2D()]);
    const strokeOf = new Map(strokes);
    for (const line of this.lines) {
      const target = strokeOf.get(line.kind);
      if (target && !line.tunnel && line.starts[1]! - line.starts[0]! >= 2) ring(line.starts[0]!, line.starts[1]!, false, target);
    }
    return { fills, strokes };
  }

  /** Draws the areas and lines (under the frame-to-device transform already set). */
  drawShapes(ctx: CanvasRenderingContext2D, paths: ReturnType<ContextLayer['buildPaths']>, pxToFrame: number): void {
    const fillStyle = new Map(AREA_STYLE);
    for (const [kind, path] of paths.fills) {
      ctx.fillStyle = fillStyle.get(kind)!;
      ctx.fill(path, 'evenodd');
    }
    for (const [kind, path] of paths.strokes) {
      const style = LINE_STYLE[kind]!;
      ctx.strokeStyle = style.color;
      ctx.lineWidth = style.width * pxToFrame;
      ctx.setLineDash(style.dash ? style.dash.map((d) => d * pxToFrame) : []);
      ctx.stroke(path);
    }
    ctx.setLineDash([]);
  }

  /**
   * Place names at their (warped) anchors, most important first, each left out where it would
   * overlap one already drawn. `toScreen` maps frame to device pixels; `ratio` is device pixels per CSS pixel.
   */
  drawPlaces(ctx: CanvasRenderingContext2D, toScreen: (x: number, y: number) => [number, number], ratio: number, width: number, height: number): number {
    const taken: [number, number, number, number][] = [];
    let drawn = 0;
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    ctx.lineJoin = 'round';
    for (const place of this.places) {
      const [x, y] = toScreen(this.positions[2 * place.vertex]!, this.positions[2 * place.vertex + 1]!);
      if (x < 0 || y < 0 || x > width || y > height) continue;
      ctx.font = PLACE_FONT[place.kind] ?? SMALL_PLACE_FONT;
      const w = ctx.measureText(place.name).width * ratio;
      const h = 16 * ratio;
      const box: [number, number, number, number] = [x - w / 2 - 3 * ratio, y - h / 2, x + w / 2 + 3 * ratio, y + h / 2];
      if (taken.some((t) => t[0] < box[2] && box[0] < t[2] && t[1] < box[3] && box[1] < t[3])) continue;
      taken.push(box);
      ctx.save();
      ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
      ctx.strokeStyle = 'rgb(255 255 255 / 0.85)';
      ctx.lineWidth = 3;
      ctx.strokeText(place.name, x / ratio, y / ratio);
      ctx.fillStyle = '#3b3b3b';
      ctx.fillText(place.name, x / ratio, y / ratio);
      ctx.restore();
      drawn++;
    }
    return drawn;
  }
}
