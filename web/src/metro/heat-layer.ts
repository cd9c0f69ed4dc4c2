import type { LayoutResponse, VisualWorthRaster, XY } from '../api/types';
import type { Frame } from '../map/projection';
import { svg } from '../map/svg';
import type { Placement } from './layout-geometry';

/**
 * Colour stops of the heat map: value (after a square root, to show the shoulders of peaks) ->
 * RGBA. A yellow-orange-brown ramp (ColorBrewer YlOrBr) that stays visible over the light map
 * from low values on, and darkens without turning to any line's red at the peaks.
 */
const RAMP: [number, [number, number, number, number]][] = [
  [0, [255, 247, 188, 0]],
  [0.15, [254, 227, 145, 0.4]],
  [0.4, [254, 196, 79, 0.55]],
  [0.65, [236, 112, 20, 0.62]],
  [1, [140, 45, 4, 0.72]],
];

/** CSS gradient of the ramp, for the legend. */
export const HEAT_GRADIENT = `linear-gradient(90deg, ${RAMP.map(([stop, [r, g, b, a]]) => `rgb(${r} ${g} ${b} / ${Math.max(a, 0.08)}) ${stop * 100}%`).join(', ')})`;

function colour(value: number): [number, number, number, number] {
  const t = Math.sqrt(Math.max(0, Math.min(1, value)));
  for (let i = 1; i < RAMP.length; i++) {
    const [s1, c1] = RAMP[i]!;
    if (t <= s1 || i === RAMP.length - 1) {
      const [s0, c0] = RAMP[i - 1]!;
      const u = s1 > s0 ? Math.min(1, (t - s0) / (s1 - s0)) : 1;
      return [0, 1, 2, 3].map((k) => c0[k]! + (c1[k]! - c0[k]!) * u) as [number, number, number, number];
    }
  }
  return RAMP[RAMP.length - 1]![1];
}

/** The raster as an image, one pixel per value, north up. */
function rasterCanvas(raster: VisualWorthRaster): HTMLCanvasElement {
  const canvas = document.createElement('canvas');
  canvas.width = raster.width;
  canvas.height = raster.height;
  const context = canvas.getContext('2d')!;
  const image = context.createImageData(raster.width, raster.height);
  raster.values.forEach((value, i) => {
    const [r, g, b, a] = colour(value);
    image.data[4 * i] = r;
    image.data[4 * i + 1] = g;
    image.data[4 * i + 2] = b;
    image.data[4 * i + 3] = Math.round(a * 255);
  });
  context.putImageData(image, 0, 0);
  return canvas;
}

type Triangle = [[number, number], [number, number], [number, number]];

/** Draws the source image's triangle `from` onto the canvas's triangle `to` (affine texture mapping). */
function drawTriangle(context: CanvasRenderingContext2D, image: HTMLCanvasElement, from: Triangle, to: Triangle): void {
  const [[u0, v0], [u1, v1], [u2, v2]] = from;
  const [[x0, y0], [x1, y1], [x2, y2]] = to;
  const det = (u1 - u0) * (v2 - v0) - (u2 - u0) * (v1 - v0);
  if (Math.abs(det) < 1e-9) return;
  // x = a u + c v + e, y = b u + d v + f through the three corners.
  const a = ((x1 - x0) * (v2 - v0) - (x2 - x0) * (v1 - v0)) / det;
  const c = ((x2 - x0) * (u1 - u0) - (x1 - x0) * (u2 - u0)) / det;
  const b = ((y1 - y0) * (v2 - v0) - (y2 - y0) * (v1 - v0)) / det;
  const d = ((y2 - y0) * (u1 - u0) - (y1 - y0) * (u2 - u0)) / det;
  const e = x0 - a * u0 - c * v0;
  const f = y0 - b * u0 - d * v0;
  // Grown by half a pixel around the centroid, so neighbouring triangles leave no seam.
  const cx = (x0 + x1 + x2) / 3;
  const cy = (y0 + y1 + y2) / 3;
  const grow = ([x, y]: [number, number]): [number, number] => {
    const length = Math.hypot(x - cx, y - cy) || 1;
    return [x + ((x - cx) / length) * 0.6, y + ((y - cy) / length) * 0.6];
  };
  context.save();
  context.beginPath();
  to.map(grow).forEach(([x, y], i) => (i === 0 ? context.moveTo(x, y) : context.lineTo(x, y)));
  context.closePath();
  context.clip();
  context.setTransform(a, b, c, d, e, f);
  context.drawImage(image, 0, 0);
  context.restore();
}

/** Longest side of the warped heat map's image, in pixels. */
const WARPED_SIDE = 1024;
/** Each mesh cell is cut into SUBDIVIDE x SUBDIVIDE bilinear pieces (two triangles each): softer creases. */
const SUBDIVIDE = 2;

