import type { BBox, LonLat } from '../api/types';

/** Web Mercator's latitude limit: the map is square between these. */
const MAX_LAT = 85.0511287798;

/** Web Mercator (EPSG:3857) in units of the world's width: x east, y south, both in [0, 1]. */
function mercator([lon, lat]: LonLat): [number, number] {
  const phi = (Math.max(-MAX_LAT, Math.min(MAX_LAT, lat)) * Math.PI) / 180;
  const sin = Math.sin(phi);
  return [(lon + 180) / 360, 0.5 - Math.log((1 + sin) / (1 - sin)) / (4 * Math.PI)];
}

function inverseMercator(x: number, y: number): LonLat {
  const lat = (Math.atan(Math.sinh(Math.PI * (1 - 2 * y))) * 180) / Math.PI;
  return [x * 360 - 180, lat];
}

/**
 * A map's own coordinate frame: Web Mercator moved to the bbox's north-west corner and scaled
 * so the bbox's longer side spans `size` units. SVG coordinates then stay small numbers and
 * keep their precision at street level, where world-sized Mercator values would not.
 */
export interface Frame {
  /** Identifies the area: two frames with the same key project identically. */
  readonly key: string;
  readonly width: number;
  readonly height: number;
  project(position: LonLat): [number, number];
  /** Projects [lon, lat, lon, lat, ...] into [x, y, ...]: project's loop without an array per point. */
  projectAll(lonLat: ArrayLike<number>): Float64Array;
  /** The position at a point of the frame: project's inverse. */
  unproject(x: number, y: number): LonLat;
}

export function frameFor(bbox: BBox, size = 1000): Frame {
  const [west, north] = mercator([bbox[0], bbox[3]]);
  const [east, south] = mercator([bbox[2], bbox[1]]);
  // A degenerate bbox (one station) still gets a usable scale.
  const span = Math.max(east - west, south - north, 1e-9);
  const scale = size / span;
  return {
    key: bbox.join(','),
    width: (east - west) * scale,
    height: (south - north) * scale,
    project(position) {
      const [x, y] = mercator(position);
      return [(x - west) * scale, (y - north) * scale];
    },
    projectAll(lonLat) {
      const out = new Float64Array(lonLat.length);
      const limit = Math.sin((MAX_LAT * Math.PI) / 180);
      for (let i = 0; i + 1 < lonLat.length; i += 2) {
        // mercator() inlined: x = (lon + 180) / 360, y = 1/2 - ln((1 + sin) / (1 - sin)) / (4 pi).
        const sin = Math.max(-limit, Math.min(limit, Math.sin((lonLat[i + 1]! * Math.PI) / 180)));
        out[i] = (((lonLat[i]! + 180) / 360) - west) * scale;
        out[i + 1] = (0.5 - Math.log((1 + sin) / (1 - sin)) / (4 * Math.PI) - north) * scale;
      }
      return out;
    },
    unproject(x, y) {
      return inverseMercator(x / scale + west, y / scale + north);
    },
  };
}
