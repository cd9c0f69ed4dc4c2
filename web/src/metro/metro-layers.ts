import type { EdgeFeature, LayoutLabel, LayoutLabels, MetroCollection, MetroLine, PoiFeature, StationFeature } from '../api/types';
import { LABEL_FONT, labelWidth, placeLabels, type Box, type Label } from '../map/labels';
import type { Frame } from '../map/projection';
import { polylinePath, svg } from '../map/svg';
import type { Anchor, SvgMap } from '../map/svg-map';
import { MapTooltip } from '../map/tooltip';
import { bundlePieces, LINE_SPACING_PX } from './bundles';
import { lineCasing, lineColor, lineDash } from './lines';
import type { Geometry, Pt } from './morph';

export type MetroPick = { kind: 'station'; station: StationFeature } | { kind: 'poi'; poi: PoiFeature };

const STATION_RADIUS = 4;
const INTERCHANGE_RADIUS = 5.5;
/** Fingers need bigger targets than a mouse pointer. */
const TOUCH_GROWTH = 1.4;
/**
 * Markers shrink (down to this fraction) while the typical gap between neighbouring stations
 * is under FULL_SIZE_GAP_PX on screen, so a whole dense network stays readable.
 */
const MIN_MARKER_SCALE = 0.5;
const FULL_SIZE_GAP_PX = 30;
const MIN_PIN_SCALE = 0.75;
const HIGHLIGHT_PRIORITY = 1000;
/** A map pin with its tip on the point. */
const POI_PIN_PATH = 'M0 0C-1 -3.5 -6.5 -6.5 -6.5 -11.5A6.5 6.5 0 1 1 6.5 -11.5C6.5 -6.5 1 -3.5 0 0Z';

interface Marked<F> {
  feature: F;
  element: SVGElement;
  anchor: Anchor;
}

/** A station's marker: a group placed at the station, holding its symbol. */
interface StationMarker {
  symbol: SVGRectElement;
}

/** An edge drawn, with the stations it joins (how a layout's edge finds it). */
export interface DrawnEdge {
  from: string;
  to: string;
  lines: string[];
}

/**
 * Station names placed by the server (metro/station_labels.hpp) for the octilinear layout: per
 * zoom, each named station's label, and how the layout's metres map to the frame.
 */
export interface ServerLabels {
  info: LayoutLabels;
  /** Frame units per metre of the layout (Placement.scale). */
  framePerMetre: number;
  /** Per scale (the order of info.scales): station id -> its label. */
  byScale: Map<string, LayoutLabel>[];
}

/** The labels' font as the server measured it (DejaVu Sans Condensed Bold), at `sizePx` (its usual size or the smaller one); fallbacks are scaled to its widths. */
function serverFont(info: LayoutLabels, sizePx = info.font.size_px): string {
  return `${info.font.weight} ${sizePx}px "${info.font.family}", "DejaVu Sans", "Arial Narrow", sans-serif`;
}

/** A line's piece on screen, with half its drawn width (px). */
export interface MapSegment {
  x0: number;
  y0: number;
  x1: number;
  y1: number;
  half: number;
}

export interface MapObstacles {
  boxes: Box[];
  segments: MapSegment[];
  /** Screen boxes the page's panels cover (legend, controls, attribution): nothing to stand under. */
  covered?: Box[];
}

/** One line's strokes: along its edges, and its joins through the stations. */
interface DrawnLine {
  stroke: SVGPathElement;
  joins: SVGPathElement;
  /** A thin contrasting border under the stroke and joins (a line told apart from one of its colour). */
  border?: SVGPathElement;
  color: string;
}

/** The lines' stroke width, px (styles: .edge). */
const LINE_WIDTH_PX = 3.5;

/** The casing under bundles of this many lines is this much wider than the bundle, px. */
const CASING_MARGIN_PX = 3.5;

/**
 * A city's metro network and POIs drawn on a map: edges in the world layers, station and POI
 * markers and station labels in screen layers. Reports picks (clicks on markers, or on empty
 * map to clear) and shows names in a tooltip on hover.
 *
 * The drawing can move: setGeometry() puts stations, edges and POIs elsewhere (the octilinear
 * layout, or a frame of the morph towards it). `geo` is the geographic drawing it starts with.
 * It also makes, under the network, the layers for a heat map and the warp mesh, and above the
 * POIs one for clusters, which other classes fill.
 */
