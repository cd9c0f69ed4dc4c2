import { fetchCities, fetchCity, fetchMetro, fetchPois, isAbort } from '../api/client';
import type { CitySummary, LastImport, PoiCollection, StationFeature } from '../api/types';
import { mapControls } from '../map/controls';
import { extendBBox } from '../map/bbox';
import { frameFor } from '../map/projection';
import { SvgMap, type Insets } from '../map/svg-map';
import { poiDetails, stationDetails, type DetailsContext } from '../metro/details';
import { Legend } from '../metro/legend';
import { MetroLayers, type MetroPick } from '../metro/metro-layers';
import { attributionBox, showAttribution } from '../ui/attribution';
import { DetailsPanel } from '../ui/details-panel';
import { h } from '../ui/dom';
import { StatusOverlay } from '../ui/status';
import type { View } from './view';

const NO_POIS: Pick<PoiCollection, 'features' | 'attribution'> = { features: [], attribution: [] };

const plural = (n: number, word: string) => `${n.toLocaleString()} ${word}${n === 1 ? '' : 's'}`;

/**
 * The Metro view: a city picker and the city's metro network and POIs on a geographic map.
 * The map element's data-status (loading, ready, error) and data-city tell tests when it is drawn.
 */
export class MetroView implements View {
  readonly element: HTMLElement;
  private readonly picker: HTMLSelectElement;
  private readonly summary: HTMLElement;
  private readonly map: SvgMap;
  private readonly legend: Legend;
  private readonly details: DetailsPanel;
  private readonly status = new StatusOverlay();
  private readonly attribution = attributionBox();
  private cities?: CitySummary[];
  /** The city the route asks for, and the one drawn. */
  private wanted?: string;
  private drawn?: string;
  private layers?: MetroLayers;
  private context?: DetailsContext;
  private cityLoad?: AbortController;

  constructor(private readonly go: (cityId: string, replace: boolean) => void) {
    this.picker = h('select', { id: 'city-picker', 'data-testid': 'city-picker', disabled: true });
    this.picker.addEventListener('change', () => this.go(this.picker.value, false));
    this.summary = h('p', { class: 'toolbar-summary', 'aria-live': 'polite' });

    this.map = new SvgMap('Metro map');
    this.map.element.dataset.testid = 'metro-map';
    this.legend = new Legend({
      onHighlight: (lineId) => this.layers?.highlightLine(lineId),
      onPoisVisible: (visible) => this.layers?.setPoisVisible(visible),
      onLabelsVisible: (visible) => this.layers?.setLabelsVisible(visible),
    });
    this.details = new DetailsPanel(() => this.pick(null));
    this.map.setFitInsets(() => this.overlayInsets());

    this.element = h(
      'section',
      { class: 'view view-metro' },
      h('div', { class: 'toolbar' }, h('label', { class: 'field', for: 'city-picker' }, 'City'), this.picker, this.summary),
      h(
        'div',
        { class: 'map-area' },
        this.map.element,
        this.legend.element,
        this.details.element,
        mapControls(this.map),
        this.attribution,
        this.status.element,
      ),
    );
    void this.loadCities();
  }

  show(cityId: string | undefined): void {
    this.wanted = cityId;
    if (this.cities) this.openWanted();
  }

  catalogChanged(lastImport: LastImport | undefined): void {
    const touchesDrawn = !lastImport || (lastImport.kind !== 'roads' && lastImport.target === this.drawn);
    void this.loadCities(touchesDrawn);
  }

  /** Fills the picker; `reload` draws the current city again (its data changed). */
  private async loadCities(reload = false): Promise<void> {
    if (!this.cities) this.status.loading('Loading cities…');
    try {
      this.cities = await fetchCities();
    } catch (error) {
      // A failed refresh keeps the list we have; only a first load has nothing to show.
      if (!this.cities) this.status.error('Could not load the list of cities', error, () => void this.loadCities());
      return;
    }
    this.fillPicker(this.cities);
    if (reload) this.drawn = undefined;
    this.openWanted();
  }

  private fillPicker(cities: CitySummary[]): void {
    this.picker.replaceChildren(
      ...cities.map((city) => h('option', { value: city.id }, `${city.name} — ${plural(city.counts.stations, 'station')}`)),
    );
    this.picker.disabled = cities.length === 0;
    if (this.wanted) this.picker.value = this.wanted;
  }

