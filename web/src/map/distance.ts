import type { LonLat } from '../api/types';

const EARTH_RADIUS_M = 6371008.8;

/** Great-circle distance in metres (haversine). */
export function distanceMeters([lon1, lat1]: LonLat, [lon2, lat2]: LonLat): number {
  const rad = Math.PI / 180;
  const dLat = (lat2 - lat1) * rad;
  const dLon = (lon2 - lon1) * rad;
  const a = Math.sin(dLat / 2) ** 2 + Math.cos(lat1 * rad) * Math.cos(lat2 * rad) * Math.sin(dLon / 2) ** 2;
  return 2 * EARTH_RADIUS_M * Math.asin(Math.min(1, Math.sqrt(a)));
}

export function formatDistance(meters: number): string {
  // A no-break space: a narrow panel must not put the unit on a line of its own.
  return meters < 1000 ? `${Math.round(meters / 10) * 10}\u00a0m` : `${(meters / 1000).toFixed(1)}\u00a0km`;
}

/** The `limit` nearest items within `maxMeters`, nearest first. */
export function nearest<T>(from: LonLat, items: T[], position: (item: T) => LonLat, maxMeters: number, limit: number) {
  return items
    .map((item) => ({ item, meters: distanceMeters(from, position(item)) }))
    .filter((entry) => entry.meters <= maxMeters)
    .sort((a, b) => a.meters - b.meters)
    .slice(0, limit);
}
