import { h } from './dom';

const OSM_CREDIT = '© OpenStreetMap contributors';
const MENTIONS_OSM = /openstreetmap|\bosm\b/i;

/**
 * The data credits to show for a map: the API's attribution strings, without repeats, and the
 * OpenStreetMap credit the ODbL asks for when a source is OSM data but does not spell it out.
 */
function attributionLines(sources: string[]): string[] {
  const lines = [...new Set(sources.map((source) => source.trim()).filter(Boolean))];
  if (lines.some((line) => MENTIONS_OSM.test(line)) && !lines.some((line) => line.includes(OSM_CREDIT))) {
    lines.unshift(OSM_CREDIT);
  }
  return lines;
}

export function attributionBox(): HTMLElement {
  return h('div', { class: 'attribution', 'aria-label': 'Data sources' });
}

export function showAttribution(box: HTMLElement, sources: string[]): void {
  box.replaceChildren(...attributionLines(sources).map((line) => h('p', {}, line)));
  box.hidden = box.childElementCount === 0;
}
