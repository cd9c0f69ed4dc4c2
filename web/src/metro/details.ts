import type { LonLat, MetroLine, PoiFeature, StationFeature } from '../api/types';
import { formatDistance, nearest } from '../map/distance';
import { h } from '../ui/dom';
import { lineColor, sortLines, textColorOn } from './lines';
import type { MetroPick } from './metro-layers';
import { httpUrl } from '../ui/url';

export interface DetailsContext {
  lines: Map<string, MetroLine>;
  stations: StationFeature[];
  pois: PoiFeature[];
  onPick(pick: MetroPick): void;
  /** The "Walk from the nearest station" section of a POI (walk-layer.ts), or null. */
  walk?(poi: PoiFeature): HTMLElement | null;
}

/** Walking distances for the "nearby" lists. */
const NEARBY_POI_METERS = 800;
const NEARBY_STATION_METERS = 1500;
const NEARBY_LIMIT = 5;

const position = (feature: StationFeature | PoiFeature): LonLat => feature.geometry.coordinates;

function lineChips(lineIds: string[], lines: Map<string, MetroLine>): HTMLElement {
  const known = sortLines(lineIds.map((id) => lines.get(id)).filter((line): line is MetroLine => line !== undefined));
  return h(
    'div',
    { class: 'line-chips' },
    ...known.map((line) => {
      const color = lineColor(line);
      return h('span', { class: 'line-chip', style: `background:${color};color:${textColorOn(color)}` }, line.label);
    }),
  );
}

function nearbyList(title: string, entries: { label: Node[]; meters: number; pick: MetroPick }[], context: DetailsContext) {
  if (entries.length === 0) return null;
  return h(
    'section',
    { class: 'nearby' },
    h('h3', {}, title),
    h(
      'ul',
      {},
      ...entries.map((entry) => {
        const button = h('button', { type: 'button', class: 'nearby-item' }, ...entry.label, h('span', { class: 'distance' }, formatDistance(entry.meters)));
        button.addEventListener('click', () => context.onPick(entry.pick));
        return h('li', {}, button);
      }),
    ),
  );
}

export function stationDetails(station: StationFeature, context: DetailsContext): Node[] {
  const nearby = nearest(position(station), context.pois, position, NEARBY_POI_METERS, NEARBY_LIMIT).map(({ item, meters }) => ({
    label: [h('span', { class: 'nearby-name' }, item.properties.name)],
    meters,
    pick: { kind: 'poi', poi: item } as const,
  }));
  const lineCount = station.properties.lines.length;
  return [
    h('p', { class: 'details-kind' }, lineCount > 1 ? `Interchange · ${lineCount} lines` : 'Station'),
    lineChips(station.properties.lines, context.lines),
    nearbyList('Places nearby', nearby, context),
  ].filter((node): node is HTMLElement => node !== null);
}

export function poiDetails(poi: PoiFeature, context: DetailsContext): Node[] {
  const { category, image, url, wikipedia } = poi.properties;
  const imageUrl = httpUrl(image);
  const figure = imageUrl
    ? h('figure', { class: 'poi-image' }, h('img', { src: imageUrl, alt: '', loading: 'lazy', referrerpolicy: 'no-referrer' }))
    : null;
  // A photo that cannot be loaded leaves no broken-image icon behind.
  figure?.querySelector('img')?.addEventListener('error', () => figure.remove());

  const links = [
    httpUrl(url) && h('a', { href: httpUrl(url), target: '_blank', rel: 'noopener noreferrer' }, 'Website'),
    httpUrl(wikipedia) && h('a', { href: httpUrl(wikipedia), target: '_blank', rel: 'noopener noreferrer' }, 'Wikipedia'),
  ].filter((link): link is HTMLAnchorElement => link instanceof HTMLAnchorElement);

  const nearby = nearest(position(poi), context.stations, position, NEARBY_STATION_METERS, NEARBY_LIMIT).map(({ item, meters }) => ({
    label: [h('span', { class: 'nearby-name' }, item.properties.name), lineChips(item.properties.lines, context.lines)],
    meters,
    pick: { kind: 'station', station: item } as const,
  }));

  return [
    h('p', { class: 'details-kind' }, category),
    figure,
    links.length > 0 ? h('p', { class: 'poi-links' }, ...links) : null,
    context.walk?.(poi) ?? null,
    nearbyList('Nearest stations', nearby, context),
  ].filter((node): node is HTMLElement => node !== null);
}
