import './styles/base.css';
import './styles/shell.css';
import './styles/map.css';
import './styles/panels.css';
import './styles/deform.css';
import './styles/metro.css';
import './styles/crowd.css';
import './styles/sheet.css';
import { EventStream } from './api/events';
import { navigate, routeHash, watchRoute, type Route, type ViewName } from './router';
import { Shell } from './ui/shell';
import { CrowdView } from './views/crowd-view';
import { DeformView } from './views/deform-view';
import { MetroView } from './views/metro-view';
import type { View } from './views/view';

const shell = new Shell(document.getElementById('app')!);

function createView(name: ViewName): View {
  switch (name) {
    case 'metro':
      return new MetroView((city, replace) => navigate({ view: 'metro', param: city }, replace));
    case 'deform':
      return new DeformView((network, replace) => navigate({ view: 'deform', param: network }, replace));
    case 'crowd':
      return new CrowdView((scene, replace) => navigate({ view: 'crowd', param: scene }, replace));
  }
}

/** Views are made on first visit and kept, so switching back keeps the map as it was. */
const views = new Map<ViewName, View>();
let current: View | undefined;

function show(route: Route): void {
  let view = views.get(route.view);
  if (!view) {
    view = createView(route.view);
    views.set(route.view, view);
  }
  if (current && current !== view) current.hide?.();
  current = view;
  if (shell.main.firstElementChild !== view.element) shell.main.replaceChildren(view.element);
  shell.setActive(route.view, routeHash(route));
  view.show(route.param);
}

new EventStream({
  onCatalogChange: (lastImport) => views.forEach((view) => view.catalogChanged(lastImport)),
  onLayoutImproved: (event) => views.forEach((view) => view.layoutImproved?.(event)),
  onStateChange: (state) => shell.setConnection(state),
}).start();

watchRoute(show);
