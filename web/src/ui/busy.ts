import { onBusyChange } from '../api/client';
import { h } from './dom';
import '../styles/busy.css';

/** The busy note stays at least this long once shown, so a short wait does not flicker. */
const MIN_SHOWN_MS = 1200;

let installed = false;

/**
 * A small, quiet note at the bottom of the window ("Busy, retrying…") while requests wait for a
 * busy server (429 or 503 answers the client retries, api/client.ts). Installed once, by the
 * first StatusOverlay; not an error: nothing failed yet.
 *
 * For tests: data-testid=busy-note, data-shown counts how often it appeared.
 */
export function installBusyIndicator(): void {
  if (installed) return;
  installed = true;
  const note = h(
    'div',
    { class: 'busy-note', role: 'status', 'aria-live': 'polite', hidden: true, 'data-testid': 'busy-note', 'data-shown': 0 },
    h('span', { class: 'spinner', 'aria-hidden': 'true' }),
    'Busy, retrying…',
  );
  document.body.append(note);
  let shownAt = 0;
  let hideTimer = 0;
  onBusyChange((busy) => {
    window.clearTimeout(hideTimer);
    if (busy) {
      if (note.hidden) {
        shownAt = performance.now();
        note.dataset.shown = String(Number(note.dataset.shown) + 1);
      }
      note.hidden = false;
    } else {
      hideTimer = window.setTimeout(() => (note.hidden = true), Math.max(0, MIN_SHOWN_MS - (performance.now() - shownAt)));
    }
  });
}
