import { ApiError, isAbort } from './client';
import type { LonLat, XY } from './types';

/** One walk from a POI to a station (GET /cities/{id}/pois/{poi}/walk). */
export interface StationWalk {
  station: { id: string; station_id: string; name: string };
  /** Along the path, metres. */
  distance_m: number;
  straight_m: number;
  /** At 4.8 km/h. */
  minutes: number;
  /** From the POI to the station. */
  path: LonLat[];
  /** The same path in the default layout's frame; null when the city has no layout. */
  path_layout: XY[] | null;
}

export interface WalkResponse {
  city: string;
  poi: { id: string; name: string; lon: number; lat: number; layout: XY | null; road_m: number | null };
  /** Nearest first; empty when no station is within max_m. */
  walks: StationWalk[];
  params: { stations: number; max_m: number; speed_kmh: number };
  layout_frame: 'layout' | null;
  attribution: string[];
}

/** How many stations a walk asks for, and the longest walk, metres. */
export const WALK_STATIONS = 3;
export const WALK_MAX_M = 2000;

/**
 * The POI's nearest stations by walking distance over the city's roads. Failures throw ApiError:
 * 409 (field road_network) when the city has no road network, 404 for an unknown POI.
 */
export async function fetchWalk(cityId: string, poiId: string, signal?: AbortSignal): Promise<WalkResponse> {
  const path = `/cities/${encodeURIComponent(cityId)}/pois/${encodeURIComponent(poiId)}/walk?stations=${WALK_STATIONS}&max_m=${WALK_MAX_M}`;
  let response: Response;
  try {
    response = await fetch(`/api/v1${path}`, { signal, cache: 'no-cache', headers: { Accept: 'application/json' } });
  } catch (error) {
    if (isAbort(error)) throw error;
    throw new ApiError(0, 'network', 'The map service cannot be reached.', undefined, path);
  }
  if (!response.ok) {
    let code = 'http_error';
    let message = `${response.status} ${response.statusText || 'error'}`;
    let field: string | undefined;
    try {
      const body = (await response.json()) as { error?: { message?: string; code?: string; field?: string } };
      code = body.error?.code ?? code;
      message = body.error?.message ?? message;
      field = body.error?.field ?? undefined;
    } catch {
      // not the API's error envelope: the status line says enough
    }
    throw new ApiError(response.status, code, message, field, path);
  }
  return (await response.json()) as WalkResponse;
}

/** What a failed walk request means to a tourist (no HTTP status shown). */
export function walkErrorText(error: unknown): string {
  if (error instanceof ApiError) {
    if (error.status === 409 || error.field === 'road_network') return 'This city has no street map to plan walks on.';
    if (error.status === 404) return 'This place is no longer on the map. Reload the page and try again.';
    if (error.status === 0) return 'The map service cannot be reached. Check your connection and try again.';
    if (error.status === 429 || error.status === 503) return 'The map service is busy. Try again in a moment.';
  }
  return 'The walk could not be worked out. Try again in a moment.';
}
