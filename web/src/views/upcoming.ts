import { h } from '../ui/dom';

/** The notice for a view the server cannot serve yet, listing what it will do. */
export function upcomingPanel(title: string, summary: string, plans: string[]): HTMLElement {
  return h(
    'section',
    { class: 'upcoming', 'data-testid': 'upcoming' },
    h('p', { class: 'badge' }, 'Coming in a later release'),
    h('h1', {}, title),
    h('p', { class: 'upcoming-summary' }, summary),
    h('h2', {}, 'What this view will do'),
    h('ul', {}, ...plans.map((plan) => h('li', {}, plan))),
  );
}
