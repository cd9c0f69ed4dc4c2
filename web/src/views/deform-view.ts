import { ApiError, fetchRoadContext, fetchRoadNetworks, fetchRoadTopology, isAbort, postDeform } from '../api/client';
import type { DeformBody, DeformGrid, DeformKind, DeformResponse, DeformStats, LastImport, RoadNetworkSummary } from '../api/types';
import { DestinationTool } from '../deform/destination-tool';
import { Displacement } from '../deform/displacement';
import { FocusTool } from '../deform/focus-tool';
import { LatestWins, type Exchange } from '../deform/latest-wins';
import { MentalTool } from '../deform/mental-tool';
import { OptionsPanel } from '../deform/options-panel';
import { StatsBox } from '../deform/stats-box';
import type { DeformTool, ScreenPoint, ToolContext } from '../deform/tool';
import { mapControls } from '../map/controls';
import { frameFor, type Frame } from '../map/projection';
import { SvgMap } from '../map/svg-map';
import { ContextLayer } from '../roads/context-layer';
import { PointIndex } from '../roads/point-index';
import { RoadCanvas } from '../roads/road-canvas';
import { RoadGraph } from '../roads/road-graph';
import { attributionBox, showAttribution } from '../ui/attribution';
import { h } from '../ui/dom';
import { ControlSheet } from '../ui/sheet';
import { StatusOverlay } from '../ui/status';
import { WantedPicker } from '../ui/wanted-picker';
import type { View } from './view';

const MODES: { kind: DeformKind; label: string }[] = [
  { kind: 'focus', label: 'Enlarge' },
  { kind: 'mental', label: 'Reshape' },
  { kind: 'destination', label: 'Destination' },
];

/** Metres the context layers are simplified to (a tenth of a pixel at the closest zoom of a town). */
const CONTEXT_SIMPLIFY_M = 2;

/** The network on screen and what is derived from it once. */
interface Network {
  summary: RoadNetworkSummary;
  graph: RoadGraph;
  /** The undeformed positions' fingerprint (positionsHash), once asked for. */
  hash?: string;
  frame: Frame;
  /** Undeformed nodes in frame coordinates, and their index. */
  original: Float64Array;
  index: PointIndex;
  context: ToolContext;
}

/** A deformed map as drawn: kept per mode, so switching modes shows each one's map at once. */
interface Shown {
  positions: Float64Array;
  grid: DeformGrid | null;
  stats: DeformStats;
  roundTripMs: number;
  /** The positions as the server sent them, and their hash once asked for (hashOf). */
  lonLat: ArrayLike<number>;
  hash?: string;
}

/** The fingerprint of a drawn map, computed once per map (2-3 ms for 54,000 nodes). */
function hashOf(shown: Shown): string {
  shown.hash ??= positionsHash(shown.lonLat);
  return shown.hash;
}

type Wanted = { kind: DeformKind; body: DeformBody };

/** FNV-1a over the positions at 1e-7 degrees: a short fingerprint of a drawn map for tests. */
function positionsHash(positions: ArrayLike<number>): string {
  let hash = 0x811c9dc5;
  for (let i = 0; i < positions.length; i++) {
    const value = Math.round(positions[i]! * 1e7);
    hash = Math.imul(hash ^ (value & 0xffff), 0x01000193);
    hash = Math.imul(hash ^ ((value / 65536) | 0), 0x01000193);
  }
  return (hash >>> 0).toString(16).padStart(8, '0');
}

function median(values: number[]): number {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted.length === 0 ? NaN : sorted[Math.floor(sorted.length / 2)]!;
}

/**
 * The Deform view: a road network on a canvas, deformed by the server as you edit focus regions,
 * mental-map guides or a destination sketch. Requests run latest-wins (one in flight; when it
 * is answered the newest state is sent), so the map follows a drag as fast as the server answers.
 *
 * Tests read the canvas's data attributes: data-status, data-network, data-requests (answers
 * drawn), data-errors, data-positions-hash (of the positions drawn) and data-busy.
 */
