import { h } from '../ui/dom';
import type { SvgMap } from './svg-map';

const BUTTON_ZOOM = 1.6;

/** The +, − and fit buttons over a map. */
export function mapControls(map: SvgMap): HTMLElement {
  const button = (label: string, title: string, className: string, action: () => void) => {
    const element = h('button', { type: 'button', class: `map-button ${className}`, title, 'aria-label': title }, label);
    element.addEventListener('click', action);
    return element;
  };
  return h(
    'div',
    { class: 'map-controls', role: 'group', 'aria-label': 'Map view' },
    button('+', 'Zoom in', 'zoom-in', () => map.zoomBy(BUTTON_ZOOM)),
    button('−', 'Zoom out', 'zoom-out', () => map.zoomBy(1 / BUTTON_ZOOM)),
    button('⤢', 'Fit the whole map', 'zoom-fit', () => map.fit()),
  );
}
