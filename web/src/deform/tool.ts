import type { DeformKind, DeformResponse, FocusRegion, Guide, LonLat } from '../api/types';
import type { Frame } from '../map/projection';
import type { SvgMap } from '../map/svg-map';
import type { RoadGraph } from '../roads/road-graph';
import type { Displacement } from './displacement';

export type ScreenPoint = [x: number, y: number];

/** The part of a deformation request a tool adds to the shared options. */
export type ToolRequest =
  | { regions: FocusRegion[]; map_points?: LonLat[] }
  | { guides: Guide[] }
  | { route: number[]; sketch: LonLat[]; simplify_m: number };

/** What a tool may use of the view: the network, the map, the deformation shown now. */
export interface ToolContext {
  readonly map: SvgMap;
  readonly frame: Frame;
  readonly graph: RoadGraph;
  /** Undeformed nodes in frame coordinates. */
  readonly original: Float64Array;
  /** The deformation drawn now (the identity before the first answer). */
  displacement(): Displacement;
  /** The tool's state changed: ask for a new deformation (latest wins) and redraw. */
  changed(): void;
  /** Only the overlay changed. */
  redraw(): void;
  /** Shows (or with null, clears) a problem found in the browser, such as "no road joins these". */
  notify(message: string | null): void;
  /** A drag that deforms the map started or ended (for the frame-rate meter). */
  dragging(active: boolean): void;
}

/**
 * One mode of the Deform view (Focus, Mental map, Destination): its side panel, its state,
 * its pointer handling and its overlay (handles, arrows, sketches) over the map.
 */
export interface DeformTool {
  readonly kind: DeformKind;
  readonly panel: HTMLElement;
  /** The tool's part of the request, or null when there is nothing to deform yet. */
  request(): ToolRequest | null;
  /** An answer to `request` arrived and is drawn. */
  applied(result: DeformResponse, request: ToolRequest): void;
  /** A pointer went down over the map; true takes the gesture (no pan), then move/up follow. */
  pointerDown(point: ScreenPoint, event: PointerEvent): boolean;
  pointerMove(point: ScreenPoint, event: PointerEvent): void;
  pointerUp(point: ScreenPoint, event: PointerEvent): void;
  /** A click (no drag, no pan) that no gesture took. */
  click(point: ScreenPoint): void;
  /** The cursor to show while hovering (no button down). */
  hover(point: ScreenPoint | null): string;
  /** A key pressed on the map; true if handled. */
  key(event: KeyboardEvent): boolean;
  /** Redraws the overlay, in screen coordinates. */
  render(layer: SVGGElement): void;
  /** Road nodes to highlight on the map (a route). */
  highlighted(): number[];
  /** A new network: forget everything. */
  reset(context: ToolContext | null): void;
}
