import type { ConnectionState } from '../api/events';
import type { ViewName } from '../router';
import { h } from './dom';

const NAV: { view: ViewName; label: string }[] = [
  { view: 'metro', label: 'Metro' },
  { view: 'deform', label: 'Deform' },
  { view: 'crowd', label: 'Crowd' },
];

const CONNECTION_TEXT: Record<ConnectionState, string> = {
  connecting: 'Connecting…',
  live: 'Live',
  offline: 'Offline, reconnecting…',
};

/** The page frame: header with the product name, view navigation and server connection state. */
export class Shell {
  readonly main: HTMLElement;
  private readonly links = new Map<ViewName, HTMLAnchorElement>();
  private readonly connection: HTMLElement;

  constructor(root: HTMLElement) {
    const logo = h('img', { src: '/favicon.svg', alt: '', width: 26, height: 26 });
    const nav = h('nav', { class: 'nav', 'aria-label': 'Views' });
    for (const { view, label } of NAV) {
      const link = h('a', { href: `#/${view}`, 'data-view': view }, label);
      this.links.set(view, link);
      nav.append(link);
    }
    this.connection = h('span', { class: 'connection', 'data-state': 'connecting', role: 'status' });
    this.main = h('main', { class: 'app-main' });
    root.replaceChildren(
      h('header', { class: 'app-header' }, h('a', { class: 'brand', href: '#/metro', 'aria-label': 'tourmap: home' }, logo, h('span', {}, 'tourmap')), nav, this.connection),
      this.main,
    );
    this.setConnection('connecting');
  }

  /** Marks the current view; `hash` becomes that view's link, so coming back keeps the city. */
  setActive(view: ViewName, hash: string): void {
    for (const [name, link] of this.links) {
      if (name === view) link.setAttribute('aria-current', 'page');
      else link.removeAttribute('aria-current');
    }
    this.links.get(view)?.setAttribute('href', hash);
  }

  setConnection(state: ConnectionState): void {
    this.connection.dataset.state = state;
    this.connection.title = state === 'live' ? 'Connected: the city list updates when data is imported' : CONNECTION_TEXT[state];
    this.connection.replaceChildren(h('span', { class: 'connection-text' }, CONNECTION_TEXT[state]));
  }
}
