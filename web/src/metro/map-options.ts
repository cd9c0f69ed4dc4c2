import type { LayoutLengths, LayoutSolverKind } from '../api/types';
import { h } from '../ui/dom';

export type MapMode = 'geographic' | 'octilinear';
export type PoiMode = 'clusters' | 'all';

export interface MapOptionsState {
  mode: MapMode;
  lengths: LayoutLengths;
  solver: LayoutSolverKind;
  heat: boolean;
  grid: boolean;
  /** The streets warped into the layout, under the octilinear map (when the city has a road network). */
  roads: boolean;
  pois: PoiMode;
}

export interface MapOptionsHandlers {
  onMode(mode: MapMode): void;
  onLayoutParams(): void;
  onHeat(visible: boolean): void;
  onGrid(visible: boolean): void;
  onRoads(visible: boolean): void;
  onPoiMode(mode: PoiMode): void;
}

function segmented<T extends string>(
  label: string,
  testid: string,
  choices: { value: T; text: string; title: string }[],
  onPick: (value: T) => void,
): { element: HTMLElement; set(value: T): void } {
  const buttons = choices.map(({ value, text, title }) => {
    const button = h('button', { type: 'button', class: 'segment', 'data-value': value, 'aria-pressed': 'false', title }, text);
    button.addEventListener('click', () => onPick(value));
    return button;
  });
  return {
    element: h('div', { class: 'segmented', role: 'group', 'aria-label': label, 'data-testid': testid }, ...buttons),
    set(value: T) {
      for (const button of buttons) button.setAttribute('aria-pressed', String(button.dataset.value === value));
    },
  };
}

/**
 * The Metro view's map switches in the toolbar: geographic or octilinear (with the layout's
 * edge lengths and solver), the visual worth heat map, the warp mesh, and POIs as clusters or
 * all of them.
 */
export class MapOptions {
  readonly element: HTMLElement;
  /** The engineering switches (edge lengths, solver, warp grid), for the Advanced disclosure. */
  readonly advanced: HTMLElement;
  readonly state: MapOptionsState = {
    mode: 'geographic',
    lengths: 'visual-worth',
    solver: 'auto',
    heat: false,
    grid: false,
    roads: true,
    pois: 'clusters',
  };
  private readonly mode;
  private readonly poiMode;
  private readonly lengths: HTMLSelectElement;
  private readonly solver: HTMLSelectElement;
  private readonly heat: HTMLInputElement;
  private readonly heatGroup: HTMLElement;
  private readonly grid: HTMLInputElement;
  private readonly roads: HTMLInputElement;
  private readonly roadsGroup: HTMLElement;
  private readonly poiGroup: HTMLElement;

