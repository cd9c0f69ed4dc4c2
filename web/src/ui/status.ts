import { ApiError } from '../api/client';
import { installBusyIndicator } from './busy';
import { h } from './dom';

/** What a 404 was about, from the API path asked for. */
function missingThing(path: string | undefined): string {
  if (path?.startsWith('/cities/')) return 'This city was not found.';
  if (path?.startsWith('/roads/')) return 'This road network was not found.';
  if (path?.startsWith('/crowd/')) return 'This crowd scene was not found.';
  return 'What you asked for was not found.';
}

/**
 * A plain sentence for any failure, for anyone: no status codes, no JSON (errorDetails has those,
 * for the Details section and the console). Errors made here with their own words keep them.
 */
export function describeError(error: unknown): string {
  if (!(error instanceof ApiError)) return error instanceof Error ? error.message : String(error);
  const { status } = error;
  if (status === 0) return error.code === 'network' ? 'The map service cannot be reached. Check your connection and try again.' : 'The map service sent an answer this page cannot read. Try again.';
  if (status === 404) return missingThing(error.path);
  if (status === 429 || status === 503) return 'The map service is busy. Try again in a moment.';
  if (status === 504 || status === 408) return 'The map service took too long to answer. Try again in a moment.';
  if (status === 413) return 'This request is too large for the map service.';
  if (status >= 500) return 'The map service ran into a problem. Try again later.';
  return 'The map service could not do this.';
}

/** The technical side of a failure (status, code, the server's message), or null when there is none. */
export function errorDetails(error: unknown): string | null {
  if (!(error instanceof ApiError)) return null;
  const where = error.path ? ` ${error.path}` : '';
  return `${error.status ? `HTTP ${error.status}` : 'no answer'}${where}: ${error.code}${error.field ? ` (${error.field})` : ''}: ${error.message}`;
}

/** A collapsed "Details" section with the technical side, logged to the console as well; null without one. */
export function detailsSection(error: unknown): HTMLElement | null {
  const details = errorDetails(error);
  if (details === null) return null;
  console.warn(`tourmap: ${details}`);
  return h('details', { class: 'error-details' }, h('summary', {}, 'Details'), h('code', {}, details));
}

/** The loading spinner or error box laid over a view's content. */
export class StatusOverlay {
  readonly element: HTMLDivElement;

  constructor() {
    this.element = h('div', { class: 'status-overlay', hidden: true });
    installBusyIndicator();
  }

  loading(text: string): void {
    this.element.replaceChildren(h('div', { class: 'loading', role: 'status' }, h('span', { class: 'spinner', 'aria-hidden': 'true' }), text));
    this.element.hidden = false;
  }

  error(title: string, error: unknown, retry?: () => void): void {
    const retryButton = retry ? h('button', { type: 'button', class: 'button' }, 'Try again') : null;
    retryButton?.addEventListener('click', retry!);
    this.element.replaceChildren(
      h('div', { class: 'error-box', role: 'alert' }, h('strong', {}, title), h('p', {}, describeError(error)), detailsSection(error), retryButton),
    );
    this.element.hidden = false;
  }

  clear(): void {
    this.element.hidden = true;
    this.element.replaceChildren();
  }
}
