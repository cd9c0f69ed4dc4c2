import type { MetroLine } from '../api/types';

/** For lines without a colour in the data. */
const FALLBACK_LINE_COLOR = '#8a9099';

export function lineColor(line: MetroLine | undefined): string {
  return line && /^[0-9a-f]{6}$/i.test(line.color) ? `#${line.color}` : FALLBACK_LINE_COLOR;
}

/** Black or white, whichever reads better on the line's colour (WCAG relative luminance). */
export function textColorOn(hex: string): string {
  const channel = (offset: number) => {
    const c = parseInt(hex.slice(offset, offset + 2), 16) / 255;
    return c <= 0.03928 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
  };
  const luminance = 0.2126 * channel(1) + 0.7152 * channel(3) + 0.0722 * channel(5);
  return luminance > 0.4 ? '#111' : '#fff';
}

/** By label, numbers in labels compared as numbers ("U2" before "U11"). */
export function sortLines(lines: MetroLine[]): MetroLine[] {
  return [...lines].sort((a, b) => a.label.localeCompare(b.label, undefined, { numeric: true, sensitivity: 'base' }));
}

/** The line's dash pattern in px for a stroke of `width` px ("" for a solid line). */
export function lineDash(line: MetroLine | undefined, width: number): string {
  const dash = line?.style?.dash ?? [];
  return dash.length > 0 ? dash.map((d) => (d * width).toFixed(1)).join(' ') : '';
}

/** Whether the line is drawn with a thin contrasting border. */
export function lineCasing(line: MetroLine | undefined): boolean {
  return line?.style?.casing === true;
}

/** A legend swatch's CSS background: the colour, dashed as the line is (stripes for a dash). */
export function swatchBackground(line: MetroLine): string {
  const color = lineColor(line);
  const dash = line.style?.dash ?? [];
  if (dash.length < 2) return color;
  const on = dash[0]! * 6;
  const off = dash[1]! * 6;
  return `repeating-linear-gradient(90deg, ${color} 0 ${on}px, transparent ${on}px ${on + off}px)`;
}