export class DeformView implements View {
  readonly element: HTMLElement;
  private readonly picker: WantedPicker<RoadNetworkSummary>;
  private readonly map = new SvgMap('Road network', { doubleClickZoom: false });
  private readonly canvas = new RoadCanvas();
  private readonly overlay: SVGGElement;
  private readonly status = new StatusOverlay();
  private readonly attribution = attributionBox();
  private readonly stats = new StatsBox();
  private readonly options: OptionsPanel;
  private readonly errorBox: HTMLElement;
  private readonly modeButtons = new Map<DeformKind, HTMLButtonElement>();
  private readonly toolSlot: HTMLElement;
  private readonly tools: Record<DeformKind, DeformTool> = {
    focus: new FocusTool(),
    mental: new MentalTool(),
    destination: new DestinationTool(),
  };
  private tool: DeformTool = this.tools.focus;
  private readonly loop: LatestWins<Wanted, DeformResponse>;
  private drawn?: string;
  private load?: AbortController;
  private network?: Network;
  /** The deformed map drawn last (undefined or null: the undeformed one). */
  private drawnShown?: Shown | null;
  private displacement?: Displacement;
  private context?: ContextLayer;
  private readonly shown = new Map<DeformKind, Shown>();
  private requests = 0;
  private errors = 0;
  /** The pointer whose gesture a tool took (no pan while it lasts), and whether the next click is its. */
  private gesture: number | null = null;
  private swallowClick = false;
  private meter?: { started: number; frames: number[]; updates: number[]; roundTrips: number[]; timer: number };

  constructor(private readonly go: (networkId: string, replace: boolean) => void) {
    this.picker = new WantedPicker<RoadNetworkSummary>({
      id: 'road-picker',
      label: (network) => `${network.name} — ${network.counts.edges.toLocaleString()} road segments`,
      go: (id, replace) => this.go(id, replace),
      open: (network) => {
        if (this.drawn !== network.id) void this.loadNetwork(network);
      },
      missing: (id) => {
        this.load?.abort();
        this.drawn = undefined;
        this.closeNetwork();
        this.setCanvasStatus('error');
        this.status.error(`There is no road network “${id}”`, new Error('Pick one of the networks in the list.'));
      },
      empty: () => this.status.error('No road networks yet', new Error('Import one with `tourmap import roads` and it will appear here.')),
    });
    this.map.element.dataset.testid = 'road-map';
    this.map.element.prepend(this.canvas.element);
    this.canvas.element.dataset.testid = 'road-canvas';
    this.overlay = this.map.addLayer('deform', 'screen');
    this.map.onRender(() => this.render());
    this.options = new OptionsPanel(() => this.optionsChanged());
    this.errorBox = h('div', { class: 'deform-error', role: 'alert', hidden: true, 'data-testid': 'deform-error' });

    this.loop = new LatestWins<Wanted, DeformResponse>((wanted, signal) => postDeform(wanted.kind, wanted.body, signal), {
      onResult: (exchange) => this.applyResult(exchange),
      onError: (error) => this.showError(error),
      onBusy: (busy) => {
        this.stats.setBusy(busy);
        if (!busy && this.network)
          this.canvas.element.dataset.positionsHash = this.drawnShown ? hashOf(this.drawnShown) : this.originalHash(this.network);
        this.canvas.element.dataset.busy = String(busy);
      },
    });

    const modeSwitch = h('div', { class: 'mode-switch', role: 'group', 'aria-label': 'What to do with the map' });
    for (const { kind, label } of MODES) {
      const button = h('button', { type: 'button', class: 'mode-button', 'data-mode': kind, 'data-testid': `mode-${kind}` }, label);
      button.addEventListener('click', () => this.setMode(kind));
      this.modeButtons.set(kind, button);
      modeSwitch.append(button);
    }
    this.toolSlot = h('div', { class: 'tool-slot' });

    // The switches: a side panel on desktop, a bottom sheet on phones (see ControlSheet).
    const sheet = new ControlSheet(
      'deform',
      'Map options',
      {
        title: 'Stretch the streets that matter',
        text: 'This map of a town can be bent: the streets around the places you care about grow larger while the rest of the map makes room, so the whole town still fits on the screen.',
        tryThis: 'tap a spot on the map: the streets around it are drawn bigger. Drag its centre to move it.',
      },
      'deform-side',
      [
        h('div', { class: 'field-row' }, h('label', { class: 'field', for: 'road-picker' }, 'Town'), this.picker.element),
        modeSwitch,
        this.toolSlot,
        this.options.element,
      ],
    );
    this.map.element.setAttribute('role', 'region');
    this.map.element.setAttribute('aria-label', 'Street map: tap to enlarge a place, drag to pan, pinch or use + and − to zoom');
    this.element = h(
      'section',
      { class: 'view view-deform has-sheet' },
      sheet.element,
      h(
        'div',
        { class: 'map-area' },
        this.map.element,
        mapControls(this.map),
        this.stats.element,
        this.errorBox,
        this.attribution,
        this.status.element,
      ),
    );
    this.map.setFitInsets(() => ({ top: 0, right: 0, bottom: this.attribution.offsetHeight, left: 0 }));
    // A resize that keeps the user's view only "settles": the canvas still needs its new size.
    this.map.onSettle(() => this.map.requestRender());
    this.canvas.element.dataset.busy = 'false';
    this.listen();
    this.setMode('focus');
    this.setCanvasStatus('loading');
    void this.loadNetworks();
  }

