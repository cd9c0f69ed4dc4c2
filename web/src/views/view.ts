import type { LastImport, LayoutImprovedEvent } from '../api/types';

/** One of the app's pages (Metro, Deform, Crowd); kept while hidden, so coming back keeps its state. */
export interface View {
  readonly element: HTMLElement;
  /** Shows the route's city or road network; called on mount and when only the parameter changes. */
  show(param: string | undefined): void;
  /** Data was imported on the server (undefined: something changed while we were offline). */
  catalogChanged(lastImport: LastImport | undefined): void;
  /** A metro layout was improved on the server (views that show none ignore it). */
  layoutImproved?(event: LayoutImprovedEvent): void;
  /** Another view is shown instead: stop what only matters on screen (a stream, say). */
  hide?(): void;
}
