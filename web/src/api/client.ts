import type {
  BBox,
  CityDetail,
  CitySummary,
  ClusterSpace,
  ClustersResponse,
  CrowdScenesResponse,
  DeformBody,
  DeformKind,
  DeformResponse,
  LayoutParams,
  LayoutResponse,
  MetroCollection,
  PoiCollection,
  PoiFeature,
  RoadCollection,
  RoadContext,
  RoadNetworkSummary,
  RoadTopology,
  VisualWorthRaster,
} from './types';

const API_ROOT = '/api/v1';
/** The server's maximum page size for POIs. */
const POI_PAGE = 10000;

/** A failed request: an HTTP error with the API's error envelope, or no answer at all (status 0). */
export class ApiError extends Error {
  constructor(
    readonly status: number,
    readonly code: string,
    message: string,
    readonly field?: string,
    /** The API path asked for (under /api/v1), to say what was not found. */
    readonly path?: string,
  ) {
    super(message);
    this.name = 'ApiError';
  }
}

export function isAbort(error: unknown): boolean {
  return error instanceof DOMException && error.name === 'AbortError';
}

async function errorFrom(response: Response, path: string): Promise<ApiError> {
  try {
    const body = (await response.json()) as { error?: { code?: string; message?: string; field?: string } };
    if (body.error?.message) {
      return new ApiError(response.status, body.error.code ?? 'error', body.error.message, body.error.field ?? undefined, path);
    }
  } catch {
    // Not the JSON error envelope (a proxy's HTML page, say): fall through to the status line.
  }
  return new ApiError(response.status, 'http_error', `${response.status} ${response.statusText || 'error'}`, undefined, path);
}

async function requestJson<T>(path: string, init: RequestInit): Promise<T> {
  return (await requestWithHeaders<T>(path, init)).body;
}

// ---- Busy answers (429, 503): wait as asked and try again ----

/** Retries of one request the server asked to repeat later (429 or 503). */
const MAX_RETRIES = 6;
/** The wait when Retry-After is missing or unreadable (doubled on every retry, up to the cap). */
const DEFAULT_RETRY_MS = 1000;
/** Longest single wait, whatever Retry-After says. */
const MAX_RETRY_WAIT_MS = 30_000;
/** Longest total waiting for one request: after this the busy answer is the error. */
const MAX_TOTAL_WAIT_MS = 60_000;

/** Resolves after `ms`, or rejects with an AbortError when `signal` aborts first. */
function wait(ms: number, signal?: AbortSignal | null): Promise<void> {
  return new Promise((resolve, reject) => {
    if (signal?.aborted) return reject(new DOMException('aborted', 'AbortError'));
    const abort = () => {
      window.clearTimeout(timer);
      reject(new DOMException('aborted', 'AbortError'));
    };
    const timer = window.setTimeout(() => {
      signal?.removeEventListener('abort', abort);
      resolve();
    }, ms);
    signal?.addEventListener('abort', abort, { once: true });
  });
}

/**
 * The wait (ms) a Retry-After header asks for: delay-seconds or an HTTP date (RFC 9110 10.2.3);
 * null when missing or unreadable.
 */
export function retryAfterMs(header: string | null, now = Date.now()): number | null {
  if (header === null || header.trim() === '') return null;
  const text = header.trim();
  if (/^\d+$/.test(text)) return Number(text) * 1000;
  const date = Date.parse(text);
  return Number.isFinite(date) ? Math.max(0, date - now) : null;
}

/** The wait before retry `attempt` (0 first): as asked, else exponential; capped, plus up to 20 % jitter. */
function retryDelayMs(response: Response, attempt: number): number {
  const asked = retryAfterMs(response.headers.get('Retry-After')) ?? DEFAULT_RETRY_MS * 2 ** attempt;
  const capped = Math.min(Math.max(asked, 100), MAX_RETRY_WAIT_MS);
  // Jitter: clients turned away together do not all come back in the same instant.
  return capped * (1 + Math.random() * 0.2);
}

