import type { DeformStats } from '../api/types';
import { h } from '../ui/dom';

const ms = (value: number | undefined) => (value === undefined || value === null ? '—' : `${value < 10 ? value.toFixed(1) : Math.round(value)} ms`);
const number = (value: number | undefined | null, digits = 0) =>
  value === undefined || value === null || !Number.isFinite(value) ? '—' : value.toLocaleString('en', { maximumFractionDigits: digits });

/** Rounds to a few significant digits for display (residues span many magnitudes). */
function significant(value: number): string {
  if (!Number.isFinite(value)) return String(value);
  return value.toLocaleString('en', { maximumSignificantDigits: 4 });
}

/**
 * The solver's numbers for the map drawn now, the browser's round trip, and while dragging the
 * frames drawn per second and the deformed maps received per second.
 */
export class StatsBox {
  readonly element: HTMLElement;
  private readonly table: HTMLDListElement;
  private readonly drag: HTMLElement;
  private readonly busy: HTMLElement;

  constructor() {
    this.table = h('dl', { class: 'stats-table' });
    this.drag = h('p', { class: 'stats-drag', 'data-testid': 'drag-meter' });
    this.busy = h('span', { class: 'stats-busy', hidden: true }, 'computing…');
    // A <details>, folded until opened: the numbers are for those who compare methods, and the
    // box would cover part of the map.
    this.element = h(
      'details',
      { class: 'stats', 'data-testid': 'deform-stats', 'aria-label': 'Deformation statistics' },
      h('summary', {}, 'Numbers', this.busy),
      this.table,
      this.drag,
    );
    this.clear();
  }

  clear(text = 'Nothing deformed yet.'): void {
    this.table.replaceChildren(h('div', { class: 'wide' }, h('dt', {}, text)));
    this.element.dataset.residue = '';
  }

  setBusy(busy: boolean): void {
    this.busy.hidden = !busy;
  }

  show(stats: DeformStats, roundTripMs: number): void {
    const ratio = stats.residue_rest > 0 ? ` (${Math.round((100 * stats.residue) / stats.residue_rest)}%)` : '';
    // Pairs side by side; the method gets a row of its own.
    const rows: { term: string; value: string; key?: string; wide?: boolean; title?: string }[] = [
      { term: 'Residue', value: `${significant(stats.residue)}${ratio}`, key: 'residue', title: 'Road-edge and guide residual after deforming, and its share of the undeformed residual' },
      { term: 'Undeformed', value: significant(stats.residue_rest), key: 'residue-rest', title: 'The same residual before deforming' },
      { term: 'Unknowns', value: number(stats.unknowns) },
      { term: 'Quads', value: number(stats.quads) },
      { term: 'Solve', value: ms(stats.solve_ms), title: 'Server: solving only' },
      { term: 'Server', value: ms(stats.total_ms), title: 'Server: the whole request' },
      { term: 'Round trip', value: ms(roundTripMs), key: 'round-trip', title: 'Browser: from sending the request to having its answer parsed' },
      { term: 'Cache', value: stats.cache, key: 'cache' },
      { term: 'Fold-overs', value: number(stats.foldovers) },
      { term: 'Converged', value: stats.converged ? 'yes' : 'no' },
      {
        term: 'Method',
        value: `${stats.method} · ${stats.solver}${stats.solver === 'cg' ? `, ${number(stats.iterations)} iterations` : ''}`,
        wide: true,
      },
    ];
    this.table.replaceChildren(
      ...rows.map(({ term, value, key, wide, title }) =>
        h('div', { class: wide ? 'wide' : undefined, 'data-stat': key, title }, h('dt', {}, term), h('dd', { class: wide ? 'words' : undefined }, value)),
      ),
    );
    this.element.dataset.residue = String(stats.residue);
    this.element.dataset.cache = stats.cache;
  }

  /** The drag meter: live numbers while dragging, a summary of the last drag after. */
  showDrag(text: string): void {
    this.drag.textContent = text;
  }
}
