import type { LonLat } from '../api/types';
import { formatDistance } from '../map/distance';
import { shortestPath } from '../roads/shortest-path';
import { h } from '../ui/dom';
import { extendStroke } from './freehand';
import { roundLonLat } from './geometry';
import { circle, label, polyline } from './overlay';
import type { DeformTool, ScreenPoint, ToolContext, ToolRequest } from './tool';

/** A click within this many pixels of a road picks that road's nearer vertex, at any zoom. */
const SNAP_PX = 20;
const DEFAULT_SIMPLIFY_M = 10;
/** The API takes at most this many sketch points. */
const MAX_SKETCH_POINTS = 10000;

/**
 * Destination map: pick a start and an end on the map, the shortest road route between them is
 * found here in the browser (Dijkstra), then a freehand sketch says how the route should run;
 * the server pulls the route onto the sketch and the rest of the map along.
 */
export class DestinationTool implements DeformTool {
  readonly kind = 'destination' as const;
  readonly panel: HTMLElement;
  private readonly steps: HTMLOListElement;
  private readonly routeInfo: HTMLElement;
  private readonly simplify: HTMLInputElement;
  private readonly restartButton: HTMLButtonElement;
  private readonly clearSketchButton: HTMLButtonElement;
  private context: ToolContext | null = null;
  private start = -1;
  private end = -1;
  private route: number[] = [];
  /** On the deformed map, as drawn. */
  private sketch: LonLat[] = [];
  private stroke?: ScreenPoint[];
  private hoverNode = -1;

  constructor() {
    this.steps = h(
      'ol',
      { class: 'steps' },
      h('li', {}, 'Click where the route starts.'),
      h('li', {}, 'Click where it ends: the shortest route is highlighted.'),
      h('li', {}, 'Draw how you want the route to run (freehand, start to end); draw again to replace it.'),
    );
    this.routeInfo = h('p', { class: 'tool-count', 'data-testid': 'route-info' });
    this.simplify = h('input', { type: 'number', id: 'sketch-simplify', min: 0, step: 1, value: DEFAULT_SIMPLIFY_M, class: 'number-input' });
    this.simplify.addEventListener('change', () => this.context?.changed());
    this.restartButton = h('button', { type: 'button', class: 'button button-quiet' }, 'New route');
    this.restartButton.addEventListener('click', () => {
      this.clearRoute();
      this.changed();
    });
    this.clearSketchButton = h('button', { type: 'button', class: 'button button-quiet' }, 'Remove the sketch');
    this.clearSketchButton.addEventListener('click', () => {
      this.sketch = [];
      this.changed();
    });
    this.panel = h(
      'div',
      { class: 'tool-panel' },
      this.steps,
      this.routeInfo,
      h('label', { class: 'inline-field', for: 'sketch-simplify' }, 'Simplify the sketch (m)', this.simplify),
      h('div', { class: 'button-row' }, this.restartButton, this.clearSketchButton),
    );
    this.syncPanel();
  }

  reset(context: ToolContext | null): void {
    this.context = context;
    this.stroke = undefined;
    this.hoverNode = -1;
    this.clearRoute();
    this.syncPanel();
  }

  request(): ToolRequest | null {
    const context = this.context;
    if (!context || this.route.length < 2 || this.sketch.length < 2) return null;
    const simplify = Number(this.simplify.value);
    return {
      route: this.route.map((node) => context.graph.nodeIds[node]!),
      sketch: this.sketch,
      // An empty box is the default; anything else goes to the server as typed, which names the field if it is wrong.
      simplify_m: this.simplify.value.trim() === '' ? DEFAULT_SIMPLIFY_M : simplify,
    };
  }

  applied(): void {}

  pointerDown(point: ScreenPoint): boolean {
    if (this.route.length < 2) return false;
    this.stroke = [point];
    return true;
  }

  pointerMove(point: ScreenPoint): void {
    if (!this.stroke) return;
    extendStroke(this.stroke, point, 2);
    this.context?.redraw();
  }

