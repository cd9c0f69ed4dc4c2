import { svg } from '../map/svg';
import type { ScreenPoint } from './tool';

const f = (value: number) => value.toFixed(1);

export function pointsAttribute(points: ScreenPoint[]): string {
  return points.map(([x, y]) => `${f(x)},${f(y)}`).join(' ');
}

export function circle([x, y]: ScreenPoint, r: number, className: string): SVGCircleElement {
  return svg('circle', { cx: f(x), cy: f(y), r, class: className });
}

export function polyline(points: ScreenPoint[], className: string, closed = false): SVGElement {
  return svg(closed ? 'polygon' : 'polyline', { points: pointsAttribute(points), class: className });
}

/** A line with an arrow head at `to`. */
export function arrow(from: ScreenPoint, to: ScreenPoint, className: string): SVGGElement {
  const group = svg('g', { class: className });
  const [x0, y0] = from;
  const [x1, y1] = to;
  const length = Math.hypot(x1 - x0, y1 - y0);
  group.append(svg('line', { x1: f(x0), y1: f(y0), x2: f(x1), y2: f(y1) }));
  if (length > 4) {
    const ux = (x1 - x0) / length;
    const uy = (y1 - y0) / length;
    const size = Math.min(10, length / 2);
    const head = [
      [x1, y1],
      [x1 - ux * size - uy * size * 0.5, y1 - uy * size + ux * size * 0.5],
      [x1 - ux * size + uy * size * 0.5, y1 - uy * size - ux * size * 0.5],
    ] as ScreenPoint[];
    group.append(svg('polygon', { points: pointsAttribute(head) }));
  }
  return group;
}

export function label([x, y]: ScreenPoint, text: string, className: string): SVGTextElement {
  const element = svg('text', { x: f(x), y: f(y), class: className });
  element.textContent = text;
  return element;
}

/** Distance from p to the segment a-b. */
export function segmentDistance(p: ScreenPoint, a: ScreenPoint, b: ScreenPoint): number {
  const dx = b[0] - a[0];
  const dy = b[1] - a[1];
  const length2 = dx * dx + dy * dy;
  const t = length2 === 0 ? 0 : Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2));
  return Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

/** Distance from p to a polyline (or closed polygon). */
export function polylineDistance(p: ScreenPoint, points: ScreenPoint[], closed: boolean): number {
  let best = Infinity;
  const count = closed ? points.length : points.length - 1;
  for (let i = 0; i < count; i++) best = Math.min(best, segmentDistance(p, points[i]!, points[(i + 1) % points.length]!));
  return best;
}