export class MetroLayers {
  readonly geo: Geometry;
  readonly heatLayer: SVGGElement;
  /** The streets in the schematic's space (RoadsLayer fills it): over the heat map, under the mesh and lines. */
  readonly roadLayer: SVGGElement;
  readonly clusterLayer: SVGGElement;
  private readonly stations = new Map<string, Marked<StationFeature> & StationMarker & { label: Label }>();
  private serverLabels: ServerLabels | null = null;
  private readonly pois = new Map<string, Marked<PoiFeature>>();
  private readonly edges: DrawnEdge[] = [];
  private readonly drawnLines = new Map<string, DrawnLine>();
  /** Per edge, its lines left to right along the edge (the layout's order, else as listed). */
  private orders: string[][] = [];
  /** Casings by bundle size (one white stroke under all edges of that many lines). */
  private readonly casings = new Map<number, SVGPathElement>();
  private readonly casingLayer: SVGGElement;
  /** The map scale the bundles were last drawn for (their spacing is in screen pixels). */
  private drawnScale = 0;
  private readonly stopRender: () => void;
  private readonly gridPath: SVGPathElement;
  private readonly connectorOutline: SVGPathElement;
  private readonly connectorInner: SVGPathElement;
  /** Pairs of station ids at one place under one name. */
  private readonly stationGroups: [string, string][];
  private readonly labels: Label[] = [];
  /** Per station id: the leader of a name set off from its symbol (made when first needed). */
  private readonly leaders = new Map<string, { line: SVGLineElement; anchor: Anchor }>();
  private readonly poiLayer: SVGGElement;
  private readonly labelLayer: SVGGElement;
  private readonly tooltip: MapTooltip;
  private readonly listeners = new AbortController();
  private readonly stopSettle: () => void;
  private selected?: SVGElement;
  /** Median straight distance between the ends of an edge, in frame units. */
  private typicalGap: number;
  private current: Geometry;
  private obstacles: () => Box[] = () => [];
  private moving = false;

  constructor(
    private readonly map: SvgMap,
    frame: Frame,
    metro: MetroCollection,
    pois: PoiFeature[],
    private readonly onPick: (pick: MetroPick | null) => void,
  ) {
    map.clear();
    const lines = new Map(metro.lines.map((line) => [line.id, line]));
    const edgeFeatures = metro.features.filter((f): f is EdgeFeature => f.properties.kind === 'edge');
    const stationFeatures = metro.features.filter((f): f is StationFeature => f.properties.kind === 'station');

    this.heatLayer = map.addLayer('heat', 'world');
    this.roadLayer = map.addLayer('roads', 'world');
    this.gridPath = svg('path', { class: 'warp-grid' });
    map.addLayer('grid', 'world').append(this.gridPath);
    this.casingLayer = map.addLayer('casing', 'world');
    this.drawEdges(map.addLayer('edges', 'world'), edgeFeatures, lines);
    // Stations of one name at one place (London's "Edgware Road (B)" and "(C)"): one symbol,
    // their rings joined by a bar over the lines.
    const connectors = map.addLayer('connectors', 'world');
    this.connectorOutline = svg('path', { class: 'station-connector-outline' });
    this.connectorInner = svg('path', { class: 'station-connector' });
    connectors.append(this.connectorOutline, this.connectorInner);
    this.stationGroups = groupsAtOnePlace(stationFeatures);
    this.poiLayer = map.addLayer('pois', 'screen');
    // Stations above POI pins and cluster markers: a tap on a station's symbol always picks the
    // station (markers are placed off the symbols, but their leaders and dots may cross them).
    this.clusterLayer = map.addLayer('clusters', 'screen');
    const stationLayer = map.addLayer('stations', 'screen');
    this.labelLayer = map.addLayer('labels', 'screen');
    for (const feature of pois) this.drawPoi(feature, frame);
    for (const feature of stationFeatures) this.drawStation(stationLayer, feature, frame, lines);

    this.geo = {
      stations: new Map([...this.stations].map(([id, { anchor }]) => [id, [anchor.x, anchor.y] as Pt])),
      pois: new Map([...this.pois].map(([id, { anchor }]) => [id, [anchor.x, anchor.y] as Pt])),
      edges: edgeFeatures.map((feature) => feature.geometry.coordinates.map((position) => frame.project(position))),
      grid: [],
    };
    this.current = this.geo;
    this.drawPaths(this.geo);
    this.typicalGap = medianGap(this.geo.edges);

    this.tooltip = new MapTooltip(map.element);
    this.listen();
    this.stopSettle = map.onSettle(() => this.settle());
    // Parallel lines keep their spacing in pixels: redrawn when the zoom changes it.
    this.stopRender = map.onRender(() => {
      if (Math.abs(this.map.scale / this.drawnScale - 1) > 0.02) this.drawPaths(this.current);
    });
    this.settle();
  }

