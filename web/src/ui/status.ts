import { ApiError } from '../api/client';
import { h } from './dom';

/** A readable sentence for any failure, with the API's error code where there is one. */
export function describeError(error: unknown): string {
  if (error instanceof ApiError) {
    return error.status === 0 ? error.message : `${error.message} (HTTP ${error.status}, ${error.code})`;
  }
  return error instanceof Error ? error.message : String(error);
}

/** The loading spinner or error box laid over a view's content. */
export class StatusOverlay {
  readonly element: HTMLDivElement;

  constructor() {
    this.element = h('div', { class: 'status-overlay', hidden: true });
  }

  loading(text: string): void {
    this.element.replaceChildren(h('div', { class: 'loading', role: 'status' }, h('span', { class: 'spinner', 'aria-hidden': 'true' }), text));
    this.element.hidden = false;
  }

  error(title: string, error: unknown, retry?: () => void): void {
    const retryButton = retry ? h('button', { type: 'button', class: 'button' }, 'Try again') : null;
    retryButton?.addEventListener('click', retry!);
    this.element.replaceChildren(
      h('div', { class: 'error-box', role: 'alert' }, h('strong', {}, title), h('p', {}, describeError(error)), retryButton),
    );
    this.element.hidden = false;
  }

  clear(): void {
    this.element.hidden = true;
    this.element.replaceChildren();
  }
}
