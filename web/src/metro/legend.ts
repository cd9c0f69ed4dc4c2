import type { MetroLine } from '../api/types';
import { h } from '../ui/dom';
import { lineCasing, sortLines, swatchBackground } from './lines';

export interface LegendHandlers {
  onHighlight(lineId: string | null): void;
  onPoisVisible(visible: boolean): void;
  onLabelsVisible(visible: boolean): void;
}


/**
 * The map key: one button per line (pressing one highlights that line) and switches for the
 * POI markers and station names. It sits in the controls panel (a bottom sheet on phones), not over the map.
 */
export class Legend {
  readonly element: HTMLDetailsElement;
  private readonly list: HTMLUListElement;
  private readonly summary: HTMLElement;
  private readonly poiToggle: HTMLLabelElement;
  private readonly poiCheckbox: HTMLInputElement;
  private readonly labelCheckbox: HTMLInputElement;
  private highlighted: string | null = null;

  constructor(private readonly handlers: LegendHandlers) {
    this.summary = h('summary', {}, 'Lines');
    this.list = h('ul', { class: 'legend-lines' });
    this.poiCheckbox = h('input', { type: 'checkbox', checked: true });
    this.poiCheckbox.addEventListener('change', () => handlers.onPoisVisible(this.poiCheckbox.checked));
    this.poiToggle = h('label', { class: 'legend-toggle' }, this.poiCheckbox);
    this.labelCheckbox = h('input', { type: 'checkbox', checked: true });
    this.labelCheckbox.addEventListener('change', () => handlers.onLabelsVisible(this.labelCheckbox.checked));
    this.element = h(
      'details',
      { class: 'legend', open: true, hidden: true, 'data-testid': 'legend' },
      this.summary,
      this.list,
      h('div', { class: 'legend-toggles' }, this.poiToggle, h('label', { class: 'legend-toggle' }, this.labelCheckbox, 'Station names')),
    );
  }

  show(lines: MetroLine[], poiCount: number, poiCategories: string[]): void {
    this.element.hidden = false;
    this.highlighted = null;
    this.summary.textContent = `Lines (${lines.length})`;
    this.list.replaceChildren(...sortLines(lines).map((line) => this.lineItem(line)));
    this.poiToggle.hidden = poiCount === 0;
    const what = poiCategories.length === 1 ? categoryPlural(poiCategories[0]!) : 'Places of interest';
    this.poiToggle.replaceChildren(this.poiCheckbox, h('span', { class: 'poi-swatch', 'aria-hidden': 'true' }), `${what} (${poiCount})`);
  }

  /** Hidden while no city is drawn. */
  hide(): void {
    this.element.hidden = true;
  }

  get poisVisible(): boolean {
    return this.poiCheckbox.checked;
  }

  get labelsVisible(): boolean {
    return this.labelCheckbox.checked;
  }

  private lineItem(line: MetroLine): HTMLLIElement {
    const button = h(
      'button',
      { type: 'button', class: 'legend-line', 'aria-pressed': 'false', 'data-line': line.id, title: `Highlight ${line.label}` },
      h('span', { class: lineCasing(line) ? 'swatch cased' : 'swatch', style: `background:${swatchBackground(line)}`, 'aria-hidden': 'true' }),
      line.label,
    );
    button.addEventListener('click', () => {
      this.highlighted = this.highlighted === line.id ? null : line.id;
      for (const other of this.list.querySelectorAll('.legend-line')) {
        other.setAttribute('aria-pressed', String(other.getAttribute('data-line') === this.highlighted));
      }
      this.handlers.onHighlight(this.highlighted);
    });
    return h('li', {}, button);
  }
}

/** "sight" -> "Sights", "museum" -> "Museums". */
function categoryPlural(category: string): string {
  const capitalised = category.charAt(0).toUpperCase() + category.slice(1);
  return capitalised.endsWith('s') ? capitalised : `${capitalised}s`;
}