  /**
   * Dims everything not on the line and draws the line's shared tracks in its own colour;
   * null shows all lines again.
   */
  highlightLine(lineId: string | null): void {
    const dimmed = (lines: string[]) => lineId !== null && !lines.includes(lineId);
    for (const [id, line] of this.drawnLines) {
      const off = lineId !== null && id !== lineId;
      line.stroke.classList.toggle('dimmed', off);
      line.joins.classList.toggle('dimmed', off);
      line.border?.classList.toggle('dimmed', off);
    }
    for (const { feature, element, label } of this.stations.values()) {
      const off = dimmed(feature.properties.lines);
      element.classList.toggle('dimmed', off);
      label.text.classList.toggle('dimmed', off);
      // The highlighted line's stations get their names first.
      label.priority = labelPriority(feature) + (lineId !== null && !off ? HIGHLIGHT_PRIORITY : 0);
    }
    this.settle();
  }

  /** `clustered`: only the selected POI shows (the clusters stand for the rest). */
  setPoisVisible(visible: boolean, clustered = false): void {
    this.poiLayer.style.display = visible ? '' : 'none';
    this.poiLayer.classList.toggle('clustered', clustered);
    this.clusterLayer.style.display = visible && clustered ? '' : 'none';
  }

  /** The edges in drawing order (the order of Geometry.edges). */
  get drawnEdges(): readonly DrawnEdge[] {
    return this.edges;
  }

  /** What is drawn now. */
  get geometry(): Geometry {
    return this.current;
  }

  /**
   * Moves everything to `geometry`. `final`: the morph is over, so markers are sized for the new
   * spacing and station names placed again; during a morph the names are hidden.
   */
  setGeometry(geometry: Geometry, final: boolean): void {
    this.current = geometry;
    if (geometry.orders) this.orders = this.validOrders(geometry.orders);
    for (const [id, { anchor, label }] of this.stations) {
      const point = geometry.stations.get(id);
      if (!point) continue;
      [anchor.x, anchor.y] = point;
      [label.anchor.x, label.anchor.y] = point;
    }
    for (const [id, { anchor }] of this.pois) {
      const point = geometry.pois.get(id);
      if (point) [anchor.x, anchor.y] = point;
    }
    this.drawPaths(geometry);
    this.moving = !final;
    this.labelLayer.classList.toggle('moving', !final);
    this.map.requestRender();
    if (final) {
      this.typicalGap = medianGap(geometry.edges);
      this.settle();
    }
  }

  setGridVisible(visible: boolean): void {
    this.gridPath.style.display = visible ? '' : 'none';
  }

  /** Screen boxes (other layers' markers) that station names keep clear of; asked at every placement. */
  setLabelObstacles(obstacles: () => Box[]): void {
    this.obstacles = obstacles;
  }

