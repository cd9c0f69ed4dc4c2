import type { DeformGrid } from '../api/types';
import type { Frame } from '../map/projection';
import type { ContextLayer } from './context-layer';
import { ROAD_CLASSES, type RoadClass, type RoadGraph } from './road-graph';

/** Major roads darker and wider; paths light and thin. Widths in CSS pixels at any zoom. */
const STYLE: Record<RoadClass, { color: string; width: number }> = {
  path: { color: '#b4a58d', width: 0.9 },
  service: { color: '#a3adb8', width: 1 },
  minor: { color: '#7b8794', width: 1 },
  medium: { color: '#45525f', width: 2.1 },
  major: { color: '#16324f', width: 3 },
};
const GHOST = { color: 'rgb(214 108 60 / 0.35)', width: 1 };
const GRID = { color: 'rgb(40 110 190 / 0.45)', width: 0.7, support: 'rgb(40 110 190 / 0.8)' };
const ROUTE = { color: '#0a7cff', casing: '#fff', width: 5 };
/**
 * Road paths leave out vertices closer than this many device pixels to the last one kept (a way
 * shorter than that is a dot): a 56,000-edge network seen whole has most of its vertices within
 * a pixel of each other, and rasterizing them is what a drag waits for. Paths are rebuilt for
 * each zoom level (ZOOM_STEP apart) and each new set of positions.
 */
const SIMPLIFY_PX = 0.6;
const ZOOM_STEP = Math.SQRT2;

export interface CanvasView {
  x: number;
  y: number;
  k: number;
}

/**
 * A road network drawn on a canvas, for networks too big for SVG: one Path2D per road class in
 * frame coordinates, stroked under the map's zoom transform. New node positions (a deformed
 * map) rebuild the paths; pans and zooms only stroke them again.
 */
export class RoadCanvas {
  readonly element: HTMLCanvasElement;
  private readonly context: CanvasRenderingContext2D;
  private graph?: RoadGraph;
  private classPaths = new Map<RoadClass, Path2D>();
  private ghost?: Path2D;
  /** The zoom levels the road paths and the ghost were simplified for (NaN: none yet). */
  private pathsLevel = NaN;
  private ghostLevel = NaN;
  private gridPath?: Path2D;
  private supportPath?: Path2D;
  private routePath?: Path2D;
  /** Sea, water, land use, rivers, railways and place names, warped with the roads. */
  private layers?: ContextLayer;
  private contextPaths?: ReturnType<ContextLayer['buildPaths']>;
  private contextLevel = NaN;
  /** Place names drawn at the last draw. */
  placesDrawn = 0;
  private positions?: Float64Array;
  /** The undeformed nodes (frame coordinates), drawn as the ghost of the original map. */
  private original?: Float64Array;
  private route: number[] = [];
  private showOriginalRoads = false;
  private showGridLines = false;
  /** What the canvas shows; draw() does nothing while it is still right. */
  private drawnView?: CanvasView;
  private dirty = true;
  /** Milliseconds the last draw took (issuing it: the rasterizing comes after). */
  lastDrawMs = 0;
  /** Draws so far (for the frame-rate meter). */
  draws = 0;

  constructor() {
    this.element = document.createElement('canvas');
    this.element.className = 'road-canvas';
    this.element.setAttribute('aria-hidden', 'true');
    const context = this.element.getContext('2d');
    if (!context) throw new Error('This browser cannot draw on a canvas.');
    this.context = context;
  }

  get showOriginal(): boolean {
    return this.showOriginalRoads;
  }

  set showOriginal(show: boolean) {
    this.dirty ||= show !== this.showOriginalRoads;
    this.showOriginalRoads = show;
  }

  get showGrid(): boolean {
    return this.showGridLines;
  }

  set showGrid(show: boolean) {
    this.dirty ||= show !== this.showGridLines;
    this.showGridLines = show;
  }

