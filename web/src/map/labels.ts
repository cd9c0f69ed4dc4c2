import type { Anchor, SvgMap } from './svg-map';

/** Labels are measured with a canvas in this font, so styles.css must not change it. */
export const LABEL_FONT = '600 12px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
const LINE_HEIGHT = 14;
/** Distance between a point and its label. */
const GAP = 8;
/** Half the size of the square kept free around every marker. */
const MARKER_RADIUS = 6;

export interface Label {
  anchor: Anchor;
  /** The marker the label names: it does not count as an obstacle to its own label. */
  marker: Anchor;
  text: SVGTextElement;
  width: number;
  /** Higher goes first, so busy interchanges keep their names. */
  priority: number;
}

/** A rectangle in screen pixels. */
export interface Box {
  x0: number;
  y0: number;
  x1: number;
  y1: number;
}

interface Placement {
  dx: number;
  dy: number;
  textAnchor: 'start' | 'middle' | 'end';
  box(x: number, y: number, width: number): Box;
}

// Right of the point first, then left, above and below. dy moves the baseline to mid-height.
const PLACEMENTS: Placement[] = [
  { dx: GAP, dy: 4, textAnchor: 'start', box: (x, y, w) => ({ x0: x + GAP, y0: y - 7, x1: x + GAP + w, y1: y + 7 }) },
  { dx: -GAP, dy: 4, textAnchor: 'end', box: (x, y, w) => ({ x0: x - GAP - w, y0: y - 7, x1: x - GAP, y1: y + 7 }) },
  { dx: 0, dy: -GAP - 2, textAnchor: 'middle', box: (x, y, w) => ({ x0: x - w / 2, y0: y - GAP - LINE_HEIGHT, x1: x + w / 2, y1: y - GAP }) },
  { dx: 0, dy: GAP + 10, textAnchor: 'middle', box: (x, y, w) => ({ x0: x - w / 2, y0: y + GAP, x1: x + w / 2, y1: y + GAP + LINE_HEIGHT }) },
];

let measureContext: CanvasRenderingContext2D | null | undefined;

export function labelWidth(text: string): number {
  measureContext ??= document.createElement('canvas').getContext('2d');
  if (!measureContext) return text.length * 7;
  measureContext.font = LABEL_FONT;
  return measureContext.measureText(text).width;
}

const overlaps = (a: Box, b: Box) => a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;

/**
 * Shows the labels that fit without overlapping each other, a marker or an obstacle (screen
 * boxes: other layers' markers), greedily by priority, and hides the rest. Labels off screen
 * are hidden too.
 */
export function placeLabels(map: SvgMap, labels: Label[], markers: Anchor[], obstacles: Box[] = []): void {
  const { width, height } = map.size;
  const markerBoxes = markers.map((marker) => {
    const [x, y] = map.toScreen(marker.x, marker.y);
    return { marker, box: { x0: x - MARKER_RADIUS, y0: y - MARKER_RADIUS, x1: x + MARKER_RADIUS, y1: y + MARKER_RADIUS } };
  });
  const taken: Box[] = [...obstacles];
  const free = (box: Box, own: Anchor) =>
    box.x0 >= 0 && box.y0 >= 0 && box.x1 <= width && box.y1 <= height &&
    !taken.some((other) => overlaps(box, other)) &&
    !markerBoxes.some(({ marker, box: markerBox }) => marker !== own && overlaps(box, markerBox));

  for (const label of [...labels].sort((a, b) => b.priority - a.priority)) {
    const [x, y] = map.toScreen(label.anchor.x, label.anchor.y);
    const placement = PLACEMENTS.find((candidate) => free(candidate.box(x, y, label.width), label.marker));
    if (!placement) {
      label.text.setAttribute('visibility', 'hidden');
      continue;
    }
    taken.push(placement.box(x, y, label.width));
    label.anchor.dx = placement.dx;
    label.anchor.dy = placement.dy;
    label.text.setAttribute('text-anchor', placement.textAnchor);
    label.text.setAttribute('visibility', 'visible');
  }
  map.requestRender();
}