  /**
   * What POI markers keep clear of, in screen pixels: station symbols, the station names shown
   * (the server's; the client's own names make way for the markers instead), and the lines as
   * segments with their half width. Only what is within `margin` px of the window.
   */
  mapObstacles(margin = 120): MapObstacles {
    const { width, height } = this.map.size;
    const inView = (x: number, y: number) => x > -margin && y > -margin && x < width + margin && y < height + margin;
    const boxes: Box[] = [];
    const bundles = this.bundlesAtStations();
    for (const [id, { anchor, symbol, label }] of this.stations) {
      const [x, y] = this.map.toScreen(anchor.x, anchor.y);
      if (!inView(x, y)) continue;
      const radius = Number(symbol.getAttribute('height') ?? 8) / 2;
      const reach = radius + ((bundles.get(id)?.lines ?? 1) - 1) * (LINE_SPACING_PX / 2) + 2;
      boxes.push({ x0: x - reach, y0: y - reach, x1: x + reach, y1: y + reach });
      const box = this.serverLabels && label.text.getAttribute('visibility') === 'visible' ? label.text.getBBox() : null;
      if (box && box.width > 0) {
        const [lx, ly] = [x + label.anchor.dx, y + label.anchor.dy];
        boxes.push({ x0: lx + box.x - 2, y0: ly + box.y - 2, x1: lx + box.x + box.width + 2, y1: ly + box.y + box.height + 2 });
      }
    }
    const segments: MapSegment[] = [];
    this.current.edges.forEach((points, i) => {
      const half = ((this.orders[i]?.length ?? 1) * LINE_SPACING_PX) / 2 + 1;
      let previous: [number, number] | null = null;
      for (const point of points) {
        const here = this.map.toScreen(point[0], point[1]);
        if (previous && (inView(...previous) || inView(...here))) segments.push({ x0: previous[0], y0: previous[1], x1: here[0], y1: here[1], half });
        previous = here;
      }
    });
    return { boxes, segments };
  }

  /** Places the station names again (after another layer's markers changed). */
  placeLabels(): void {
    if (!this.moving) this.settle();
  }

  setLabelsVisible(visible: boolean): void {
    this.labelLayer.style.display = visible ? '' : 'none';
  }

  /** Marks a station or POI as selected, or none. */
  select(pick: MetroPick | null): void {
    this.selected?.classList.remove('selected');
    this.selected = pick ? this.marked(pick)?.element : undefined;
    if (!this.selected) return;
    this.selected.classList.add('selected');
    this.selected.parentNode?.append(this.selected); // on top of its neighbours
  }

  /** Moves the map to a station or POI that may be out of view. */
  reveal(pick: MetroPick): void {
    const marked = this.marked(pick);
    if (marked) this.map.reveal(marked.anchor.x, marked.anchor.y);
  }

  /**
   * Names placed by the server (the octilinear layout's), or null: the client places them (the
   * geographic map). Symbols then grow with the zoom as the server assumed.
   */
  setServerLabels(labels: ServerLabels | null): void {
    this.serverLabels = labels;
    for (const { label, feature } of this.stations.values())
      resetLabelText(label, feature.properties.name, labels ? serverFont(labels.info) : LABEL_FONT);
    if (!this.moving) this.settle();
  }

  /** Per drawn edge, its lines left to right: only an order of exactly the edge's lines is taken. */
  private validOrders(orders: (string[] | undefined)[]): string[][] {
    return this.edges.map((edge, i) => {
      const order = orders[i];
      return order && order.length === edge.lines.length && order.every((id) => edge.lines.includes(id)) ? order : edge.lines;
    });
  }

  destroy(): void {
    this.listeners.abort();
    this.stopSettle();
    this.stopRender();
    this.tooltip.destroy();
    this.map.clear();
  }

  private drawEdges(edgeLayer: SVGGElement, features: EdgeFeature[], lines: Map<string, MetroLine>): void {
    for (const feature of features) {
      const { from, to, lines: lineIds } = feature.properties;
      this.edges.push({ from, to, lines: lineIds });
      for (const id of lineIds) {
        if (this.drawnLines.has(id)) continue;
        const line = lines.get(id);
        const color = lineColor(line);
        const stroke = svg('path', { class: 'edge', stroke: color, 'data-line': id });
        const joins = svg('path', { class: 'edge-join', stroke: color, 'data-line': id });
        const dash = lineDash(line, LINE_WIDTH_PX);
        if (dash) stroke.style.strokeDasharray = dash;
        const border = lineCasing(line) ? svg('path', { class: 'edge-border', 'data-line': id }) : undefined;
        if (border) edgeLayer.append(border);
        edgeLayer.append(stroke, joins);
        this.drawnLines.set(id, { stroke, joins, border, color });
      }
    }
    this.orders = this.edges.map((edge) => edge.lines);
  }

