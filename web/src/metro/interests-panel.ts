import { interestsQuery, type CityCategory, type InterestWeights } from '../api/interests';
import '../styles/interests-walk.css';
import { h } from '../ui/dom';

/** The three steps a tourist picks from, and the weight each sends (only ratios matter). */
const CHOICES = [
  { weight: 0, text: 'Skip', title: 'Leave these out of the top picks and give them no room on the map' },
  { weight: 1, text: 'Normal', title: 'As the map weighs them anyway' },
  { weight: 5, text: 'Love it', title: 'Give these more room on the map and put them first among the top picks' },
] as const;
/** Categories listed before "More". */
const SHOWN = 12;
/** Quiet time after a change before the map asks for a new layout (several quick taps: one request). */
const DEBOUNCE_MS = 400;

const storageKey = (cityId: string) => `tourmap.interests.${cityId}`;
const capitalised = (text: string) => text.charAt(0).toUpperCase() + text.slice(1);

/** The stored choice of a city, only for categories it has and weights the panel offers. */
function loadStored(cityId: string, categories: CityCategory[]): InterestWeights {
  const known = new Set(categories.map((category) => category.id));
  const offered = new Set<number>(CHOICES.map((choice) => choice.weight));
  try {
    const stored = JSON.parse(window.localStorage.getItem(storageKey(cityId)) ?? '{}') as unknown;
    if (!stored || typeof stored !== 'object') return {};
    return Object.fromEntries(
      Object.entries(stored as Record<string, unknown>).filter(
        (entry): entry is [string, number] => known.has(entry[0]) && typeof entry[1] === 'number' && offered.has(entry[1]) && entry[1] !== 1,
      ),
    );
  } catch {
    return {}; // unreadable or blocked storage: the default
  }
}

function store(cityId: string, weights: InterestWeights): void {
  try {
    if (Object.keys(weights).length === 0) window.localStorage.removeItem(storageKey(cityId));
    else window.localStorage.setItem(storageKey(cityId), JSON.stringify(weights));
  } catch {
    // private mode or full storage: the choice lasts for this visit only
  }
}

/**
 * "Your interests": the city's POI categories (most frequent first, the first 12 and the rest
 * behind "More"), each Skip / Normal / Love it (weights 0 / 1 / 5), and Reset. A change is
 * reported after a short quiet time (`onChange`), with `query` the new `interests` parameter
 * ('' for the default map). Remembered per city in localStorage. Hidden for a city with fewer
 * than two categories (there is nothing to weigh one against). The element reports
 * data-interests (the parameter) for tests.
 */
export class InterestsPanel {
  readonly element: HTMLDetailsElement;
  private readonly list: HTMLUListElement;
  private readonly more: HTMLButtonElement;
  private readonly reset: HTMLButtonElement;
  private readonly note: HTMLParagraphElement;
  private cityId?: string;
  private categories: CityCategory[] = [];
  private weights: InterestWeights = {};
  private showAll = false;
  private timer = 0;
  /** The parameter the map was last told about. */
  private applied = '';

  constructor(private readonly onChange: (query: string) => void) {
    this.list = h('ul', { class: 'interests-list' });
    this.more = h('button', { type: 'button', class: 'interests-more' });
    this.more.addEventListener('click', () => {
      this.showAll = !this.showAll;
      this.render();
    });
    this.reset = h('button', { type: 'button', class: 'interests-reset', 'data-testid': 'interests-reset' }, 'Reset');
    this.reset.addEventListener('click', () => this.set({}));
    this.note = h('p', { class: 'interests-note', 'aria-live': 'polite' });
    this.element = h(
      'details',
      { class: 'interests', open: true, hidden: true, 'data-testid': 'interests' },
      h('summary', {}, 'Your interests'),
      h('p', { class: 'interests-hint' }, 'What would you like to see? The map makes room for what you love.'),
      this.list,
      this.note,
      h('div', { class: 'interests-actions' }, this.more, this.reset),
    );
  }

  /** The `interests` parameter of the current choice ('' : the default map). */
  get query(): string {
    return this.categories.length >= 2 ? interestsQuery(this.weights) : '';
  }

  /** Shows the city's categories with its remembered choice (applied at once: no onChange). */
  show(cityId: string, categories: CityCategory[]): void {
    window.clearTimeout(this.timer);
    this.cityId = cityId;
    this.categories = categories;
    this.weights = loadStored(cityId, categories);
    this.showAll = false;
    this.note.textContent = '';
    this.applied = this.query;
    this.element.hidden = categories.length < 2;
    this.render();
  }

  hide(): void {
    window.clearTimeout(this.timer);
    this.cityId = undefined;
    this.categories = [];
    this.weights = {};
    this.applied = '';
    this.element.hidden = true;
    delete this.element.dataset.interests;
  }

  private choose(category: string, weight: number): void {
    const next = { ...this.weights };
    if (weight === 1) delete next[category];
    else next[category] = weight;
    // The server refuses a map with every kind of place left out.
    if (this.categories.every((c) => next[c.id] === 0)) {
      this.note.textContent = 'Keep at least one kind of place.';
      return;
    }
    this.set(next);
  }

  private set(weights: InterestWeights): void {
    if (!this.cityId) return;
    this.weights = weights;
    this.note.textContent = '';
    store(this.cityId, weights);
    this.render();
    window.clearTimeout(this.timer);
    this.timer = window.setTimeout(() => {
      const query = this.query;
      if (query === this.applied) return;
      this.applied = query;
      this.onChange(query);
    }, DEBOUNCE_MS);
  }

  private render(): void {
    const shown = this.showAll ? this.categories : this.categories.slice(0, SHOWN);
    this.list.replaceChildren(...shown.map((category) => this.row(category)));
    const hiddenCount = this.categories.length - SHOWN;
    this.more.hidden = hiddenCount <= 0;
    this.more.textContent = this.showAll ? 'Fewer' : `More (${hiddenCount})`;
    this.reset.disabled = Object.keys(this.weights).length === 0;
    this.element.dataset.interests = this.query;
  }

  private row(category: CityCategory): HTMLLIElement {
    const current = this.weights[category.id] ?? 1;
    const name = capitalised(category.id);
    const buttons = CHOICES.map(({ weight, text, title }) => {
      const button = h(
        'button',
        { type: 'button', class: 'segment', 'data-weight': weight, 'aria-pressed': String(weight === current), title },
        text,
      );
      button.addEventListener('click', () => this.choose(category.id, weight));
      return button;
    });
    return h(
      'li',
      { class: 'interest', 'data-category': category.id },
      h('span', { class: 'interest-name' }, name, h('span', { class: 'interest-count' }, ` ${category.count}`)),
      h('div', { class: 'segmented interest-choice', role: 'group', 'aria-label': `${name}: how much you want to see them` }, ...buttons),
    );
  }
}
