import { layoutQuery } from '../api/client';
import type { LayoutParams } from '../api/types';
import '../styles/export.css';
import { h } from '../ui/dom';

/** The city and layout parameters to export, or null while no city is drawn. */
export type ExportTarget = () => { cityId: string; params: LayoutParams } | null;

/** The files offered: the whole octilinear schematic drawn by the server (GET .../map.{ext}). */
const FORMATS = [
  { ext: 'svg', text: 'SVG', note: 'A3, vector, names as text', query: 'paper=a3' },
  { ext: 'pdf', text: 'PDF', note: 'A3, for print', query: 'paper=a3' },
  { ext: 'png', text: 'PNG', note: 'A3 at 200 dpi', query: 'paper=a3&dpi=200' },
] as const;

/** The address of a city's map file for a layout. */
export function mapFileUrl(cityId: string, params: LayoutParams, ext: string, query: string): string {
  return `/api/v1/cities/${encodeURIComponent(cityId)}/map.${ext}?${query}&${layoutQuery(params)}`;
}

/**
 * The Metro view's download control: a menu of the map's files (SVG, PDF, PNG) for the city
 * and layout parameters `target` gives when it opens, as the server draws them (same line
 * order, names, symbols, legend and attribution as the octilinear map here).
 */
export function exportButton(target: ExportTarget): HTMLDetailsElement {
  const links = FORMATS.map(({ ext, text, note }) =>
    h('a', { class: 'export-link', 'data-format': ext, role: 'menuitem' }, h('strong', {}, text), ` ${note}`),
  );
  const menu = h('details', { class: 'export-menu', 'data-testid': 'map-export' });
  menu.append(
    h('summary', { class: 'button button-quiet', title: 'Download the octilinear map as a file' }, 'Download'),
    h('div', { class: 'export-list', role: 'menu' }, ...links),
  );
  const refresh = () => {
    const current = target();
    FORMATS.forEach(({ ext, query }, i) => {
      const link = links[i]!;
      if (!current) {
        link.removeAttribute('href');
        return;
      }
      link.href = mapFileUrl(current.cityId, current.params, ext, query);
      link.download = `${current.cityId}-metro-a3.${ext}`; // the name the server gives it
    });
  };
  menu.addEventListener('toggle', refresh);
  // Chosen: the menu closes (the browser downloads the file).
  for (const link of links) link.addEventListener('click', () => (menu.open = false));
  return menu;
}