  /**
   * Each line its own stroke, side by side where lines share an edge (in the edge's order),
   * joined through the stations; under each bundle a white casing as wide as the bundle.
   */
  private drawPaths(geometry: Geometry): void {
    const scale = this.map.scale > 0 ? this.map.scale : 1;
    this.drawnScale = scale;
    const spacing = LINE_SPACING_PX / scale;
    const bundles = this.edges.map((edge, i) => ({
      from: edge.from,
      to: edge.to,
      points: geometry.edges[i] ?? [],
      order: this.orders[i] ?? edge.lines,
    }));
    const pieces = bundlePieces(
      bundles.filter((b) => b.points.length > 1),
      spacing,
    );
    for (const [id, line] of this.drawnLines) {
      line.stroke.setAttribute('d', (pieces.strokes.get(id) ?? []).map(polylinePath).join(''));
      line.joins.setAttribute('d', (pieces.joins.get(id) ?? []).map(polylinePath).join(''));
      line.border?.setAttribute('d', `${line.stroke.getAttribute('d')}${line.joins.getAttribute('d')}`);
    }
    const bySize = new Map<number, string[]>();
    for (const bundle of bundles) {
      const size = Math.max(1, bundle.order.length);
      bySize.set(size, [...(bySize.get(size) ?? []), polylinePath(bundle.points)]);
    }
    for (const [size, paths] of bySize) {
      let casing = this.casings.get(size);
      if (!casing) {
        casing = svg('path', { class: 'edge-casing' });
        casing.style.strokeWidth = `${size * LINE_SPACING_PX + CASING_MARGIN_PX}px`;
        // Wider casings first, so a narrower bundle's casing never hides a wider one's lines.
        this.casingLayer.prepend(casing);
        this.casings.set(size, casing);
      }
      casing.setAttribute('d', paths.join(''));
    }
    this.gridPath.setAttribute('d', geometry.grid.map(polylinePath).join(''));
    const bars = this.stationGroups
      .map(([a, b]) => [geometry.stations.get(a), geometry.stations.get(b)])
      .filter((pair): pair is [Pt, Pt] => pair[0] !== undefined && pair[1] !== undefined)
      .map((pair) => polylinePath(pair))
      .join('');
    this.connectorOutline.setAttribute('d', bars);
    this.connectorInner.setAttribute('d', bars);
  }

  private drawStation(layer: SVGGElement, feature: StationFeature, frame: Frame, lines: Map<string, MetroLine>): void {
    const { id, name, lines: lineIds } = feature.properties;
    const interchange = lineIds.length > 1;
    const element = svg('g', { class: interchange ? 'station interchange' : 'station', 'data-id': id });
    if (!interchange) element.style.stroke = lineColor(lines.get(lineIds[0] ?? ''));
    const symbol = svg('rect', { class: 'station-symbol' });
    element.append(symbol);
    layer.append(element);
    const point = frame.project(feature.geometry.coordinates);
    const anchor = this.map.anchor(element, point);

    const text = svg('text', { class: 'station-label', visibility: 'hidden' });
    text.style.font = LABEL_FONT;
    text.textContent = name;
    this.labelLayer.append(text);
    const label = { anchor: this.map.anchor(text, point), marker: anchor, text, width: labelWidth(name), priority: labelPriority(feature) };
    this.labels.push(label);
    this.stations.set(id, { feature, element, anchor, symbol, label });
  }

  private drawPoi(feature: PoiFeature, frame: Frame): void {
    const element = svg('g', { class: 'poi', 'data-id': feature.properties.id });
    const shape = svg('g', { class: 'poi-shape' });
    shape.append(svg('path', { class: 'poi-pin', d: POI_PIN_PATH }), svg('circle', { class: 'poi-dot', cy: -11.5, r: 2.4 }));
    element.append(shape);
    this.poiLayer.append(element);
    this.pois.set(feature.properties.id, { feature, element, anchor: this.map.anchor(element, frame.project(feature.geometry.coordinates)) });
  }