/** Requests now waiting to retry a busy answer; listeners hear when that becomes true or false. */
let waitingRequests = 0;
const busyListeners = new Set<(busy: boolean) => void>();

/** Calls `listener(busy)` whenever requests start or stop waiting on a busy server; returns the unsubscriber. */
export function onBusyChange(listener: (busy: boolean) => void): () => void {
  busyListeners.add(listener);
  return () => busyListeners.delete(listener);
}

function setWaiting(delta: number): void {
  const before = waitingRequests > 0;
  waitingRequests += delta;
  const after = waitingRequests > 0;
  if (before !== after) for (const listener of busyListeners) listener(after);
}

/** The successful answer to a request, retrying quietly where the server asks to come back later. */
async function fetchOk(path: string, init: RequestInit): Promise<Response> {
  let waited = 0;
  for (let attempt = 0; ; attempt++) {
    let response: Response;
    try {
      response = await fetch(API_ROOT + path, { ...init, headers: { Accept: 'application/json', ...init.headers } });
    } catch (error) {
      if (isAbort(error)) throw error;
      console.warn(`tourmap: ${API_ROOT}${path} failed:`, error);
      throw new ApiError(0, 'network', 'The map service cannot be reached. Check your connection and try again.', undefined, path);
    }
    if (response.ok) return response;
    const busy = response.status === 429 || response.status === 503;
    const delay = busy ? retryDelayMs(response, attempt) : 0;
    if (!busy || attempt >= MAX_RETRIES || waited + delay > MAX_TOTAL_WAIT_MS) throw await errorFrom(response, path);
    // Busy or rate limited: the server says when to come back; wait quietly and try again.
    console.info(`tourmap: ${API_ROOT}${path} answered ${response.status}; retrying in ${Math.round(delay)} ms`);
    await response.body?.cancel().catch(() => {});
    waited += delay;
    setWaiting(+1);
    try {
      await wait(delay, init.signal);
    } finally {
      setWaiting(-1);
    }
  }
}

/** requestJson, also handing back the answer's headers (X-Result-Cache, say). */
async function requestWithHeaders<T>(path: string, init: RequestInit): Promise<{ body: T; headers: Headers }> {
  const response = await fetchOk(path, init);
  return { body: (await response.json()) as T, headers: response.headers };
}

function getJson<T>(path: string, signal?: AbortSignal): Promise<T> {
  // no-cache: revalidate with the ETag every time, so data imported a moment ago is never
  // hidden behind the API's max-age.
  return requestJson<T>(path, { signal, cache: 'no-cache' });
}

const segment = encodeURIComponent;

export function fetchCities(signal?: AbortSignal): Promise<CitySummary[]> {
  return getJson<{ cities: CitySummary[] }>('/cities', signal).then((body) => body.cities);
}

export function fetchCity(id: string, signal?: AbortSignal): Promise<CityDetail> {
  return getJson<CityDetail>(`/cities/${segment(id)}`, signal);
}

export function fetchMetro(id: string, signal?: AbortSignal): Promise<MetroCollection> {
  return getJson<MetroCollection>(`/cities/${segment(id)}/metro`, signal);
}

/** Every POI of the city, following the server's pagination. */
export async function fetchPois(id: string, signal?: AbortSignal): Promise<PoiCollection> {
  const first = await getJson<PoiCollection>(`/cities/${segment(id)}/pois?limit=${POI_PAGE}`, signal);
  const features: PoiFeature[] = [...first.features];
  while (first.returned > 0 && features.length < first.matched) {
    const page = await getJson<PoiCollection>(
      `/cities/${segment(id)}/pois?limit=${POI_PAGE}&offset=${features.length}`,
      signal,
    );
    if (page.returned === 0) break;
    features.push(...page.features);
  }
  return { ...first, features, returned: features.length };
}

export function fetchRoadNetworks(signal?: AbortSignal): Promise<RoadNetworkSummary[]> {
  return getJson<{ roads: RoadNetworkSummary[] }>('/roads', signal).then((body) => body.roads);
}