  show(networkId: string | undefined): void {
    document.title = 'Deform · tourmap';
    this.picker.want(networkId);
  }

  catalogChanged(lastImport: LastImport | undefined): void {
    if (lastImport && lastImport.kind !== 'roads') return;
    if (!lastImport || lastImport.target === this.drawn) this.drawn = undefined;
    void this.loadNetworks();
  }

  private async loadNetworks(): Promise<void> {
    const loaded = this.picker.items !== undefined;
    if (!loaded) this.status.loading('Loading road networks…');
    let networks: RoadNetworkSummary[];
    try {
      networks = await fetchRoadNetworks();
    } catch (error) {
      if (!loaded) this.status.error('Could not load the road networks', error, () => void this.loadNetworks());
      return;
    }
    this.picker.setItems(networks);
  }

  private async loadNetwork(summary: RoadNetworkSummary): Promise<void> {
    this.load?.abort();
    const load = new AbortController();
    this.load = load;
    this.drawn = summary.id;
    this.closeNetwork();
    this.setCanvasStatus('loading');
    this.status.loading(`Loading ${summary.name}…`);
    try {
      const topology = await fetchRoadTopology(summary.id, load.signal);
      if (load.signal.aborted) return;
      const graph = new RoadGraph(topology);
      const frame = frameFor(summary.bbox);
      const original = frame.projectAll(graph.lonLat);
      const index = new PointIndex(original);
      const context: ToolContext = {
        map: this.map,
        frame,
        graph,
        original,
        displacement: () => this.displacement!,
        changed: () => this.stateChanged(),
        redraw: () => this.map.requestRender(),
        notify: (message) => this.showNotice(message),
        dragging: (active) => this.dragging(active),
      };
      this.network = { summary, graph, frame, original, index, context };
      this.displacement = new Displacement(original, index, original, graph.edges);
      this.canvas.setNetwork(graph, original);
      void this.loadContext(summary, frame, original, index, load.signal);
      for (const tool of Object.values(this.tools)) tool.reset(context);
      this.map.setFrame(frame);
      showAttribution(this.attribution, [...summary.attribution, ...topology.attribution]);
      this.status.clear();
      this.canvas.element.dataset.network = summary.id;
      this.drawnShown = null;
      this.canvas.element.dataset.positionsHash = positionsHash(graph.lonLat);
      this.setCanvasStatus('ready');
      this.stateChanged();
    } catch (error) {
      if (isAbort(error)) return;
      this.drawn = undefined;
      this.closeNetwork();
      this.setCanvasStatus('error');
      this.status.error(`Could not load ${summary.name}`, error, () => void this.loadNetwork(summary));
    }
  }