  /**
   * Each station's symbol: a circle, or where lines run side by side through it a capsule across
   * the bundle. With the server's names, symbols grow with the zoom as it assumed (a share of
   * the mean edge on screen, within bounds); on the geographic map they shrink where stations
   * crowd.
   */
  private sizeMarkers(): void {
    const gap = this.typicalGap * this.map.scale;
    const scale = Math.max(MIN_MARKER_SCALE, Math.min(1, gap / FULL_SIZE_GAP_PX));
    const growth = window.matchMedia('(pointer: coarse)').matches ? TOUCH_GROWTH : 1;
    const server = this.serverLabels?.info;
    const meanEdgePx = server ? server.mean_edge_m * this.serverLabels!.framePerMetre * this.map.scale : 0;
    const serverRadius = server ? Math.min(server.symbol.max_px, Math.max(server.symbol.min_px, server.symbol.share * meanEdgePx)) : 0;
    const bundles = this.bundlesAtStations();
    for (const [id, { feature, symbol }] of this.stations) {
      const interchange = feature.properties.lines.length > 1;
      const radius = server ? serverRadius : (interchange ? INTERCHANGE_RADIUS : STATION_RADIUS) * scale * growth;
      const bundle = bundles.get(id);
      const lanes = bundle ? bundle.lines - 1 : 0;
      const length = 2 * radius + lanes * LINE_SPACING_PX;
      symbol.setAttribute('x', (-length / 2).toFixed(2));
      symbol.setAttribute('y', (-radius).toFixed(2));
      symbol.setAttribute('width', length.toFixed(2));
      symbol.setAttribute('height', (2 * radius).toFixed(2));
      symbol.setAttribute('rx', radius.toFixed(2));
      // Across the bundle: its long side at right angles to the lines.
      symbol.setAttribute('transform', bundle && lanes > 0 ? `rotate(${(bundle.angle + 90).toFixed(1)})` : '');
    }
    // Pins shrink less: they must stay recognisable as pins.
    const pinScale = `scale(${Math.max(MIN_PIN_SCALE, scale * growth).toFixed(2)})`;
    for (const { element } of this.pois.values()) element.firstElementChild?.setAttribute('transform', pinScale);
  }

  private marked(pick: MetroPick): Marked<StationFeature> | Marked<PoiFeature> | undefined {
    return pick.kind === 'station' ? this.stations.get(pick.station.properties.id) : this.pois.get(pick.poi.properties.id);
  }

  /** The station or POI marker under an event, if any. */
  private pickAt(target: EventTarget | null): { pick: MetroPick; marked: Marked<StationFeature> | Marked<PoiFeature> } | undefined {
    const element = target instanceof Element ? target.closest('.station, .poi') : null;
    const id = element?.getAttribute('data-id') ?? '';
    const station = element?.classList.contains('station') ? this.stations.get(id) : undefined;
    if (station) return { pick: { kind: 'station', station: station.feature }, marked: station };
    const poi = element?.classList.contains('poi') ? this.pois.get(id) : undefined;
    if (poi) return { pick: { kind: 'poi', poi: poi.feature }, marked: poi };
    return undefined;
  }

  private listen(): void {
    const options = { signal: this.listeners.signal };
    const svgElement = this.map.svg;
    svgElement.addEventListener(
      'click',
      (event) => {
        // Cluster markers are the cluster layer's to handle.
        if (event.target instanceof Element && event.target.closest('.cluster')) return;
        this.onPick(this.pickAt(event.target)?.pick ?? null);
      },
      options,
    );
    svgElement.addEventListener(
      'pointerover',
      (event) => {
        const hit = event.pointerType === 'mouse' ? this.pickAt(event.target) : undefined;
        if (!hit) return;
        const name = hit.pick.kind === 'station' ? hit.pick.station.properties.name : hit.pick.poi.properties.name;
        this.tooltip.show(name, this.map.toScreen(hit.marked.anchor.x, hit.marked.anchor.y));
      },
      options,
    );
    svgElement.addEventListener('pointerout', () => this.tooltip.hide(), options);
    svgElement.addEventListener('pointerdown', () => this.tooltip.hide(), options);
  }

  /** Per station: the widest bundle through it, and the direction its lines run (degrees, screen). */
  private bundlesAtStations(): Map<string, { lines: number; angle: number }> {
    const out = new Map<string, { lines: number; angle: number }>();
    this.edges.forEach((edge, i) => {
      const points = this.current.edges[i] ?? [];
      const lines = (this.orders[i] ?? edge.lines).length;
      if (points.length < 2 || lines < 2) return;
      for (const [id, from, to] of [
        [edge.from, points[0]!, points[1]!],
        [edge.to, points[points.length - 1]!, points[points.length - 2]!],
      ] as const) {
        if ((out.get(id)?.lines ?? 0) >= lines) continue;
        out.set(id, { lines, angle: (Math.atan2(to[1] - from[1], to[0] - from[0]) * 180) / Math.PI });
      }
    });
    return out;
  }

