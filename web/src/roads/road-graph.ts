import type { RoadTopology } from '../api/types';

/** Road classes drawn alike, from the bottom of the map to the top. */
export const ROAD_CLASSES = ['path', 'service', 'minor', 'medium', 'major'] as const;
export type RoadClass = (typeof ROAD_CLASSES)[number];

const HIGHWAYS: Record<RoadClass, string[]> = {
  path: ['footway', 'path', 'pedestrian', 'steps', 'cycleway', 'track', 'bridleway', 'corridor'],
  service: ['service'],
  minor: ['residential', 'unclassified', 'living_street', 'road'],
  medium: ['secondary', 'secondary_link', 'tertiary', 'tertiary_link'],
  major: ['motorway', 'motorway_link', 'trunk', 'trunk_link', 'primary', 'primary_link'],
};
const CLASS_OF = new Map<string, RoadClass>(
  ROAD_CLASSES.flatMap((roadClass) => HIGHWAYS[roadClass].map((highway) => [highway, roadClass] as const)),
);

const EARTH_RADIUS_M = 6371008.8;
const RAD = Math.PI / 180;

/**
 * A road network's topology: nodes (original positions and OSM ids), ways grouped by road
 * class for drawing, and an adjacency list with edge lengths in metres for routing.
 */
export class RoadGraph {
  readonly id: string;
  readonly nodeCount: number;
  readonly nodeIds: number[];
  /** Original [lon, lat, ...]. */
  readonly lonLat: Float64Array;
  /** Node index lists of the ways of each class. */
  readonly waysByClass: Map<RoadClass, Uint32Array[]>;
  /** Compressed adjacency: the neighbours of node i are targets[offsets[i] .. offsets[i + 1]). */
  readonly offsets: Uint32Array;
  readonly targets: Uint32Array;
  readonly lengths: Float64Array;
  /** Every road edge once, as node pairs (a, b, a, b, ...). */
  readonly edges: Uint32Array;
  private indexById?: Map<number, number>;

  constructor(topology: RoadTopology) {
    this.id = topology.network;
    this.nodeCount = topology.node_ids.length;
    this.nodeIds = topology.node_ids;
    this.lonLat = Float64Array.from(topology.positions);
    if (this.lonLat.length !== 2 * this.nodeCount) throw new Error('The road topology has a position count that does not match its nodes.');

    this.waysByClass = new Map(ROAD_CLASSES.map((roadClass) => [roadClass, []]));
    const degree = new Uint32Array(this.nodeCount + 1);
    for (const way of topology.ways) {
      const nodes = Uint32Array.from(way.nodes);
      this.waysByClass.get(CLASS_OF.get(way.highway) ?? 'minor')!.push(nodes);
      for (let i = 1; i < nodes.length; i++) {
        if (nodes[i] === nodes[i - 1]) continue;
        degree[nodes[i - 1]!]!++;
        degree[nodes[i]!]!++;
      }
    }
    this.offsets = new Uint32Array(this.nodeCount + 1);
    for (let i = 0; i < this.nodeCount; i++) this.offsets[i + 1] = this.offsets[i]! + degree[i]!;
    this.targets = new Uint32Array(this.offsets[this.nodeCount]!);
    this.lengths = new Float64Array(this.targets.length);
    const fill = this.offsets.slice(0, this.nodeCount);
    const link = (a: number, b: number, length: number) => {
      const slot = fill[a]!++;
      this.targets[slot] = b;
      this.lengths[slot] = length;
    };
    const pairs: number[] = [];
    for (const way of topology.ways) {
      for (let i = 1; i < way.nodes.length; i++) {
        const a = way.nodes[i - 1]!;
        const b = way.nodes[i]!;
        if (a === b) continue;
        const length = this.distance(a, b);
        link(a, b, length);
        link(b, a, length);
        pairs.push(a, b);
      }
    }
    this.edges = Uint32Array.from(pairs);
  }

  /** The node index of an OSM node id. */
  indexOf(nodeId: number): number | undefined {
    this.indexById ??= new Map(this.nodeIds.map((id, index) => [id, index]));
    return this.indexById.get(nodeId);
  }

  /** Metres between two nodes, at their original positions (equirectangular: edges are short). */
  distance(a: number, b: number): number {
    const p = this.lonLat;
    const cosLat = Math.cos(((p[2 * a + 1]! + p[2 * b + 1]!) / 2) * RAD);
    const dx = (p[2 * b]! - p[2 * a]!) * cosLat;
    const dy = p[2 * b + 1]! - p[2 * a + 1]!;
    return Math.hypot(dx, dy) * RAD * EARTH_RADIUS_M;
  }
}
