/** Numbers of the Crowd view as people read them: 1.94 M triangles, 45.7 kB, 310 ms. */

const missing = (value: number | undefined | null): value is undefined | null => value === undefined || value === null || !Number.isFinite(value);

/** 3 significant digits with k / M / G above ten thousand: 1.94 M, 16.4 M, 45.7 k, 5,200. */
export function formatCount(value: number | undefined | null): string {
  if (missing(value)) return '—';
  const abs = Math.abs(value);
  const scaled = (divisor: number, unit: string) => `${Number((value / divisor).toPrecision(3)).toLocaleString('en')} ${unit}`;
  if (abs >= 1e9) return scaled(1e9, 'G');
  if (abs >= 1e6) return scaled(1e6, 'M');
  if (abs >= 1e4) return scaled(1e3, 'k');
  return Math.round(value).toLocaleString('en');
}

export function formatBytes(value: number | undefined | null): string {
  if (missing(value)) return '—';
  if (value >= 1e6) return `${(value / 1e6).toPrecision(3)} MB`;
  if (value >= 1e3) return `${(value / 1e3).toPrecision(3)} kB`;
  return `${Math.round(value)} B`;
}

export function formatMs(value: number | undefined | null): string {
  if (missing(value)) return '—';
  return `${Math.abs(value) < 10 ? value.toFixed(1) : Math.round(value).toLocaleString('en')} ms`;
}

export function formatFps(value: number | undefined | null): string {
  if (missing(value)) return '—';
  return value < 10 ? value.toFixed(1) : Math.round(value).toString();
}

/** A pixel error: 0.50, 2.5, 16. */
export const formatPoe = (poe: number) => (poe < 1 ? poe.toFixed(2) : poe < 10 ? poe.toFixed(1) : poe.toFixed(0));