  private settle(): void {
    this.tooltip.hide();
    this.sizeMarkers();
    if (this.serverLabels) {
      this.showServerLabels(this.serverLabels);
      return;
    }
    const markers = [...this.stations.values()].map((station) => station.anchor);
    placeLabels(this.map, this.labels, markers, this.obstacles());
  }

  /**
   * The server's names for the largest zoom it placed them for at or below the map's: none of
   * them overlap there, nor (boxes keeping their size while positions spread) at any larger
   * zoom. Below the smallest, no names.
   */
  private showServerLabels(server: ServerLabels): void {
    const pxPerMetre = this.map.scale * server.framePerMetre;
    let chosen = -1;
    server.info.scales.forEach((scale, i) => {
      if (scale.px_per_m <= pxPerMetre * (1 + 1e-9)) chosen = i;
    });
    const byStation = chosen >= 0 ? server.byScale[chosen]! : new Map<string, LayoutLabel>();
    for (const [id, { label, feature }] of this.stations) {
      const placed = byStation.get(id);
      this.showLeader(id, label.anchor, placed && placed.length > 10 ? (placed.slice(10) as number[]) : undefined);
      if (!placed) {
        label.text.setAttribute('visibility', 'hidden');
        continue;
      }
      const [, x0, , x1, , tx, ty, anchor, split, size] = placed;
      const { font: type } = server.info;
      setLabelText(label, feature.properties.name, split, x1 - x0, (type.line_px * size) / type.size_px, serverFont(server.info, size));
      label.text.setAttribute('text-anchor', anchor === 's' ? 'start' : anchor === 'm' ? 'middle' : 'end');
      label.anchor.dx = tx;
      label.anchor.dy = ty;
      label.text.setAttribute('visibility', 'visible');
    }
    this.map.requestRender();
    // After that render (frame callbacks run in the order asked for).
    requestAnimationFrame(() => this.keepNamesOnTheMap());
  }

  /**
   * The server places names for the layout, not for the screen: after a fit, the outer ones
   * may stick out of the map (a phone's narrow screen). The map then fits again with room for
   * them (SvgMap.growFitMargins, only while it follows its fit); names still cut off after its
   * rounds (the room is capped, and other names show at the new zoom) are hidden rather than
   * shown in part: zooming in shows them. A map the user moved shows what it shows.
   */
  private keepNamesOnTheMap(): void {
    if (this.moving || !this.map.followingFit) return;
    const area = this.map.fitArea();
    const over = { top: 0, right: 0, bottom: 0, left: 0 };
    const outside: SVGTextElement[] = [];
    const breathing = 6; // px between a grown margin's name and the map's edge
    for (const { label } of this.stations.values()) {
      if (label.text.getAttribute('visibility') !== 'visible') continue;
      const box = label.text.getBoundingClientRect();
      if (box.width === 0) continue;
      const cut = box.left < area.left || box.right > area.right || box.top < area.top || box.bottom > area.bottom;
      if (!cut) continue;
      outside.push(label.text);
      over.left = Math.max(over.left, area.left - box.left + breathing);
      over.right = Math.max(over.right, box.right - area.right + breathing);
      over.top = Math.max(over.top, area.top - box.top + breathing);
      over.bottom = Math.max(over.bottom, box.bottom - area.bottom + breathing);
    }
    if (outside.length === 0 || this.map.growFitMargins(over)) return;
    for (const text of outside) text.setAttribute('visibility', 'hidden');
  }

  /** The name's leader from the symbol's rim to its box ([x0, y0, x1, y1] px from `at`), or none. */
  private showLeader(id: string, at: Anchor, coords?: number[]): void {
    let leader = this.leaders.get(id);
    if (!coords || coords.length < 4) {
      leader?.line.setAttribute('visibility', 'hidden');
      return;
    }
    if (!leader) {
      const line = svg('line', { class: 'station-leader' });
      this.labelLayer.prepend(line); // under every name
      leader = { line, anchor: this.map.anchor(line, [at.x, at.y]) };
      this.leaders.set(id, leader);
    }
    [leader.anchor.x, leader.anchor.y] = [at.x, at.y];
    const [x1, y1, x2, y2] = coords.map((v) => v.toFixed(1));
    for (const [name, value] of [['x1', x1], ['y1', y1], ['x2', x2], ['y2', y2]] as const) leader.line.setAttribute(name, value!);
    leader.line.setAttribute('visibility', 'visible');
  }
}

