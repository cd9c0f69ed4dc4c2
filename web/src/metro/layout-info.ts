import type { LayoutAnswer } from '../api/client';
import type { LayoutSolver } from '../api/types';
import { h } from '../ui/dom';
import { HEAT_GRADIENT } from './heat-layer';

const seconds = (ms: number) => (ms < 1000 ? `${Math.round(ms)} ms` : `${(ms / 1000).toFixed(1)} s`);
const percent = (share: number) => `${(share * 100).toFixed(share >= 0.995 && share < 1 ? 1 : 0)}%`;

/**
 * The box over the map's lower left corner: the octilinear layout's quality and solver (or a
 * spinner with the time spent while it computes), the heat map's key and the clusters shown.
 * A <details>, so it can be folded away.
 */
export class LayoutInfo {
  readonly element: HTMLDetailsElement;
  /** A small note over the map while a layout computes (the numbers box sits in Advanced). */
  readonly busy: HTMLElement;
  private readonly summary: HTMLElement;
  private readonly layout: HTMLElement;
  private readonly heat: HTMLElement;
  private readonly places: HTMLElement;
  private readonly grid: HTMLElement;
  private timer = 0;

  constructor() {
    this.summary = h('summary', {}, 'Map');
    this.busy = h('p', { class: 'map-busy', role: 'status', hidden: true });
    this.layout = h('div', { class: 'info-layout', 'data-testid': 'layout-info', hidden: true });
    this.heat = h('div', { class: 'info-heat', hidden: true });
    this.places = h('p', { class: 'info-places', 'data-testid': 'cluster-info', hidden: true });
    this.grid = h('p', { class: 'info-grid', hidden: true });
    this.element = h(
      'details',
      { class: 'map-info', open: true, hidden: true },
      this.summary,
      this.layout,
      this.heat,
      this.grid,
      this.places,
    );
  }

  /** A spinner and the seconds spent, while the server computes a layout. */
  loading(cityName: string, note: string): void {
    this.stopTimer();
    const started = performance.now();
    const elapsed = h('span', { class: 'elapsed num' }, '');
    const busyElapsed = h('span', { class: 'num' }, '');
    this.busy.replaceChildren(h('span', { class: 'spinner', 'aria-hidden': 'true' }), 'Drawing the schematic map… ', busyElapsed);
    this.busy.hidden = false;
    const tick = () => {
      elapsed.textContent = `${((performance.now() - started) / 1000).toFixed(1)} s`;
      busyElapsed.textContent = elapsed.textContent;
    };
    tick();
    this.timer = window.setInterval(tick, 100);
    this.layout.replaceChildren(
      h(
        'div',
        { class: 'info-loading', role: 'status' },
        h('span', { class: 'spinner', 'aria-hidden': 'true' }),
        h('span', {}, `Computing the octilinear layout of ${cityName}… `, elapsed),
      ),
      h('p', { class: 'info-note' }, note),
    );
    this.layout.dataset.state = 'loading';
    this.layout.hidden = false;
    this.update();
  }

