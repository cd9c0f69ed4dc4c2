import { describeError, detailsSection } from './status';
import { h } from './dom';

/**
 * An error box over the top of a map that does not block it (a failed layer, say): a title,
 * the reason, an optional "Try again" and a close button. One at a time; `key` lets a later
 * success clear only its own error.
 */
export class MapNotice {
  readonly element: HTMLElement;
  private key?: string;

  constructor() {
    this.element = h('div', { class: 'map-notice', role: 'alert', hidden: true, 'data-testid': 'map-notice' });
  }

  error(key: string, title: string, error: unknown, retry?: () => void): void {
    this.key = key;
    const close = h('button', { type: 'button', class: 'map-notice-close', 'aria-label': 'Close' }, '×');
    close.addEventListener('click', () => this.clear());
    const retryButton = retry ? h('button', { type: 'button', class: 'button' }, 'Try again') : null;
    retryButton?.addEventListener('click', () => {
      this.clear();
      retry!();
    });
    this.element.replaceChildren(h('strong', {}, title), close, h('p', {}, describeError(error)), ...[detailsSection(error), retryButton].filter((e) => e !== null));
    this.element.dataset.key = key;
    this.element.hidden = false;
  }

  /** Hides the box; with a key, only if it shows that key's error. */
  clear(key?: string): void {
    if (key !== undefined && key !== this.key) return;
    this.key = undefined;
    this.element.hidden = true;
    this.element.replaceChildren();
    delete this.element.dataset.key;
  }
}