export function fetchRoads(id: string, signal?: AbortSignal): Promise<RoadCollection> {
  return getJson<RoadCollection>(`/roads/${segment(id)}`, signal);
}

/** The road network as nodes and ways: what the Deform view draws and routes on. */
export function fetchRoadTopology(id: string, signal?: AbortSignal): Promise<RoadTopology> {
  return getJson<RoadTopology>(`/roads/${segment(id)}?format=topology`, signal);
}

/** The context layers of a road network, simplified to `simplifyM` metres. */
export function fetchRoadContext(id: string, simplifyM: number, signal?: AbortSignal): Promise<RoadContext> {
  return getJson<RoadContext>(`/roads/${segment(id)}/context?simplify_m=${simplifyM}`, signal);
}

/** The binary deform answer's first bytes (api/positions_binary.hpp). */
const POSITIONS_MAGIC = 'TMDP';

/**
 * The binary answer to a deform request: the JSON fields, then the positions as float32
 * offsets from a float64 origin (openapi.yaml, DeformResult). Copied into a Float64Array of
 * [lon, lat, ...] without parsing text.
 */
export function decodeDeformBinary(buffer: ArrayBuffer): DeformResponse {
  const view = new DataView(buffer);
  const bad = (why: string) => new ApiError(0, 'bad_answer', `The server's binary answer is malformed: ${why}.`);
  if (buffer.byteLength < 32) throw bad('too short');
  const magic = String.fromCharCode(view.getUint8(0), view.getUint8(1), view.getUint8(2), view.getUint8(3));
  if (magic !== POSITIONS_MAGIC) throw bad('not a positions answer');
  if (view.getUint32(4, true) !== 1) throw bad('an unknown version');
  const jsonBytes = view.getUint32(8, true);
  const count = view.getUint32(12, true);
  const lon0 = view.getFloat64(16, true);
  const lat0 = view.getFloat64(24, true);
  const start = Math.ceil((32 + jsonBytes) / 4) * 4;
  if (buffer.byteLength !== start + 8 * count) throw bad('its length does not match its header');
  const result = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 32, jsonBytes))) as DeformResponse;
  const offsets = new Float32Array(buffer, start, 2 * count);
  const positions = new Float64Array(2 * count);
  for (let i = 0; i < 2 * count; i += 2) {
    positions[i] = lon0 + offsets[i]!;
    positions[i + 1] = lat0 + offsets[i + 1]!;
  }
  result.positions = positions;
  return result;
}

/**
 * POST /api/v1/deform/{kind}. Positions come as binary (a 56,000-node network's answer is
 * copied, not parsed); a server that answers JSON anyway is read as JSON.
 */
export async function postDeform(kind: DeformKind, body: DeformBody, signal?: AbortSignal): Promise<DeformResponse> {
  const binary = body.output.roads === 'positions';
  const response = await fetchOk(`/deform/${kind}`, {
    method: 'POST',
    signal,
    headers: { 'Content-Type': 'application/json', ...(binary ? { Accept: 'application/octet-stream' } : {}) },
    body: JSON.stringify(body),
  });
  if (response.headers.get('Content-Type')?.startsWith('application/octet-stream')) return decodeDeformBinary(await response.arrayBuffer());
  return (await response.json()) as DeformResponse;
}

/** The query string of a layout's parameters, in a fixed order (the same layout for /layout and /clusters). */
export function layoutQuery(params: LayoutParams & { interests?: string }): string {
  // The tourist's interests (api/interests.ts), when set, choose another layout.
  const interests = params.interests ? `&interests=${segment(params.interests)}` : '';
  return `lengths=${segment(params.lengths)}&solver=${segment(params.solver)}${interests}`;
}

export type SchematicRoadClass = 'major' | 'medium' | 'minor';