  showLayout(answer: LayoutAnswer): void {
    this.stopTimer();
    const { quality, solver, timing_ms: timing, params } = answer.layout;
    const mip = solver.mip;
    const room = solver.label_room;
    const applied = [
      solver.kind === 'mip' ? 'polished by the MIP' : '',
      room && room.kept > 0 ? `room made for ${room.unnamed_before - room.unnamed_after} more station names` : '',
    ].filter(Boolean);
    const mipText = [
      mip ? `MIP ${mip.accepted ? 'accepted' : 'not used'}${mip.status ? ` (${mip.status}${mip.accepted || !mip.reason ? '' : `: ${mip.reason}`})` : ''}` : '',
      solver.improvement === 'scheduled'
        ? 'The server improves this layout in the background (fewer bends, room for names): the map changes to it if it is better'
        : '',
      solver.improvement === 'applied' && applied.length > 0 ? `Improved in the background: ${applied.join(', ')}` : '',
      solver.improvement === 'none' && solver.tried ? `Kept after trying in the background: ${triedText(solver.tried)}` : '',
    ]
      .filter(Boolean)
      .join('. ');
    const rows: [string, string, string?][] = [
      ['Octilinear', percent(quality.octilinear_share), 'Share of edge segments at a multiple of 45°'],
      ['Bends', (quality.compare?.bends ?? quality.bends).toLocaleString()],
      ['Crossings', `${quality.crossings} (geo ${quality.geo_crossings}, added ${quality.added_crossings})`, 'Edge crossings in the layout (in the geographic map; in the layout only)'],
      ['Order viol.', String(quality.order_violations), 'Order violations: stations whose neighbours changed their circular order'],
      ['Solver', `${solver.kind} · ${solver.status}`],
      ['Lengths', params.lengths === 'uniform' ? 'uniform' : 'visual worth'],
      ['Server', `${seconds(timing.total ?? 0)}${answer.cache === 'hit' ? ' (cache)' : ''}`, 'Server time to compute the layout (when it was made; "cache": this answer came from the cache)'],
      ['Fetch', seconds(answer.fetchMs), 'Browser: this request, from sending it to the parsed answer'],
    ];
    this.layout.replaceChildren(
      h('dl', { class: 'info-table' }, ...rows.map(([term, value, title]) => h('div', { title }, h('dt', {}, term), h('dd', {}, value)))),
      ...(mipText ? [h('p', { class: 'info-note' }, mipText)] : []),
    );
    this.layout.dataset.state = 'ready';
    this.layout.dataset.octilinear = String(quality.octilinear_share);
    this.layout.dataset.solver = solver.kind;
    this.layout.dataset.improvement = solver.improvement ?? '';
    this.layout.hidden = false;
    this.update();
  }

  hideLayout(): void {
    this.stopTimer();
    this.layout.hidden = true;
    this.layout.replaceChildren();
    delete this.layout.dataset.state;
    this.update();
  }

  /** The heat map's key, with a note on what it shows; null hides it. */
  setHeat(note: string | null): void {
    this.heat.hidden = note === null;
    if (note !== null) {
      this.heat.replaceChildren(
        h('div', { class: 'heat-key' }, h('span', {}, 'Visual worth'), h('span', { class: 'heat-ramp', style: `background:${HEAT_GRADIENT}` }), h('span', {}, 'high')),
        ...(note ? [h('p', { class: 'info-note' }, note)] : []),
      );
    }
    this.update();
  }

  /** What the warp grid shows now; null hides the line. */
  setGrid(text: string | null): void {
    this.grid.hidden = text === null;
    this.grid.textContent = text ?? '';
    this.update();
  }

  setPlaces(text: string | null): void {
    this.places.hidden = text === null;
    this.places.textContent = text ?? '';
    this.update();
  }

  private update(): void {
    this.element.hidden = this.layout.hidden && this.heat.hidden && this.grid.hidden && this.places.hidden;
    this.summary.textContent = this.layout.hidden ? 'Map numbers' : 'Layout numbers';
  }

  private stopTimer(): void {
    this.busy.hidden = true;
    window.clearInterval(this.timer);
    this.timer = 0;
  }
}

/** What a background improvement tried and why none of it was kept, in words. */
function triedText(tried: NonNullable<LayoutSolver['tried']>): string {
  const parts: string[] = [];
  if (tried.mip) parts.push(`the MIP: ${tried.mip.reason ?? tried.mip.status ?? 'no result'}`);
  const room = tried.label_room;
  if (room && room.status !== 'not_needed') parts.push(`room for ${room.rooms} station names: ${room.status === 'no_time' ? 'out of time' : 'none more named'}`);
  return parts.length > 0 ? parts.join('; ') : 'nothing to improve';
}
