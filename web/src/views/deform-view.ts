import { fetchRoadNetworks, fetchRoads, isAbort } from '../api/client';
import type { LastImport, RoadNetworkSummary } from '../api/types';
import { mapControls } from '../map/controls';
import { frameFor } from '../map/projection';
import { SvgMap } from '../map/svg-map';
import { drawRoads } from '../roads/road-layers';
import { attributionBox, showAttribution } from '../ui/attribution';
import { h } from '../ui/dom';
import { StatusOverlay } from '../ui/status';
import { upcomingPanel } from './upcoming';
import type { View } from './view';

/**
 * The Deform view. The server cannot deform maps yet, so this says what is coming and, to
 * choose a network already, draws the picked road network as it is: geographic, undeformed.
 */
export class DeformView implements View {
  readonly element: HTMLElement;
  private readonly picker: HTMLSelectElement;
  private readonly map = new SvgMap('Road network, undeformed');
  private readonly status = new StatusOverlay();
  private readonly attribution = attributionBox();
  private networks?: RoadNetworkSummary[];
  private wanted?: string;
  private drawn?: string;
  private load?: AbortController;

  constructor(private readonly go: (networkId: string, replace: boolean) => void) {
    this.picker = h('select', { id: 'road-picker', 'data-testid': 'road-picker', disabled: true });
    this.picker.addEventListener('change', () => this.go(this.picker.value, false));
    this.map.element.dataset.testid = 'road-map';

    this.element = h(
      'section',
      { class: 'view view-deform' },
      h(
        'div',
        { class: 'view-side' },
        upcomingPanel(
          'Deform: focus + context road maps',
          'Enlarge the part of a road network you care about while the rest stays on screen as context. The server does not compute deformed maps yet.',
          [
            'Pick a road network and a focus area; the focus is drawn larger, its surroundings shrink smoothly around it.',
            'The deformation runs on an adaptive grid, finer where roads are dense, so roads stay smooth and never fold over each other.',
            'Road networks come from the server’s imported OpenStreetMap extracts (the picker below already lists them).',
          ],
        ),
        h('div', { class: 'field-row' }, h('label', { class: 'field', for: 'road-picker' }, 'Road network'), this.picker),
        h('p', { class: 'note' }, 'The map shows the chosen network as it is today: geographic, not deformed.'),
      ),
      h('div', { class: 'map-area' }, this.map.element, mapControls(this.map), this.attribution, this.status.element),
    );
    void this.loadNetworks();
  }

  show(networkId: string | undefined): void {
    this.wanted = networkId;
    document.title = 'Deform · tourmap';
    if (this.networks) this.openWanted();
  }

  catalogChanged(lastImport: LastImport | undefined): void {
    if (lastImport && lastImport.kind !== 'roads') return;
    if (!lastImport || lastImport.target === this.drawn) this.drawn = undefined;
    void this.loadNetworks();
  }

  private async loadNetworks(): Promise<void> {
    if (!this.networks) this.status.loading('Loading road networks…');
    try {
      this.networks = await fetchRoadNetworks();
    } catch (error) {
      if (!this.networks) this.status.error('Could not load the road networks', error, () => void this.loadNetworks());
      return;
    }
    this.picker.replaceChildren(
      ...this.networks.map((network) =>
        h('option', { value: network.id }, `${network.name} — ${network.counts.edges.toLocaleString()} road segments`),
      ),
    );
    this.picker.disabled = this.networks.length === 0;
    this.openWanted();
  }

  private openWanted(): void {
    const networks = this.networks ?? [];
    if (!this.wanted) {
      if (networks[0]) this.go(networks[0].id, true);
      else this.status.error('No road networks yet', new Error('Import one with `tourmap import roads` and it will appear here.'));
      return;
    }
    const network = networks.find((candidate) => candidate.id === this.wanted);
    if (!network) {
      this.load?.abort();
      this.drawn = undefined;
      this.map.clear();
      showAttribution(this.attribution, []);
      this.map.element.dataset.status = 'error';
      this.status.error(`There is no road network “${this.wanted}”`, new Error('Pick one of the networks in the list.'));
      return;
    }
    this.picker.value = network.id;
    if (this.drawn !== network.id) void this.loadNetwork(network);
  }

  private async loadNetwork(network: RoadNetworkSummary): Promise<void> {
    this.load?.abort();
    const load = new AbortController();
    this.load = load;
    this.drawn = network.id;
    this.map.element.dataset.status = 'loading';
    this.status.loading(`Loading ${network.name}…`);
    try {
      const roads = await fetchRoads(network.id, load.signal);
      const frame = frameFor(network.bbox);
      this.map.setFrame(frame);
      drawRoads(this.map, frame, roads.features);
      showAttribution(this.attribution, [...network.attribution, ...roads.attribution]);
      this.status.clear();
      this.map.element.dataset.status = 'ready';
    } catch (error) {
      if (isAbort(error)) return;
      this.drawn = undefined;
      this.map.clear();
      this.map.element.dataset.status = 'error';
      this.status.error(`Could not load ${network.name}`, error, () => void this.loadNetwork(network));
    }
  }
}
