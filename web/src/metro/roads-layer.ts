import type { LayoutRoadsResponse, SchematicRoadClass } from '../api/client';
import { polylinePath, svg } from '../map/svg';
import type { SvgMap } from '../map/svg-map';
import type { Placement } from './layout-geometry';

/** Road classes of GET /cities/{id}/layout/roads, from the most to the least important. */
export const SCHEMATIC_ROAD_CLASSES = ['major', 'medium', 'minor'] as const satisfies readonly SchematicRoadClass[];
export type { LayoutRoadsResponse, SchematicRoadClass };

/**
 * Screen pixels per layout metre from which each class is drawn: the streets are context for a
 * close look, not part of the overview (at a whole-city zoom they would be a grey felt).
 */
const SHOWN_FROM_PX_PER_M: Record<SchematicRoadClass, number> = { major: 0.04, medium: 0.07, minor: 0.14 };

/** Faint grey strokes (px; the world layers keep strokes this wide at every zoom), under the lines' colours. */
const STROKE: Record<SchematicRoadClass, { width: number; opacity: number }> = {
  major: { width: 2.4, opacity: 0.6 },
  medium: { width: 1.7, opacity: 0.55 },
  minor: { width: 1, opacity: 0.5 },
};
const ROAD_COLOUR = '#8d99a6';

/**
 * The streets in the schematic's space, drawn faintly in a world layer under the lines: one
 * path per road class, placed on the map like the layout (Placement). Hidden while the map is
 * geographic or morphing (the roads belong to one layout), and per class until the zoom is
 * close enough.
 */
export class RoadsLayer {
  private readonly paths = new Map<SchematicRoadClass, SVGPathElement>();
  private placement: Placement | null = null;
  private shown: LayoutRoadsResponse | null = null;
  private visible = false;
  private wasDrawn = false;
  private readonly stopRender: () => void;

  /** `onDrawn`: the roads came on screen or left it (the view credits their data meanwhile). */
  constructor(
    private readonly map: SvgMap,
    private readonly layer: SVGGElement,
    private readonly onDrawn: (drawn: boolean) => void,
  ) {
    // The least important class at the bottom.
    for (const roadClass of [...SCHEMATIC_ROAD_CLASSES].reverse()) {
      const { width, opacity } = STROKE[roadClass];
      const path = svg('path', {
        class: `schematic-road schematic-road-${roadClass}`,
        stroke: ROAD_COLOUR,
        'stroke-width': width,
        'stroke-opacity': opacity,
      });
      this.paths.set(roadClass, path);
      layer.append(path);
    }
    this.layer.dataset.testid = 'schematic-roads';
    this.layer.style.display = 'none';
    this.stopRender = map.onRender(() => this.applyZoom());
  }

  /** The roads drawn: what `answer` holds, placed like the layout. */
  get roads(): LayoutRoadsResponse | null {
    return this.shown;
  }

  show(answer: LayoutRoadsResponse, placement: Placement): void {
    if (this.shown === answer && this.placement === placement) return;
    this.shown = answer;
    this.placement = placement;
    for (const roadClass of SCHEMATIC_ROAD_CLASSES) {
      const lines = answer.roads[roadClass] ?? [];
      const d = lines
        .map((flat) => {
          const points: [number, number][] = [];
          for (let i = 0; i + 1 < flat.length; i += 2) points.push(placement.toFrame([flat[i]!, flat[i + 1]!]));
          return polylinePath(points);
        })
        .join('');
      this.paths.get(roadClass)!.setAttribute('d', d);
    }
    this.layer.dataset.roads = String(answer.stats.roads);
    this.applyZoom();
  }

  setVisible(visible: boolean): void {
    this.visible = visible;
    this.layer.style.display = visible && this.shown ? '' : 'none';
    this.applyZoom();
  }

  /** Forgets the roads drawn (another city, or a layout without them). */
  clear(): void {
    this.shown = null;
    this.placement = null;
    for (const path of this.paths.values()) path.removeAttribute('d');
    delete this.layer.dataset.roads;
    this.setVisible(false);
  }

  /** Whether any class is on screen now (the view credits the road data then). */
  get drawn(): boolean {
    return this.visible && this.shown !== null && [...this.paths.values()].some((path) => path.style.display !== 'none');
  }

  destroy(): void {
    this.stopRender();
    this.layer.remove();
  }

  private applyZoom(): void {
    if (this.placement) {
      const pxPerMetre = this.map.scale * this.placement.scale;
      for (const roadClass of SCHEMATIC_ROAD_CLASSES) {
        const display = pxPerMetre >= SHOWN_FROM_PX_PER_M[roadClass] ? '' : 'none';
        const path = this.paths.get(roadClass)!;
        if (path.style.display !== display) path.style.display = display;
      }
      this.layer.dataset.zoomPxPerM = pxPerMetre.toFixed(3);
    }
    const drawn = this.drawn;
    this.layer.dataset.drawn = String(drawn);
    if (drawn !== this.wasDrawn) {
      this.wasDrawn = drawn;
      this.onDrawn(drawn);
    }
  }
}