/** A name without a bracketed part ("Edgware Road (B)" -> "edgware road"). */
const baseName = (name: string) => name.replace(/\s*[([][^)\]]*[)\]]\s*/g, ' ').trim().toLowerCase();

/**
 * Pairs of stations that are one place under one name: the same name once bracketed parts are
 * dropped, less than 500 m apart on the ground.
 */
function groupsAtOnePlace(stations: StationFeature[]): [string, string][] {
  const byName = new Map<string, StationFeature[]>();
  for (const station of stations) {
    const key = baseName(station.properties.name);
    if (key) byName.set(key, [...(byName.get(key) ?? []), station]);
  }
  const pairs: [string, string][] = [];
  for (const group of byName.values()) {
    for (let i = 0; i < group.length; i++)
      for (let j = i + 1; j < group.length; j++) {
        const [a, b] = [group[i]!, group[j]!];
        if (groundMetres(a.geometry.coordinates, b.geometry.coordinates) < 500) pairs.push([a.properties.id, b.properties.id]);
      }
  }
  return pairs;
}

/** Equirectangular distance on the ground, metres: enough for stations a few hundred metres apart. */
function groundMetres([lon0, lat0]: [number, number], [lon1, lat1]: [number, number]): number {
  const k = Math.PI / 180;
  const x = (lon1 - lon0) * k * Math.cos(((lat0 + lat1) / 2) * k);
  const y = (lat1 - lat0) * k;
  return Math.hypot(x, y) * 6_371_000;
}

/** Back to one line of the name in `font`, unstretched. */
function resetLabelText(label: Label, name: string, font: string): void {
  label.text.replaceChildren(name);
  label.text.style.font = font;
  label.text.removeAttribute('textLength');
  label.text.removeAttribute('lengthAdjust');
  delete label.text.dataset.split;
}

/**
 * The name on one line or two (split at byte `split` of its UTF-8), each line stretched to the
 * width the server measured, so a fallback font takes the same room.
 */
function setLabelText(label: Label, name: string, split: number, width: number, linePx: number, font: string): void {
  const key = `${split} ${font}`;
  if (label.text.dataset.split !== key) {
    label.text.dataset.split = key;
    label.text.style.font = font;
    const bytes = new TextEncoder().encode(name);
    const parts = split > 0 ? [new TextDecoder().decode(bytes.slice(0, split)).trimEnd(), new TextDecoder().decode(bytes.slice(split))] : [name];
    const widths = parts.map((part) => measure(part, font));
    const stretch = width / Math.max(...widths, 1);
    label.text.replaceChildren(
      ...parts.map((part, i) => {
        const tspan = svg('tspan', { x: 0, dy: i === 0 ? 0 : linePx, textLength: (widths[i]! * stretch).toFixed(1), lengthAdjust: 'spacingAndGlyphs' });
        tspan.textContent = part;
        return tspan;
      }),
    );
  }
}

let measureCanvas: CanvasRenderingContext2D | null | undefined;

function measure(text: string, font: string): number {
  measureCanvas ??= document.createElement('canvas').getContext('2d');
  if (!measureCanvas) return text.length * 7;
  measureCanvas.font = font;
  return measureCanvas.measureText(text).width;
}

/** Interchanges are named before plain stations. */
function labelPriority(station: StationFeature): number {
  return station.properties.lines.length;
}

function medianGap(edges: Pt[][]): number {
  const gaps = edges
    .filter((points) => points.length > 1)
    .map((points) => {
      const [x0, y0] = points[0]!;
      const [x1, y1] = points[points.length - 1]!;
      return Math.hypot(x1 - x0, y1 - y0);
    })
    .filter((gap) => gap > 0)
    .sort((a, b) => a - b);
  return gaps[Math.floor(gaps.length / 2)] ?? 1;
}