  /**
   * The network's sea, water, land use, rivers, railways and place names, drawn under the roads
   * and warped with them. Optional: the roads are usable before (or without) it.
   */
  private async loadContext(summary: RoadNetworkSummary, frame: Frame, original: Float64Array, index: PointIndex, signal: AbortSignal): Promise<void> {
    try {
      const context = await fetchRoadContext(summary.id, CONTEXT_SIMPLIFY_M, signal);
      if (signal.aborted || this.network?.original !== original) return;
      this.context = new ContextLayer(context, frame, original, index);
      this.context.warp(original, this.displacement?.deformed ?? original);
      this.canvas.setContext(this.context);
      this.canvas.element.dataset.contextVertices = String(this.context.vertexCount);
      this.map.requestRender();
    } catch (error) {
      if (isAbort(error)) return;
      this.canvas.element.dataset.contextError = String(error);
    }
  }

  /** Forgets the network on screen: requests, tool state, drawings. */
  private closeNetwork(): void {
    this.loop.reset();
    this.gesture = null;
    this.dragging(false);
    this.network = undefined;
    this.displacement = undefined;
    this.context = undefined;
    delete this.canvas.element.dataset.contextVertices;
    this.shown.clear();
    this.canvas.clear();
    for (const tool of Object.values(this.tools)) tool.reset(null);
    this.stats.clear();
    this.hideError();
    showAttribution(this.attribution, []);
    delete this.canvas.element.dataset.network;
    this.map.requestRender();
  }

  private setCanvasStatus(status: 'loading' | 'ready' | 'error'): void {
    this.map.element.dataset.status = status;
    this.canvas.element.dataset.status = status;
    this.canvas.element.dataset.requests = String(this.requests);
    this.canvas.element.dataset.errors = String(this.errors);
  }

  private setMode(kind: DeformKind): void {
    this.loop.reset();
    this.gesture = null;
    this.dragging(false);
    this.tool = this.tools[kind];
    for (const [mode, button] of this.modeButtons) button.setAttribute('aria-pressed', String(mode === kind));
    this.toolSlot.replaceChildren(this.tool.panel);
    this.element.dataset.mode = kind;
    this.hideError();
    if (!this.network) return;
    // Never show another mode's map for this one: its own last map, or the undeformed network.
    this.draw(this.shown.get(kind) ?? null);
    this.stateChanged();
  }

  private optionsChanged(): void {
    const { showGrid, showOriginal } = this.options.value;
    this.canvas.showOriginal = showOriginal;
    if (!showGrid) this.canvas.setGrid(null, this.network?.frame ?? frameFor([0, 0, 1, 1]));
    this.canvas.showGrid = showGrid;
    // Options are part of every request: a new grid or solver means a new answer.
    this.stateChanged();
  }

  /** The current tool's request with the shared options; null when there is nothing to deform. */
  private wantedRequest(): Wanted | null {
    const network = this.network;
    const request = network ? this.tool.request() : null;
    if (!network || !request) return null;
    const options = this.options.value;
    const body: DeformBody = {
      roads: network.summary.id,
      grid: options.grid,
      solver: options.solver,
      relax: options.relax,
      output: { roads: 'positions', grid: options.showGrid },
      ...request,
    };
    return { kind: this.tool.kind, body };
  }

  /** The tool's state or the options changed: show what we have for it and ask for the rest. */
  private stateChanged(): void {
    const network = this.network;
    if (!network) return;
    const wanted = this.wantedRequest();
    if (!wanted) {
      this.loop.want(null);
      this.shown.delete(this.tool.kind);
      this.draw(null);
    } else {
      const shown = this.shown.get(this.tool.kind);
      if (shown && shown.positions !== this.displacement?.deformed) this.draw(shown);
      this.loop.want(wanted);
    }
    this.canvas.setRoute(this.tool.highlighted());
    this.map.requestRender();
  }

