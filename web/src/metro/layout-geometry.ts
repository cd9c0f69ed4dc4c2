import type { LayoutLabel, LayoutResponse, XY } from '../api/types';
import type { Frame } from '../map/projection';
import type { DrawnEdge, ServerLabels } from './metro-layers';
import type { Geometry, Pt } from './morph';

/**
 * Puts a layout's planar frame (metres, y north) on the map's frame (Web Mercator units, y
 * south) by a uniform scale, a flip of y and a translation: angles stay as they are, so an
 * octilinear layout is drawn octilinear. The scale and translation are fitted (least squares)
 * to the stations' geographic positions, which the layout gives in both frames; the rest of
 * the difference between the two projections is a few tens of metres at a city's edge.
 */
export class Placement {
  private constructor(
    readonly scale: number,
    private readonly tx: number,
    private readonly ty: number,
  ) {}

  static fit(layout: LayoutResponse, frame: Frame): Placement {
    const pairs = layout.stations.features.map((station) => ({
      u: [station.properties.geo[0], -station.properties.geo[1]] as Pt,
      f: frame.project(station.properties.lonlat),
    }));
    const n = Math.max(1, pairs.length);
    const mean = (pick: (pair: (typeof pairs)[number]) => number) => pairs.reduce((sum, pair) => sum + pick(pair), 0) / n;
    const [ux, uy, fx, fy] = [mean((p) => p.u[0]), mean((p) => p.u[1]), mean((p) => p.f[0]), mean((p) => p.f[1])];
    let num = 0;
    let den = 0;
    for (const { u, f } of pairs) {
      num += (u[0] - ux) * (f[0] - fx) + (u[1] - uy) * (f[1] - fy);
      den += (u[0] - ux) ** 2 + (u[1] - uy) ** 2;
    }
    // One station (or none): 1 m is 1/1000 of the frame, a guess that still draws something.
    const scale = den > 0 && num > 0 ? num / den : 1e-3;
    return new Placement(scale, fx - scale * ux, fy - scale * uy);
  }

  toFrame([x, y]: XY): Pt {
    return [this.scale * x + this.tx, -this.scale * y + this.ty];
  }

  fromFrame([fx, fy]: Pt): XY {
    return [(fx - this.tx) / this.scale, -(fy - this.ty) / this.scale];
  }
}

/** The mesh's rows and columns and the closed outline, as polylines in the frame. */
function gridLines(cols: number, rows: number, nodes: XY[], outline: XY[], place: (p: XY) => Pt): Pt[][] {
  if (nodes.length !== cols * rows) return [];
  const node = (i: number, j: number) => place(nodes[j * cols + i]!);
  const lines: Pt[][] = [];
  for (let j = 0; j < rows; j++) lines.push(Array.from({ length: cols }, (_, i) => node(i, j)));
  for (let i = 0; i < cols; i++) lines.push(Array.from({ length: rows }, (_, j) => node(i, j)));
  if (outline.length > 2) lines.push([...outline, outline[0]!].map(place));
  return lines;
}

/** The regular geographic mesh (and the outline) of a layout: what the warp starts from. */
export function geoGrid(layout: LayoutResponse, placement: Placement): Pt[][] {
  const place = (p: XY) => placement.toFrame(p);
  return gridLines(layout.mesh.cols, layout.mesh.rows, layout.mesh.geo, layout.outline.geo, place);
}

/**
 * The octilinear drawing: stations, edges and POIs where the layout puts them, in the order of
 * the edges drawn (matched by their stations; an edge the layout lacks keeps its geographic
 * track, mapped the same way), and the warped mesh.
 */
export function layoutGeometry(layout: LayoutResponse, placement: Placement, edges: readonly DrawnEdge[], geo: Geometry): Geometry {
  const place = (p: XY) => placement.toFrame(p);
  type Found = { points: XY[]; order: string[] | undefined };
  const byEnds = new Map<string, Found[]>();
  for (const edge of layout.edges.features) {
    const key = `${edge.properties.from}\u0000${edge.properties.to}`;
    byEnds.set(key, [...(byEnds.get(key) ?? []), { points: edge.geometry.coordinates, order: edge.properties.line_order }]);
  }
  // Parallel edges between the same stations are matched in order. An edge drawn the other way
  // round has its points, and its lines' order (left to right along them), reversed.
  const take = (from: string, to: string): { points: Pt[]; order: string[] | undefined } | undefined => {
    const forward = byEnds.get(`${from}\u0000${to}`);
    if (forward?.length) {
      const found = forward.shift()!;
      return { points: found.points.map(place), order: found.order };
    }
    const backward = byEnds.get(`${to}\u0000${from}`);
    if (backward?.length) {
      const found = backward.shift()!;
      return { points: found.points.map(place).reverse(), order: found.order ? [...found.order].reverse() : undefined };
    }
    return undefined;
  };
  const taken = edges.map((edge) => take(edge.from, edge.to));
  return {
    stations: new Map(layout.stations.features.map((station) => [station.properties.id, place(station.geometry.coordinates)])),
    pois: new Map(layout.pois.features.map((poi) => [poi.properties.id, place(poi.geometry.coordinates)])),
    edges: taken.map((found, i) => found?.points ?? geo.edges[i] ?? []),
    grid: gridLines(layout.mesh.cols, layout.mesh.rows, layout.mesh.layout, layout.outline.layout, place),
    orders: taken.map((found) => found?.order),
  };
}

/** The server's station names, by station id per zoom, placed on the map by `placement`. */
export function serverLabels(layout: LayoutResponse, placement: Placement): ServerLabels | null {
  if (!layout.labels) return null;
  const ids = layout.stations.features.map((station) => station.properties.id);
  return {
    info: layout.labels,
    framePerMetre: placement.scale,
    byScale: layout.labels.scales.map((scale) => {
      const byId = new Map<string, LayoutLabel>();
      for (const label of scale.labels) {
        const id = ids[label[0]];
        if (id !== undefined) byId.set(id, label);
      }
      return byId;
    }),
  };
}