/** GET /cities/{id}/layout/roads: the road map warped into the layout (api/openapi.yaml). */
export interface LayoutRoadsResponse {
  city: string;
  version: number;
  road_network: { id: string; name: string; version: number };
  frame: 'layout';
  /** Per class, polylines as flat [x, y, x, y, ...] in the layout's frame (the stations' coordinates). */
  roads: Record<SchematicRoadClass, number[][]>;
  stats: {
    roads: number;
    road_edges: number;
    guides: number;
    stations: number;
    max_guide_error: number;
    timing_ms: { total: number; solve: number };
  };
  attribution: string[];
}

/**
 * The streets under the layout drawn for `params`, or null when the city has no road network
 * (404): the view then offers no streets. Other failures throw (ApiError); busy answers are retried.
 */
export async function fetchLayoutRoads(id: string, params: LayoutParams & { interests?: string }, signal?: AbortSignal): Promise<LayoutRoadsResponse | null> {
  try {
    return await getJson<LayoutRoadsResponse>(`/cities/${segment(id)}/layout/roads?${layoutQuery(params)}`, signal);
  } catch (error) {
    if (error instanceof ApiError && error.status === 404) return null;
    throw error;
  }
}

export interface LayoutAnswer {
  layout: LayoutResponse;
  /** X-Result-Cache: the server had the layout already (hit) or computed it (miss). */
  cache: string;
  /** Browser: from sending the request to having the answer parsed. */
  fetchMs: number;
}

/** GET /cities/{id}/layout: the octilinear, transit-centric map; the first request per parameters can take seconds. */
export async function fetchLayout(id: string, params: LayoutParams, signal?: AbortSignal): Promise<LayoutAnswer> {
  const started = performance.now();
  const { body, headers } = await requestWithHeaders<LayoutResponse>(`/cities/${segment(id)}/layout?${layoutQuery(params)}`, {
    signal,
    cache: 'no-cache',
  });
  return { layout: body, cache: headers.get('X-Result-Cache') ?? 'unknown', fetchMs: performance.now() - started };
}

const coordinate = (value: number) => String(Math.round(value * 1e6) / 1e6);

/** GET /cities/{id}/visual-worth: a width x height raster over a lon/lat bbox. */
export function fetchVisualWorth(id: string, bbox: BBox, width: number, height: number, signal?: AbortSignal, interests = ''): Promise<VisualWorthRaster> {
  const weights = interests ? `&interests=${segment(interests)}` : '';
  return getJson<VisualWorthRaster>(
    `/cities/${segment(id)}/visual-worth?bbox=${bbox.map(coordinate).join(',')}&width=${width}&height=${height}${weights}`,
    signal,
  );
}

export interface ClusterQuery {
  space: ClusterSpace;
  /** geo: min_lon,min_lat,max_lon,max_lat; layout: x0,y0,x1,y1 in the layout frame */
  bbox: [number, number, number, number];
  m: number;
  /** space=layout: the parameters of the layout drawn (with its interests). */
  layout?: LayoutParams & { interests?: string };
  /** space=geo: the tourist's interests (the `interests` parameter), if any. */
  interests?: string;
}

/** The path (under /api/v1) of a /clusters request. */
export function clustersPath(id: string, query: ClusterQuery): string {
  const bbox = query.space === 'geo' ? query.bbox.map(coordinate) : query.bbox.map((value) => value.toFixed(1));
  const layout = query.space === 'layout' && query.layout ? `&${layoutQuery(query.layout)}` : '';
  const interests = query.space === 'geo' && query.interests ? `&interests=${segment(query.interests)}` : '';
  return `/cities/${segment(id)}/clusters?space=${query.space}&bbox=${bbox.join(',')}&m=${query.m}${layout}${interests}`;
}

/** GET /cities/{id}/clusters: the active POI clusters of a window. */
export function fetchClusters(id: string, query: ClusterQuery, signal?: AbortSignal): Promise<ClustersResponse> {
  return getJson<ClustersResponse>(clustersPath(id, query), signal);
}

/** GET /crowd/scenes: the crowd scenes the server renders, its modes, limits and the models' credits. */
export function fetchCrowdScenes(signal?: AbortSignal): Promise<CrowdScenesResponse> {
  return getJson<CrowdScenesResponse>('/crowd/scenes', signal);
}