  /** Draws a deformed map, or with null the undeformed network. */
  private draw(shown: Shown | null): void {
    const network = this.network!;
    const positions = shown?.positions ?? network.original;
    this.displacement = new Displacement(network.original, network.index, positions, network.graph.edges);
    this.context?.warp(network.original, positions);
    this.canvas.setPositions(positions);
    this.canvas.setGrid(shown && this.options.value.showGrid ? shown.grid : null, network.frame);
    // The fingerprint is for tests, which read it when the answers stop: not computed for
    // each answer of a drag (the next request is already out then), but at the last.
    this.drawnShown = shown;
    if (!this.loop.busy) this.canvas.element.dataset.positionsHash = shown ? hashOf(shown) : this.originalHash(network);
    if (shown) this.stats.show(shown.stats, shown.roundTripMs);
    else this.stats.clear(this.emptyText());
  }

  private originalHash(network: Network): string {
    network.hash ??= positionsHash(network.graph.lonLat);
    return network.hash;
  }

  private emptyText(): string {
    switch (this.tool.kind) {
      case 'focus':
        return 'Click the map to add a focus region.';
      case 'mental':
        return 'Drag a road vertex to add a guide.';
      case 'destination':
        return 'Pick a route and sketch it.';
    }
  }

  private applyResult({ body, result, roundTripMs }: Exchange<Wanted, DeformResponse>): void {
    const network = this.network;
    if (!network || body.kind !== this.tool.kind || body.body.roads !== network.summary.id) return;
    const started = performance.now();
    const lonLat = result.positions;
    if (!lonLat || lonLat.length !== 2 * network.graph.nodeCount) {
      this.showError(new Error('The server answered with positions for another version of this network. Reload the page to get the current one.'));
      return;
    }
    const positions = network.frame.projectAll(lonLat);
    const shown: Shown = { positions, grid: result.grid, stats: result.stats, roundTripMs, lonLat };
    this.shown.set(body.kind, shown);
    this.draw(shown);
    this.tool.applied(result, body.body);
    this.requests++;
    this.canvas.element.dataset.requests = String(this.requests);
    this.canvas.element.dataset.applyMs = (performance.now() - started).toFixed(1);
    this.hideError();
    if (this.meter) {
      this.meter.updates.push(performance.now());
      this.meter.roundTrips.push(roundTripMs);
    }
    this.map.requestRender();
  }

  private showError(error: unknown): void {
    this.errors++;
    this.canvas.element.dataset.errors = String(this.errors);
    const field = error instanceof ApiError ? error.field : undefined;
    const title = error instanceof ApiError && error.status > 0 ? 'The server could not deform the map' : 'The map could not be deformed';
    this.fillErrorBox('error', title, error instanceof Error ? error.message : String(error), field);
  }

  /** A problem found here (no route, too many regions), or null to hide it. */
  private showNotice(message: string | null): void {
    if (message === null) {
      if (this.errorBox.dataset.kind === 'notice') this.hideError();
      return;
    }
    this.fillErrorBox('notice', message);
  }

  private fillErrorBox(kind: 'error' | 'notice', title: string, message?: string, field?: string): void {
    const close = h('button', { type: 'button', class: 'deform-error-close', 'aria-label': 'Dismiss' }, '×');
    close.addEventListener('click', () => this.hideError());
    this.errorBox.replaceChildren(h('strong', {}, title), close);
    if (message) this.errorBox.append(h('p', {}, message));
    if (field) this.errorBox.append(h('p', { class: 'deform-error-field' }, 'Field: ', h('code', {}, field)));
    this.errorBox.dataset.kind = kind;
    if (field) this.errorBox.dataset.field = field;
    else delete this.errorBox.dataset.field;
    this.errorBox.hidden = false;
  }

  private hideError(): void {
    this.errorBox.hidden = true;
    this.errorBox.replaceChildren();
    delete this.errorBox.dataset.kind;
  }