/**
 * The visual worth heat map: one semi-transparent image in a world layer under the network.
 * Geographic: the raster of the window shown, placed on its bbox. Octilinear: a raster of the
 * whole warp mesh, carried cell by cell (two triangles each) from the mesh's geographic nodes to
 * its warped ones: the heat map of the layout, as coarse as that mesh (21 x 21 nodes).
 */
export class HeatLayer {
  private readonly image: SVGImageElement;

  constructor(private readonly layer: SVGGElement) {
    this.image = svg('image', { class: 'heat-image', preserveAspectRatio: 'none' });
    this.layer.append(this.image);
    this.clear();
  }

  clear(): void {
    this.image.removeAttribute('href');
    this.image.style.display = 'none';
    delete this.layer.dataset.kind;
  }

  /** A raster over a lon/lat bbox, on a geographic map. */
  showRaster(raster: VisualWorthRaster, frame: Frame): void {
    const [west, south, east, north] = raster.bbox;
    const [x0, y0] = frame.project([west, north]);
    const [x1, y1] = frame.project([east, south]);
    this.put(rasterCanvas(raster).toDataURL(), x0, y0, x1 - x0, y1 - y0, 'geographic');
  }

  /** A raster of the mesh's geographic extent, warped into the layout through the mesh. */
  showWarped(raster: VisualWorthRaster, layout: LayoutResponse, placement: Placement, frame: Frame): void {
    const { cols, rows, geo, layout: warped } = layout.mesh;
    if (geo.length !== cols * rows || warped.length !== cols * rows) return;
    const [west, south, east, north] = raster.bbox;
    const source = rasterCanvas(raster);
    const sourcePixel = (p: XY): [number, number] => {
      const [lon, lat] = frame.unproject(...placement.toFrame(p));
      return [((lon - west) / (east - west)) * raster.width, ((north - lat) / (north - south)) * raster.height];
    };
    const targets = warped.map((p) => placement.toFrame(p));
    const xs = targets.map(([x]) => x);
    const ys = targets.map(([, y]) => y);
    const [bx0, by0, bx1, by1] = [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)];
    const pixelsPerUnit = WARPED_SIDE / Math.max(bx1 - bx0, by1 - by0, 1e-9);
    const canvas = document.createElement('canvas');
    canvas.width = Math.max(1, Math.ceil((bx1 - bx0) * pixelsPerUnit));
    canvas.height = Math.max(1, Math.ceil((by1 - by0) * pixelsPerUnit));
    const context = canvas.getContext('2d')!;
    context.imageSmoothingEnabled = true;
    const started = performance.now();
    const dst = targets.map(([x, y]): [number, number] => [(x - bx0) * pixelsPerUnit, (y - by0) * pixelsPerUnit]);
    const src = geo.map(sourcePixel);
    const bilinear = (points: [number, number][], k00: number, u: number, v: number): [number, number] => {
      const [p00, p10, p01, p11] = [points[k00]!, points[k00 + 1]!, points[k00 + cols]!, points[k00 + cols + 1]!];
      return [0, 1].map(
        (d) => (1 - u) * (1 - v) * p00[d]! + u * (1 - v) * p10[d]! + (1 - u) * v * p01[d]! + u * v * p11[d]!,
      ) as [number, number];
    };
    for (let j = 0; j + 1 < rows; j++) {
      for (let i = 0; i + 1 < cols; i++) {
        const k00 = j * cols + i;
        for (let b = 0; b < SUBDIVIDE; b++) {
          for (let a = 0; a < SUBDIVIDE; a++) {
            const corners = [
              [a, b],
              [a + 1, b],
              [a + 1, b + 1],
              [a, b + 1],
            ].map(([u, v]) => ({ s: bilinear(src, k00, u! / SUBDIVIDE, v! / SUBDIVIDE), d: bilinear(dst, k00, u! / SUBDIVIDE, v! / SUBDIVIDE) }));
            const [c0, c1, c2, c3] = corners as [(typeof corners)[0], (typeof corners)[0], (typeof corners)[0], (typeof corners)[0]];
            drawTriangle(context, source, [c0.s, c1.s, c2.s], [c0.d, c1.d, c2.d]);
            drawTriangle(context, source, [c0.s, c2.s, c3.s], [c0.d, c2.d, c3.d]);
          }
        }
      }
    }
    this.layer.dataset.warpMs = (performance.now() - started).toFixed(1);
    this.put(canvas.toDataURL(), bx0, by0, bx1 - bx0, by1 - by0, 'warped');
  }

  private put(href: string, x: number, y: number, width: number, height: number, kind: string): void {
    this.image.setAttribute('href', href);
    this.image.setAttribute('x', String(x));
    this.image.setAttribute('y', String(y));
    this.image.setAttribute('width', String(Math.max(width, 1e-6)));
    this.image.setAttribute('height', String(Math.max(height, 1e-6)));
    this.image.style.display = '';
    this.layer.dataset.kind = kind;
  }
}
