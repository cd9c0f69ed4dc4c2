import type { LonLat } from '../api/types';
import { h } from '../ui/dom';
import { extendStroke, patternTargets, resample, type PatternShape } from './freehand';
import { roundLonLat } from './geometry';
import { arrow, circle, polyline } from './overlay';
import type { DeformTool, ScreenPoint, ToolContext, ToolRequest } from './tool';

const MAX_GUIDES = 2000;
const VERTEX_HIT_PX = 10;
const TARGET_HIT_PX = 10;
/** A press on a vertex becomes a guide once the pointer has moved this far. */
const DRAG_START_PX = 3;
const PATTERN_SPACING_PX = 26;
const PATTERN_MAX_POINTS = 60;
const PATTERN_SNAP_PX = 24;

interface GuideState {
  /** Node index. */
  node: number;
  /** Where the node should be on the deformed map. */
  target: LonLat;
}

type Drag = { node: number; start: ScreenPoint; guide?: GuideState };

const SHAPES: Record<PatternShape, string> = { line: 'Straight line (start to end)', circle: 'Circle' };

/**
 * Mental map: drag road vertices to where you picture them; each drag adds (or moves) a guide
 * that pulls that vertex to its target, shown as an arrow from its original position. The
 * pattern helper turns a freehand stroke into guides whose targets lie on a line or circle.
 */
export class MentalTool implements DeformTool {
  readonly kind = 'mental' as const;
  readonly panel: HTMLElement;
  private readonly count: HTMLElement;
  private readonly patternButton: HTMLButtonElement;
  private readonly shapeSelect: HTMLSelectElement;
  private readonly undoButton: HTMLButtonElement;
  private readonly clearButton: HTMLButtonElement;
  private context: ToolContext | null = null;
  private guides: GuideState[] = [];
  private drag?: Drag;
  private hoverNode = -1;
  private patternMode = false;
  private stroke?: ScreenPoint[];

  constructor() {
    this.count = h('p', { class: 'tool-count', 'data-testid': 'guide-count' });
    this.patternButton = h('button', { type: 'button', class: 'button button-toggle', 'aria-pressed': 'false', 'data-testid': 'pattern-button' }, 'Draw a pattern');
    this.patternButton.addEventListener('click', () => this.setPatternMode(!this.patternMode));
    this.shapeSelect = h(
      'select',
      { id: 'pattern-shape', 'aria-label': 'Pattern shape' },
      ...Object.entries(SHAPES).map(([value, text]) => h('option', { value }, text)),
    );
    this.undoButton = h('button', { type: 'button', class: 'button button-quiet' }, 'Remove last guide');
    this.undoButton.addEventListener('click', () => {
      this.guides.pop();
      this.changed();
    });
    this.clearButton = h('button', { type: 'button', class: 'button button-quiet' }, 'Remove all guides');
    this.clearButton.addEventListener('click', () => {
      this.guides = [];
      this.changed();
    });
    this.panel = h(
      'div',
      { class: 'tool-panel' },
      h(
        'p',
        { class: 'hint' },
        'Drag a road vertex (the map snaps to the nearest one) to where you picture it: it becomes a guide, drawn as an arrow from its true position to its target, and the map bends to follow. Drag an arrow’s head to move its target.',
      ),
      this.count,
      h(
        'fieldset',
        { class: 'pattern' },
        h('legend', {}, 'Pattern helper'),
        h('p', { class: 'note' }, 'Draw a freehand line over roads: the vertices under it are pulled onto the chosen shape (a straight line from where you started to where you stopped, or a circle around what you drew).'),
        h('div', { class: 'button-row' }, this.patternButton, this.shapeSelect),
      ),
      h('div', { class: 'button-row' }, this.undoButton, this.clearButton),
    );
    this.syncPanel();
  }

  reset(context: ToolContext | null): void {
    this.context = context;
    this.guides = [];
    this.drag = undefined;
    this.hoverNode = -1;
    this.stroke = undefined;
    this.setPatternMode(false);
    this.syncPanel();
  }

  request(): ToolRequest | null {
    const context = this.context;
    if (!context || this.guides.length === 0) return null;
    return { guides: this.guides.map((guide) => ({ vertex: context.graph.nodeIds[guide.node]!, target: roundLonLat(guide.target) })) };
  }

  applied(): void {}

  pointerDown(point: ScreenPoint): boolean {
    const context = this.context;
    if (!context) return false;
    if (this.patternMode) {
      this.stroke = [point];
      return true;
    }
    const target = this.targetAt(point);
    const node = target ? target.node : this.vertexAt(point);
    if (node < 0) return false;
    this.drag = { node, start: point, guide: target };
    context.dragging(true);
    return true;
  }

  pointerMove(point: ScreenPoint): void {
    const context = this.context;
    if (!context) return;
    if (this.stroke) {
      extendStroke(this.stroke, point);
      context.redraw();
      return;
    }
    const drag = this.drag;
    if (!drag) return;
    if (!drag.guide) {
      if (Math.hypot(point[0] - drag.start[0], point[1] - drag.start[1]) < DRAG_START_PX) return;
      drag.guide = this.guides.find((guide) => guide.node === drag.node);
      if (!drag.guide) {
        if (this.guides.length >= MAX_GUIDES) return context.notify(`At most ${MAX_GUIDES} guides: remove some first.`);
        drag.guide = { node: drag.node, target: [0, 0] };
        this.guides.push(drag.guide);
      }
    }
    drag.guide.target = context.frame.unproject(...context.map.toFrame(...point));
    this.changed();
  }