  constructor(handlers: MapOptionsHandlers) {
    this.mode = segmented<MapMode>(
      'Layout',
      'mode-switch',
      [
        { value: 'geographic', text: 'Geographic', title: 'Stations and tracks where they really are' },
        { value: 'octilinear', text: 'Schematic', title: 'A tidy metro diagram with the sights moved along with it (the octilinear layout)' },
      ],
      (mode) => {
        if (mode === this.state.mode) return;
        this.setMode(mode);
        handlers.onMode(mode);
      },
    );
    this.lengths = h(
      'select',
      { id: 'layout-lengths', 'data-testid': 'layout-lengths', title: 'Edge lengths of the octilinear layout' },
      h('option', { value: 'visual-worth' }, 'visual worth (more room near sights)'),
      h('option', { value: 'uniform' }, 'uniform'),
    );
    this.solver = h(
      'select',
      {
        id: 'layout-solver',
        'data-testid': 'layout-solver',
        title: 'Layout solver: auto draws the fast layout at once, then the MIP polish if it is better',
      },
      h('option', { value: 'auto' }, 'auto'),
      h('option', { value: 'fast' }, 'fast'),
      h('option', { value: 'mip' }, 'MIP (slow)'),
    );
    const layoutChanged = () => {
      this.state.lengths = this.lengths.value as LayoutLengths;
      this.state.solver = this.solver.value as LayoutSolverKind;
      handlers.onLayoutParams();
    };
    this.lengths.addEventListener('change', layoutChanged);
    this.solver.addEventListener('change', layoutChanged);

    this.heat = h('input', { type: 'checkbox', 'data-testid': 'heat-toggle' });
    this.heat.addEventListener('change', () => {
      this.state.heat = this.heat.checked;
      handlers.onHeat(this.heat.checked);
    });
    this.heatGroup = h(
      'label',
      { class: 'option-inline check-inline', title: 'Where the sights worth seeing are (the visual worth heat map)' },
      this.heat,
      'Where the sights are',
    );
    this.grid = h('input', { type: 'checkbox', 'data-testid': 'grid-toggle' });
    this.grid.addEventListener('change', () => {
      this.state.grid = this.grid.checked;
      handlers.onGrid(this.grid.checked);
    });
    this.roads = h('input', { type: 'checkbox', 'data-testid': 'roads-toggle', checked: true });
    this.roads.addEventListener('change', () => {
      this.state.roads = this.roads.checked;
      handlers.onRoads(this.roads.checked);
    });
    this.roadsGroup = h(
      'label',
      { class: 'option-inline check-inline', title: 'The streets warped into the octilinear layout, drawn faintly under it when you zoom in' },
      this.roads,
      'Streets under the diagram',
    );
    this.poiMode = segmented<PoiMode>(
      'Sights',
      'poi-mode',
      [
        { value: 'clusters', text: 'Top picks', title: 'The best-known sights in view, grouped (clusters)' },
        { value: 'all', text: 'All', title: 'Every place of interest' },
      ],
      (mode) => {
        this.state.pois = mode;
        this.poiMode.set(mode);
        handlers.onPoiMode(mode);
      },
    );
    this.poiGroup = h('div', { class: 'option-row' }, h('span', { class: 'field', 'aria-hidden': 'true' }, 'Sights'), this.poiMode.element);

    this.element = h(
      'div',
      { class: 'map-options', 'data-testid': 'map-options' },
      h('div', { class: 'option-row' }, h('span', { class: 'field', 'aria-hidden': 'true' }, 'Layout'), this.mode.element),
      this.poiGroup,
      this.heatGroup,
      this.roadsGroup,
    );
    this.advanced = h(
      'div',
      { class: 'map-options map-options-advanced' },
      h('label', { class: 'option-row', for: 'layout-lengths' }, h('span', { class: 'field' }, 'Lengths'), this.lengths),
      h('label', { class: 'option-row', for: 'layout-solver' }, h('span', { class: 'field' }, 'Solver'), this.solver),
      h('label', { class: 'option-inline check-inline', title: 'The mesh that shows how the layout moved space around' }, this.grid, 'Warp grid'),
    );
    this.setMode('geographic');
    this.poiMode.set(this.state.pois);
  }

  /** Shows a mode without asking for it (a failed layout falls back to geographic). */
  setMode(mode: MapMode): void {
    this.state.mode = mode;
    this.mode.set(mode);
    this.element.dataset.mode = mode;
  }

  /** Shows the parameters of the layout drawn (after asking for another one failed). */
  setLayoutParams(lengths: LayoutLengths, solver: LayoutSolverKind): void {
    this.state.lengths = lengths;
    this.state.solver = solver;
    this.lengths.value = lengths;
    this.solver.value = solver;
  }

  /**
   * The streets switch only for a city with a road network (a 404 for its layout's roads hides
   * it); unknown until asked, it is offered.
   */
  setHasRoads(has: boolean): void {
    this.roadsGroup.hidden = !has;
  }

  /**
   * The places switch and the heat map (the visual worth of the city's POIs, eq. 5.1) only
   * mean something for a city with POIs: elsewhere they are not offered.
   */
  setHasPois(has: boolean): void {
    this.poiGroup.hidden = !has;
    this.heatGroup.hidden = !has;
    if (!has && this.heat.checked) {
      this.heat.checked = false;
      this.state.heat = false;
    }
  }
}
