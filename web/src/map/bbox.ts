import type { BBox, LonLat } from '../api/types';

/** The bbox grown to hold every position. */
export function extendBBox(bbox: BBox, positions: LonLat[]): BBox {
  const [west, south, east, north] = bbox;
  const out: BBox = [west, south, east, north];
  for (const [lon, lat] of positions) {
    out[0] = Math.min(out[0], lon);
    out[1] = Math.min(out[1], lat);
    out[2] = Math.max(out[2], lon);
    out[3] = Math.max(out[3], lat);
  }
  return out;
}
