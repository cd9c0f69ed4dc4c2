import type { RoadFeature } from '../api/types';
import type { Frame } from '../map/projection';
import { polylinePath, svg } from '../map/svg';
import type { SvgMap } from '../map/svg-map';

/** Road classes drawn alike, from the bottom of the map to the top. */
const CLASSES: { name: string; highways: string[] }[] = [
  { name: 'path', highways: ['footway', 'path', 'pedestrian', 'steps', 'cycleway', 'track', 'bridleway', 'corridor'] },
  { name: 'service', highways: ['service'] },
  { name: 'minor', highways: ['residential', 'unclassified', 'living_street', 'road'] },
  { name: 'medium', highways: ['secondary', 'secondary_link', 'tertiary', 'tertiary_link'] },
  { name: 'major', highways: ['motorway', 'motorway_link', 'trunk', 'trunk_link', 'primary', 'primary_link'] },
];
const CLASS_OF = new Map(CLASSES.flatMap(({ name, highways }) => highways.map((highway) => [highway, name])));

/**
 * A road network on a map, geographically. Tens of thousands of ways become one SVG path per
 * road class: far fewer DOM nodes than one element per way, and still crisp at any zoom.
 */
export function drawRoads(map: SvgMap, frame: Frame, roads: RoadFeature[]): void {
  map.clear();
  const paths = new Map(CLASSES.map(({ name }) => [name, [] as string[]]));
  for (const road of roads) {
    const roadClass = CLASS_OF.get(road.properties.highway) ?? 'minor';
    paths.get(roadClass)!.push(polylinePath(road.geometry.coordinates.map((position) => frame.project(position))));
  }
  const layer = map.addLayer('roads', 'world');
  for (const [name, d] of paths) {
    if (d.length > 0) layer.append(svg('path', { class: `road road-${name}`, d: d.join('') }));
  }
}
