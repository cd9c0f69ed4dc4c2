import type { RoadGraph } from './road-graph';

/** A binary min-heap of node indices keyed by distance (lazy deletion: stale entries are skipped). */
class Heap {
  private keys: number[] = [];
  private nodes: number[] = [];

  get size(): number {
    return this.keys.length;
  }

  push(key: number, node: number): void {
    let i = this.keys.length;
    this.keys.push(key);
    this.nodes.push(node);
    while (i > 0) {
      const parent = (i - 1) >> 1;
      if (this.keys[parent]! <= key) break;
      this.keys[i] = this.keys[parent]!;
      this.nodes[i] = this.nodes[parent]!;
      i = parent;
    }
    this.keys[i] = key;
    this.nodes[i] = node;
  }

  /** Removes the smallest entry; returns its node (the heap must not be empty). */
  pop(): { key: number; node: number } {
    const top = { key: this.keys[0]!, node: this.nodes[0]! };
    const lastKey = this.keys.pop()!;
    const lastNode = this.nodes.pop()!;
    const n = this.keys.length;
    if (n > 0) {
      let i = 0;
      for (;;) {
        let child = 2 * i + 1;
        if (child >= n) break;
        if (child + 1 < n && this.keys[child + 1]! < this.keys[child]!) child++;
        if (this.keys[child]! >= lastKey) break;
        this.keys[i] = this.keys[child]!;
        this.nodes[i] = this.nodes[child]!;
        i = child;
      }
      this.keys[i] = lastKey;
      this.nodes[i] = lastNode;
    }
    return top;
  }
}

/**
 * The shortest path between two nodes (Dijkstra on edge lengths in metres) as node indices
 * from `from` to `to`, or null when no road joins them.
 */
export function shortestPath(graph: RoadGraph, from: number, to: number): { nodes: number[]; meters: number } | null {
  const distance = new Float64Array(graph.nodeCount).fill(Infinity);
  const previous = new Int32Array(graph.nodeCount).fill(-1);
  const heap = new Heap();
  distance[from] = 0;
  heap.push(0, from);
  while (heap.size > 0) {
    const { key, node } = heap.pop();
    if (key > distance[node]!) continue;
    if (node === to) break;
    for (let s = graph.offsets[node]!; s < graph.offsets[node + 1]!; s++) {
      const next = graph.targets[s]!;
      const candidate = key + graph.lengths[s]!;
      if (candidate < distance[next]!) {
        distance[next] = candidate;
        previous[next] = node;
        heap.push(candidate, next);
      }
    }
  }
  if (!Number.isFinite(distance[to]!)) return null;
  const nodes = [to];
  for (let node = to; node !== from; ) {
    node = previous[node]!;
    nodes.push(node);
  }
  return { nodes: nodes.reverse(), meters: distance[to]! };
}
