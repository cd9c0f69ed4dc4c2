import { h } from '../ui/dom';
import '../styles/heat-legend.css';

/**
 * The server's heat-map ramp (core/render/crowd_shaders.hpp, heat()): a cluster's fineness t
 * (0 at the root of its hierarchy, the coarsest; 1 at a leaf, full resolution; Fig. 3.11) as
 * the "jet" colours clamp(1.5 - |4t - (3, 2, 1)|, 0, 1): dark blue, blue, cyan, yellow, red,
 * dark red. The picture is lit, so what it shows is this ramp darkened on faces turned from the light.
 */
export function heatColour(t: number): [number, number, number] {
  const channel = (centre: number) => Math.min(1, Math.max(0, 1.5 - Math.abs(4 * t - centre)));
  return [channel(3), channel(2), channel(1)];
}

/** The ramp as a CSS gradient, from t = 0 (left) to 1 (right); the ramp is piecewise linear with breaks every 1/8. */
export function heatGradient(): string {
  const stops: string[] = [];
  for (let i = 0; i <= 8; i++) {
    const [r, g, b] = heatColour(i / 8).map((c) => Math.round(c * 255));
    stops.push(`rgb(${r} ${g} ${b}) ${(i / 8) * 100}%`);
  }
  return `linear-gradient(to right, ${stops.join(', ')})`;
}

/**
 * A small legend for the level-of-detail heat map, over the picture's lower left corner; shown
 * only while the heat map is on. data-testid=crowd-heat-legend.
 */
export class HeatLegend {
  readonly element: HTMLElement;

  constructor() {
    this.element = h(
      'figure',
      { class: 'crowd-heat-legend', hidden: true, 'data-testid': 'crowd-heat-legend', 'aria-label': 'Heat map legend' },
      h('figcaption', {}, 'Level of detail'),
      h('div', { class: 'crowd-heat-ramp', style: `background: ${heatGradient()}`, 'aria-hidden': 'true' }),
      h('div', { class: 'crowd-heat-labels' }, h('span', {}, 'Fewer triangles'), h('span', {}, 'Full detail')),
    );
  }

  set shown(on: boolean) {
    this.element.hidden = !on;
  }
}
