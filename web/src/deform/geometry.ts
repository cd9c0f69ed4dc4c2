import type { LonLat } from '../api/types';
import { distanceMeters } from '../map/distance';
import type { Frame } from '../map/projection';

/** Metres per frame unit around a point of the frame (Web Mercator's scale varies with latitude). */
export function metersPerUnit(frame: Frame, x: number, y: number): number {
  return distanceMeters(frame.unproject(x, y), frame.unproject(x + 1, y));
}

/** Rounds degrees to 7 decimals (about a centimetre): shorter requests, same map. */
export function roundLonLat([lon, lat]: LonLat): LonLat {
  return [Math.round(lon * 1e7) / 1e7, Math.round(lat * 1e7) / 1e7];
}

/** value limited to [min, max]. */
export function clamp(value: number, min: number, max: number): number {
  return Math.max(min, Math.min(max, value));
}