  private openWanted(): void {
    const cities = this.cities ?? [];
    if (!this.wanted) {
      if (cities[0]) this.go(cities[0].id, true);
      else this.status.error('No cities yet', new Error('Import a city with `tourmap import manifest` and it will appear here.'));
      return;
    }
    const city = cities.find((candidate) => candidate.id === this.wanted);
    if (!city) {
      this.cityLoad?.abort();
      this.drawn = undefined;
      this.clearMap();
      this.map.element.dataset.status = 'error';
      this.status.error(`There is no city “${this.wanted}”`, new Error('Pick one of the cities in the list.'));
      return;
    }
    this.picker.value = city.id;
    document.title = `${city.name} metro · tourmap`;
    if (this.drawn !== city.id) void this.loadCity(city);
  }

  private async loadCity(summary: CitySummary): Promise<void> {
    this.cityLoad?.abort();
    const load = new AbortController();
    this.cityLoad = load;
    this.drawn = summary.id;
    this.map.element.dataset.status = 'loading';
    this.status.loading(`Loading ${summary.name}…`);
    try {
      const [city, metro, pois] = await Promise.all([
        fetchCity(summary.id, load.signal),
        fetchMetro(summary.id, load.signal),
        summary.counts.pois > 0 ? fetchPois(summary.id, load.signal) : NO_POIS,
      ]);
      if (load.signal.aborted) return;
      this.clearMap();
      // Legend and attribution first: fitting the map keeps clear of them.
      this.legend.show(metro.lines, pois.features.length, city.poi_categories);
      showAttribution(this.attribution, [...city.attribution, ...metro.attribution, ...pois.attribution]);
      const frame = frameFor(extendBBox(city.bbox, pois.features.map((poi) => poi.geometry.coordinates)));
      this.map.setFrame(frame);
      this.layers = new MetroLayers(this.map, frame, metro, pois.features, (pick) => this.pick(pick));
      this.layers.setPoisVisible(this.legend.poisVisible);
      this.layers.setLabelsVisible(this.legend.labelsVisible);
      this.context = {
        lines: new Map(metro.lines.map((line) => [line.id, line])),
        stations: metro.features.filter((f): f is StationFeature => f.properties.kind === 'station'),
        pois: pois.features,
        onPick: (pick) => this.pick(pick, true),
      };
      this.summary.textContent = [
        plural(city.counts.stations, 'station'),
        plural(metro.lines.length, 'line'),
        pois.features.length > 0 ? plural(pois.features.length, 'place') + ' of interest' : '',
      ].filter(Boolean).join(' · ');
      this.status.clear();
      this.map.element.dataset.city = city.id;
      this.map.element.dataset.status = 'ready';
    } catch (error) {
      if (isAbort(error)) return;
      this.drawn = undefined;
      this.clearMap();
      this.map.element.dataset.status = 'error';
      this.status.error(`Could not load the metro map of ${summary.name}`, error, () => void this.loadCity(summary));
    }
  }

  private clearMap(): void {
    this.layers?.destroy();
    this.layers = undefined;
    this.context = undefined;
    this.details.hide();
    this.legend.hide();
    this.summary.textContent = '';
    showAttribution(this.attribution, []);
    delete this.map.element.dataset.city;
  }

  /** The open legend covers the map's left side, the attribution its foot: fit the network beside them. */
  private overlayInsets(): Insets {
    const legend = this.legend.element;
    const left = legend.open ? legend.offsetLeft + legend.offsetWidth : 0;
    return { top: 0, right: 0, bottom: this.attribution.offsetHeight, left };
  }

  /** Shows a picked station or POI; `reveal` also moves the map to it (picked from a list). */
  private pick(pick: MetroPick | null, reveal = false): void {
    this.layers?.select(pick);
    if (!pick || !this.context) {
      this.details.hide();
      return;
    }
    if (reveal) this.layers?.reveal(pick);
    if (pick.kind === 'station') this.details.show(pick.station.properties.name, stationDetails(pick.station, this.context));
    else this.details.show(pick.poi.properties.name, poiDetails(pick.poi, this.context));
  }
}
