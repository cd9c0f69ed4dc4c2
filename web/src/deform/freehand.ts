import type { ScreenPoint } from './tool';

/** Adds a point to a freehand stroke unless it is within `minGap` pixels of the last one. */
export function extendStroke(stroke: ScreenPoint[], point: ScreenPoint, minGap = 3): void {
  const last = stroke[stroke.length - 1];
  if (!last || Math.hypot(point[0] - last[0], point[1] - last[1]) >= minGap) stroke.push(point);
}

export function strokeLength(stroke: ScreenPoint[]): number {
  let length = 0;
  for (let i = 1; i < stroke.length; i++) length += Math.hypot(stroke[i]![0] - stroke[i - 1]![0], stroke[i]![1] - stroke[i - 1]![1]);
  return length;
}

/**
 * Points every `spacing` pixels along a stroke (its ends included), at most `maxCount`, each
 * with its fraction of the stroke's length.
 */
export function resample(stroke: ScreenPoint[], spacing: number, maxCount: number): { point: ScreenPoint; t: number }[] {
  const total = strokeLength(stroke);
  if (stroke.length === 0) return [];
  if (total === 0) return [{ point: stroke[0]!, t: 0 }];
  const count = Math.max(2, Math.min(maxCount, Math.floor(total / spacing) + 1));
  const samples: { point: ScreenPoint; t: number }[] = [];
  let segment = 0;
  let walked = 0;
  for (let i = 0; i < count; i++) {
    const at = (total * i) / (count - 1);
    while (segment < stroke.length - 2) {
      const length = Math.hypot(stroke[segment + 1]![0] - stroke[segment]![0], stroke[segment + 1]![1] - stroke[segment]![1]);
      if (walked + length >= at) break;
      walked += length;
      segment++;
    }
    const a = stroke[segment]!;
    const b = stroke[Math.min(segment + 1, stroke.length - 1)]!;
    const length = Math.hypot(b[0] - a[0], b[1] - a[1]);
    const u = length === 0 ? 0 : Math.max(0, Math.min(1, (at - walked) / length));
    samples.push({ point: [a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])], t: at / total });
  }
  return samples;
}

export type PatternShape = 'line' | 'circle';

/**
 * The targets of a pattern: the drawn samples moved onto a straight line from the stroke's
 * start to its end (at the same fraction of length), or radially onto the circle through the
 * samples' centroid at their mean distance.
 */
export function patternTargets(samples: { point: ScreenPoint; t: number }[], shape: PatternShape): ScreenPoint[] {
  if (samples.length === 0) return [];
  if (shape === 'line') {
    const [x0, y0] = samples[0]!.point;
    const [x1, y1] = samples[samples.length - 1]!.point;
    return samples.map(({ t }) => [x0 + t * (x1 - x0), y0 + t * (y1 - y0)]);
  }
  let cx = 0;
  let cy = 0;
  for (const { point } of samples) {
    cx += point[0] / samples.length;
    cy += point[1] / samples.length;
  }
  const radius = samples.reduce((sum, { point }) => sum + Math.hypot(point[0] - cx, point[1] - cy), 0) / samples.length;
  return samples.map(({ point }) => {
    const d = Math.hypot(point[0] - cx, point[1] - cy);
    return d === 0 ? point : [cx + ((point[0] - cx) / d) * radius, cy + ((point[1] - cy) / d) * radius];
  });
}