  /** A new network: `original` holds its undeformed nodes in frame coordinates. */
  setNetwork(graph: RoadGraph, original: Float64Array): void {
    this.graph = graph;
    this.original = original;
    this.ghostLevel = NaN;
    this.gridPath = this.supportPath = undefined;
    this.route = [];
    this.setPositions(original);
  }

  /** The network's context layers (already warped to the positions to come), or undefined for none. */
  setContext(context: ContextLayer | undefined): void {
    this.layers = context;
    this.contextPaths = undefined;
    this.dirty = true;
  }

  clear(): void {
    this.graph = undefined;
    this.layers = this.contextPaths = undefined;
    this.positions = this.original = undefined;
    this.classPaths.clear();
    this.pathsLevel = this.ghostLevel = NaN;
    this.ghost = this.gridPath = this.supportPath = this.routePath = undefined;
    this.route = [];
    this.dirty = true;
  }

  /** The nodes' drawn positions (frame coordinates, x, y per node). */
  setPositions(positions: Float64Array): void {
    this.positions = positions;
    this.pathsLevel = NaN;  // built at the next draw, for its zoom
    this.contextPaths = undefined;
    this.routePath = this.buildRoute();
    this.dirty = true;
  }

  /** The deformed grid (its `after` corners), or null for none. */
  setGrid(grid: DeformGrid | null, frame: Frame): void {
    this.dirty = true;
    if (!grid) {
      this.gridPath = this.supportPath = undefined;
      return;
    }
    const after = grid.after.map((position) => frame.project(position));
    const quads = new Path2D();
    for (const quad of grid.quads) {
      const [x0, y0] = after[quad[0]]!;
      quads.moveTo(x0, y0);
      for (let i = 1; i < 4; i++) quads.lineTo(...after[quad[i]!]!);
      quads.closePath();
    }
    // T-junction support edges: from the coarse quad's centre to the hanging vertex.
    const support = new Path2D();
    for (const [vertex, quadIndex] of grid.tjunctions) {
      const quad = grid.quads[quadIndex];
      const hanging = after[vertex];
      if (!quad || !hanging) continue;
      let cx = 0;
      let cy = 0;
      for (const corner of quad) {
        cx += after[corner]![0] / 4;
        cy += after[corner]![1] / 4;
      }
      support.moveTo(cx, cy);
      support.lineTo(hanging[0], hanging[1]);
    }
    this.gridPath = quads;
    this.supportPath = support;
  }

  /** Highlights a route (node indices), drawn at the current positions; [] for none. */
  setRoute(nodes: number[]): void {
    if (nodes === this.route || (nodes.length === 0 && this.route.length === 0)) return;
    this.route = nodes;
    this.routePath = this.buildRoute();
    this.dirty = true;
  }

