/** Hash routes: #/metro, #/metro/{city}, #/deform, #/deform/{network}, #/crowd, #/crowd/{scene}. */
const VIEW_NAMES = ['metro', 'deform', 'crowd'] as const;
export type ViewName = (typeof VIEW_NAMES)[number];

export interface Route {
  view: ViewName;
  /** The city, road network or crowd scene the view shows. */
  param?: string;
}

const DEFAULT_ROUTE: Route = { view: 'metro' };

function parseHash(hash: string): Route | null {
  const [view, param, ...rest] = hash.replace(/^#\/?/, '').split('/');
  if (rest.length > 0 || !VIEW_NAMES.includes(view as ViewName)) return null;
  return { view: view as ViewName, param: param ? decodeURIComponent(param) : undefined };
}

export function routeHash(route: Route): string {
  return `#/${route.view}${route.param ? `/${encodeURIComponent(route.param)}` : ''}`;
}

/** Goes to a route; `replace` rewrites the current history entry instead of adding one. */
export function navigate(route: Route, replace = false): void {
  const hash = routeHash(route);
  if (hash === window.location.hash) return;
  if (replace) {
    history.replaceState(null, '', hash);
    window.dispatchEvent(new HashChangeEvent('hashchange'));
  } else {
    window.location.hash = hash;
  }
}

/** Calls the listener with the current route now and on every change; fixes unknown hashes. */
export function watchRoute(listener: (route: Route) => void): void {
  const current = () => {
    const route = parseHash(window.location.hash);
    if (route) listener(route);
    else navigate(DEFAULT_ROUTE, true);
  };
  window.addEventListener('hashchange', current);
  current();
}