  private render(): void {
    this.canvas.draw(this.map.view);
    this.canvas.element.dataset.drawMs = this.canvas.lastDrawMs.toFixed(1);
    this.canvas.element.dataset.draws = String(this.canvas.draws);
    this.canvas.element.dataset.placesDrawn = String(this.canvas.placesDrawn);
    this.overlay.replaceChildren();
    if (this.network) this.tool.render(this.overlay);
    this.meter?.frames.push(performance.now());
  }

  /** Frame-rate meter: frames drawn and deformed maps received per second while a drag lasts. */
  private dragging(active: boolean): void {
    if (active && !this.meter) {
      const meter = { started: performance.now(), frames: [] as number[], updates: [] as number[], roundTrips: [] as number[], timer: 0 };
      meter.timer = window.setInterval(() => {
        const since = performance.now() - 1000;
        const fps = meter.frames.filter((t) => t > since).length;
        const updates = meter.updates.filter((t) => t > since).length;
        this.stats.showDrag(`Dragging: ${fps} fps · ${updates} map updates/s · round trip ${Math.round(median(meter.roundTrips.slice(-10))) || '—'} ms`);
      }, 250);
      this.meter = meter;
    } else if (!active && this.meter) {
      const meter = this.meter;
      this.meter = undefined;
      window.clearInterval(meter.timer);
      const seconds = Math.max((performance.now() - meter.started) / 1000, 1e-3);
      const fps = meter.frames.length / seconds;
      const updates = meter.updates.length / seconds;
      const rtt = median(meter.roundTrips);
      const element = this.stats.element;
      element.dataset.dragFps = fps.toFixed(1);
      element.dataset.dragUpdates = String(meter.updates.length);
      element.dataset.dragUpdatesPerSecond = updates.toFixed(1);
      element.dataset.dragRttMedian = Number.isFinite(rtt) ? rtt.toFixed(1) : '';
      this.stats.showDrag(
        meter.updates.length === 0
          ? ''
          : `Last drag: ${fps.toFixed(0)} fps, ${updates.toFixed(1)} map updates/s, median round trip ${Math.round(rtt)} ms (${meter.updates.length} answers in ${seconds.toFixed(1)} s)`,
      );
    }
  }

  /** Pointer events go to the tool first; what it does not take pans and zooms the map. */
  private listen(): void {
    const svg = this.map.svg;
    const point = (event: MouseEvent): ScreenPoint => {
      const box = svg.getBoundingClientRect();
      return [event.clientX - box.left, event.clientY - box.top];
    };
    this.map.setGestureFilter((event) => event.type === 'wheel' || this.gesture === null);
    svg.addEventListener('pointerdown', (event) => {
      this.swallowClick = false;
      if (!this.network || event.button !== 0 || this.gesture !== null) return;
      if (this.tool.pointerDown(point(event), event)) {
        this.gesture = event.pointerId;
        this.swallowClick = true;
        svg.setPointerCapture(event.pointerId);
        // No mouse events follow (so no pan), and no focus from them: focus the map for its
        // keys (Delete, Escape) without the keyboard focus ring.
        event.preventDefault();
        svg.focus({ preventScroll: true, focusVisible: false } as FocusOptions);
      }
    });
    svg.addEventListener('pointermove', (event) => {
      if (!this.network) return;
      if (event.pointerId === this.gesture) this.tool.pointerMove(point(event), event);
      else if (event.buttons === 0 && event.pointerType === 'mouse') svg.style.cursor = this.tool.hover(point(event));
    });
    const end = (event: PointerEvent) => {
      if (event.pointerId !== this.gesture) return;
      this.gesture = null;
      this.tool.pointerUp(point(event), event);
      this.map.requestRender();
    };
    svg.addEventListener('pointerup', end);
    svg.addEventListener('pointercancel', end);
    svg.addEventListener('pointerleave', () => {
      if (this.gesture === null && this.network) this.tool.hover(null);
    });
    svg.addEventListener('click', (event) => {
      if (this.swallowClick || !this.network) return;
      this.tool.click(point(event));
      svg.style.cursor = this.tool.hover(point(event));
    });
    svg.addEventListener('keydown', (event) => {
      if (this.network && this.tool.key(event)) event.preventDefault();
    });
  }
}