  /** Draws the roads under the map's pan and zoom, unless the canvas already shows just that. */
  draw(view: CanvasView): void {
    const canvas = this.element;
    const ratio = window.devicePixelRatio || 1;
    const width = Math.round(canvas.clientWidth * ratio);
    const height = Math.round(canvas.clientHeight * ratio);
    const sameView = this.drawnView && this.drawnView.x === view.x && this.drawnView.y === view.y && this.drawnView.k === view.k;
    if (!this.dirty && sameView && canvas.width === width && canvas.height === height) return;
    const started = performance.now();
    this.dirty = false;
    this.drawnView = { ...view };
    this.draws++;
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    const ctx = this.context;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, width, height);
    if (!this.graph) return;
    const k = view.k * ratio;
    // Road paths simplified for this zoom level (device pixels per frame unit, in ZOOM_STEPs).
    const level = Math.floor(Math.log(k) / Math.log(ZOOM_STEP));
    if (level !== this.pathsLevel && this.positions) {
      const tolerance = SIMPLIFY_PX / ZOOM_STEP ** level;
      this.classPaths = new Map(ROAD_CLASSES.map((roadClass) => [roadClass, this.buildPath([roadClass], this.positions!, tolerance)]));
      this.pathsLevel = level;
    }
    if (this.showOriginal && this.original && level !== this.ghostLevel) {
      this.ghost = this.buildPath(ROAD_CLASSES, this.original, SIMPLIFY_PX / ZOOM_STEP ** level);
      this.ghostLevel = level;
    }
    ctx.setTransform(k, 0, 0, k, view.x * ratio, view.y * ratio);
    // Butt caps and bevel joins rasterize faster than round ones and look alike at these widths.
    ctx.lineCap = 'butt';
    ctx.lineJoin = 'bevel';
    // Line widths are divided by the zoom so they stay the same on screen.
    const stroke = (path: Path2D | undefined, color: string, widthPx: number, dash?: number[]) => {
      if (!path) return;
      ctx.strokeStyle = color;
      ctx.lineWidth = (widthPx * ratio) / k;
      ctx.setLineDash(dash ? dash.map((length) => (length * ratio) / k) : []);
      ctx.stroke(path);
    };
    if (this.layers) {
      if (!this.contextPaths || level !== this.contextLevel) {
        this.contextPaths = this.layers.buildPaths(SIMPLIFY_PX / ZOOM_STEP ** level);
        this.contextLevel = level;
      }
      this.layers.drawShapes(ctx, this.contextPaths, ratio / k);
    }
    if (this.showOriginal) stroke(this.ghost, GHOST.color, GHOST.width);
    if (this.showGrid) {
      stroke(this.gridPath, GRID.color, GRID.width);
      stroke(this.supportPath, GRID.support, GRID.width, [4, 3]);
    }
    for (const roadClass of ROAD_CLASSES) stroke(this.classPaths.get(roadClass), STYLE[roadClass].color, STYLE[roadClass].width);
    if (this.routePath) {
      ctx.lineJoin = 'round';
      ctx.lineCap = 'round';
      stroke(this.routePath, ROUTE.casing, ROUTE.width + 3);
      stroke(this.routePath, ROUTE.color, ROUTE.width);
    }
    if (this.layers) {
      ctx.setTransform(1, 0, 0, 1, 0, 0);
      const toScreen = (x: number, y: number): [number, number] => [x * k + view.x * ratio, y * k + view.y * ratio];
      this.placesDrawn = this.layers.drawPlaces(ctx, toScreen, ratio, width, height);
    }
    this.lastDrawMs = performance.now() - started;
  }

  /** The ways of `classes` at positions `xy`, leaving out vertices within `tolerance` (frame units) of the last kept. */
  private buildPath(classes: readonly RoadClass[], xy: Float64Array, tolerance: number): Path2D {
    const path = new Path2D();
    const t2 = tolerance * tolerance;
    for (const roadClass of classes) {
      for (const nodes of this.graph!.waysByClass.get(roadClass)!) {
        let lastX = xy[2 * nodes[0]!]!;
        let lastY = xy[2 * nodes[0]! + 1]!;
        path.moveTo(lastX, lastY);
        let drawn = false;
        for (let i = 1; i < nodes.length; i++) {
          const x = xy[2 * nodes[i]!]!;
          const y = xy[2 * nodes[i]! + 1]!;
          const end = i === nodes.length - 1;
          const dx = x - lastX;
          const dy = y - lastY;
          if (dx * dx + dy * dy < t2 && !(end && !drawn)) continue;
          path.lineTo(x, y);
          lastX = x;
          lastY = y;
          drawn = true;
        }
      }
    }
    return path;
  }

  private buildRoute(): Path2D | undefined {
    const xy = this.positions;
    if (!xy || this.route.length < 2) return undefined;
    const path = new Path2D();
    path.moveTo(xy[2 * this.route[0]!]!, xy[2 * this.route[0]! + 1]!);
    for (const node of this.route.slice(1)) path.lineTo(xy[2 * node]!, xy[2 * node + 1]!);
    return path;
  }
}