  pointerUp(): void {
    const context = this.context;
    const stroke = this.stroke;
    this.stroke = undefined;
    if (!context || !stroke) return;
    if (stroke.length < 2) {
      context.notify('Draw the sketch as a line: press, move along where the route should run, release.');
      context.redraw();
      return;
    }
    const { map, frame } = context;
    const step = Math.ceil(stroke.length / MAX_SKETCH_POINTS);
    this.sketch = stroke.filter((_, i) => i % step === 0 || i === stroke.length - 1).map((p) => roundLonLat(frame.unproject(...map.toFrame(...p))));
    context.notify(null);
    this.changed();
  }

  click(point: ScreenPoint): void {
    const context = this.context;
    if (!context || this.route.length >= 2) return;
    const node = this.nodeAt(point);
    if (node < 0) return context.notify('Click on a road (closer to a road vertex).');
    context.notify(null);
    if (this.start < 0 || this.end >= 0) {
      this.start = node;
      this.end = -1;
    } else if (node !== this.start) {
      const path = shortestPath(context.graph, this.start, node);
      if (!path) {
        context.notify('No road joins these two points (the network has separate parts): pick another end.');
      } else {
        this.end = node;
        this.route = path.nodes;
        this.routeInfo.dataset.meters = String(Math.round(path.meters));
      }
    }
    this.changed();
  }

  hover(point: ScreenPoint | null): string {
    if (this.route.length >= 2) return 'crosshair';
    const node = point ? this.nodeAt(point) : -1;
    if (node !== this.hoverNode) {
      this.hoverNode = node;
      this.context?.redraw();
    }
    return node >= 0 ? 'pointer' : '';
  }

  key(event: KeyboardEvent): boolean {
    if (event.key === 'Escape' && this.stroke) {
      this.stroke = undefined;
      this.context?.redraw();
      return true;
    }
    return false;
  }

  highlighted(): number[] {
    return this.route;
  }

  render(layer: SVGGElement): void {
    const context = this.context;
    if (!context) return;
    const { map, frame } = context;
    const drawn = context.displacement().deformed;
    const at = (node: number) => map.toScreen(drawn[2 * node]!, drawn[2 * node + 1]!);
    if (this.hoverNode >= 0 && this.route.length < 2) layer.append(circle(at(this.hoverNode), 7, 'vertex-hover'));
    if (this.sketch.length > 1 && !this.stroke) layer.append(polyline(this.sketch.map((p) => map.toScreen(...frame.project(p))), 'sketch'));
    if (this.stroke && this.stroke.length > 1) layer.append(polyline(this.stroke, 'sketch drawing'));
    for (const [node, text, className] of [[this.start, 'A', 'route-start'], [this.end, 'B', 'route-end']] as const) {
      if (node < 0) continue;
      const p = at(node);
      layer.append(circle(p, 9, `route-marker ${className}`), label([p[0], p[1] + 4], text, 'route-marker-label'));
    }
  }

  private nodeAt(point: ScreenPoint): number {
    const context = this.context!;
    return context.displacement().nearestRoadVertex(...context.map.toFrame(...point), SNAP_PX / context.map.scale);
  }

  private clearRoute(): void {
    this.start = this.end = -1;
    this.route = [];
    this.sketch = [];
    delete this.routeInfo.dataset.meters;
  }

  private changed(): void {
    this.syncPanel();
    this.context?.changed();
  }

  private syncPanel(): void {
    const step = this.start < 0 ? 0 : this.route.length < 2 ? 1 : 2;
    [...this.steps.children].forEach((item, i) => {
      item.classList.toggle('current', i === step);
      item.classList.toggle('done', i < step || (i === 2 && this.sketch.length > 1));
    });
    this.routeInfo.textContent =
      this.route.length >= 2
        ? `Route: ${this.route.length} road vertices, ${formatDistance(Number(this.routeInfo.dataset.meters ?? 0))}${this.sketch.length > 1 ? `; sketch of ${this.sketch.length} points` : ''}`
        : '';
    this.routeInfo.hidden = this.route.length < 2;
    this.clearSketchButton.disabled = this.sketch.length === 0;
    this.restartButton.disabled = this.start < 0;
  }
}