  pointerUp(): void {
    if (this.stroke) {
      const stroke = this.stroke;
      this.stroke = undefined;
      this.applyPattern(stroke);
      this.setPatternMode(false);
      return;
    }
    if (!this.drag) return;
    this.drag = undefined;
    this.context?.dragging(false);
  }

  click(): void {}

  hover(point: ScreenPoint | null): string {
    if (this.patternMode) return 'crosshair';
    const target = point ? this.targetAt(point) : undefined;
    const node = target ? -1 : point ? this.vertexAt(point) : -1;
    if (node !== this.hoverNode) {
      this.hoverNode = node;
      this.context?.redraw();
    }
    return target || node >= 0 ? 'grab' : '';
  }

  key(event: KeyboardEvent): boolean {
    if (event.key === 'Escape' && this.patternMode) {
      this.stroke = undefined;
      this.setPatternMode(false);
      this.context?.redraw();
      return true;
    }
    if ((event.key === 'Delete' || event.key === 'Backspace') && this.guides.length > 0) {
      this.guides.pop();
      this.changed();
      return true;
    }
    return false;
  }

  highlighted(): number[] {
    return [];
  }

  render(layer: SVGGElement): void {
    const context = this.context;
    if (!context) return;
    const { map, frame, original } = context;
    const drawn = context.displacement().deformed;
    for (const guide of this.guides) {
      const from = map.toScreen(original[2 * guide.node]!, original[2 * guide.node + 1]!);
      const to = map.toScreen(...frame.project(guide.target));
      const active = this.drag?.guide === guide;
      layer.append(circle(from, 3, 'guide-origin'), arrow(from, to, `guide-arrow${active ? ' active' : ''}`), circle(to, 5, 'guide-target'));
    }
    const node = this.drag && !this.drag.guide ? this.drag.node : this.hoverNode;
    if (node >= 0) layer.append(circle(map.toScreen(drawn[2 * node]!, drawn[2 * node + 1]!), 7, 'vertex-hover'));
    if (this.stroke && this.stroke.length > 1) {
      layer.append(polyline(this.stroke, 'pattern-stroke'));
      const samples = resample(this.stroke, PATTERN_SPACING_PX, PATTERN_MAX_POINTS);
      layer.append(polyline(patternTargets(samples, this.shape), 'pattern-preview'));
    }
  }

  private get shape(): PatternShape {
    return this.shapeSelect.value as PatternShape;
  }

  private setPatternMode(on: boolean): void {
    this.patternMode = on;
    this.patternButton.setAttribute('aria-pressed', String(on));
    this.patternButton.textContent = on ? 'Drawing… (Esc cancels)' : 'Draw a pattern';
  }

  /**
   * The stroke's sample points snap to the nearest drawn road vertex (each vertex once); their
   * targets are the samples moved onto the shape.
   */
  private applyPattern(stroke: ScreenPoint[]): void {
    const context = this.context;
    if (!context) return;
    const { map, frame } = context;
    const samples = resample(stroke, PATTERN_SPACING_PX, PATTERN_MAX_POINTS);
    if (samples.length < 2) return context.notify('Draw a longer line for a pattern.');
    const targets = patternTargets(samples, this.shape);
    const displacement = context.displacement();
    const used = new Set<number>();
    let added = 0;
    samples.forEach(({ point }, i) => {
      const node = displacement.nearestDrawn(...map.toFrame(...point), PATTERN_SNAP_PX / map.scale);
      if (node < 0 || used.has(node)) return;
      used.add(node);
      const target = frame.unproject(...map.toFrame(...targets[i]!));
      const existing = this.guides.find((guide) => guide.node === node);
      if (existing) existing.target = target;
      else if (this.guides.length < MAX_GUIDES) this.guides.push({ node, target });
      added++;
    });
    if (added === 0) return context.notify('No road vertex under the pattern: draw it along roads.');
    context.notify(null);
    this.changed();
  }

  /** The guide whose target handle is under the point. */
  private targetAt(point: ScreenPoint): GuideState | undefined {
    const context = this.context;
    if (!context) return undefined;
    let best: GuideState | undefined;
    let bestDistance = TARGET_HIT_PX;
    for (const guide of this.guides) {
      const [x, y] = context.map.toScreen(...context.frame.project(guide.target));
      const distance = Math.hypot(point[0] - x, point[1] - y);
      if (distance <= bestDistance) {
        best = guide;
        bestDistance = distance;
      }
    }
    return best;
  }

  /** The road vertex drawn nearest to the point, within VERTEX_HIT_PX; -1 if none. */
  private vertexAt(point: ScreenPoint): number {
    const context = this.context;
    if (!context) return -1;
    const { map } = context;
    return context.displacement().nearestDrawn(...map.toFrame(...point), VERTEX_HIT_PX / map.scale);
  }

  private changed(): void {
    this.syncPanel();
    this.context?.changed();
  }

  private syncPanel(): void {
    const n = this.guides.length;
    this.count.textContent = n === 0 ? 'No guides yet.' : `${n} guide${n === 1 ? '' : 's'}`;
    this.undoButton.disabled = this.clearButton.disabled = n === 0;
  }
}
