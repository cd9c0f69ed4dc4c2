import { h } from './dom';

/** What a WantedPicker does once it knows both the list and the id the route asks for. */
export interface WantedPickerOptions<T> {
  /** The select's id and data-testid. */
  id: string;
  /** An option's text. */
  label: (item: T) => string;
  /** The user picked `id` in the list, or (replace) the route asked for nothing and the first is taken. */
  go: (id: string, replace: boolean) => void;
  /** The wanted item is in the list: show it (the view skips it when it is drawn already). */
  open: (item: T) => void;
  /** The route asks for an id the list does not have. */
  missing: (id: string) => void;
  /** The route asks for nothing and the list is empty. */
  empty: () => void;
}

/**
 * A picker of the items a view shows (cities, road networks, crowd scenes) that opens the one
 * the URL asks for once both are known: the route's id can come before the list or after it.
 */
export class WantedPicker<T extends { id: string }> {
  readonly element: HTMLSelectElement;
  private list?: T[];
  private wantedId?: string;

  constructor(private readonly options: WantedPickerOptions<T>) {
    this.element = h('select', { id: options.id, 'data-testid': options.id, disabled: true });
    this.element.addEventListener('change', () => options.go(this.element.value, false));
  }

  /** The list, once loaded. */
  get items(): T[] | undefined {
    return this.list;
  }

  /** The id the route asks for (undefined: none). */
  get wanted(): string | undefined {
    return this.wantedId;
  }

  /** The route's id; opened now when the list is there (and `open`), else when it comes. */
  want(id: string | undefined, open = true): void {
    this.wantedId = id;
    if (this.list && open) this.openWanted();
  }

  /** Fills the list; `open` then opens the wanted item. */
  setItems(items: T[], open = true): void {
    this.list = items;
    this.element.replaceChildren(...items.map((item) => h('option', { value: item.id }, this.options.label(item))));
    this.element.disabled = items.length === 0;
    if (this.wantedId) this.element.value = this.wantedId;
    if (open) this.openWanted();
  }

  /** Opens the wanted item: the first one when none is asked for, or says it is missing. */
  openWanted(): void {
    const items = this.list ?? [];
    if (!this.wantedId) {
      if (items[0]) this.options.go(items[0].id, true);
      else this.options.empty();
      return;
    }
    const item = items.find((candidate) => candidate.id === this.wantedId);
    if (!item) {
      this.options.missing(this.wantedId);
      return;
    }
    this.element.value = item.id;
    this.options.open(item);
  }
}
