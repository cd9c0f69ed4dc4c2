import { h } from '../ui/dom';
import { upcomingPanel } from './upcoming';
import type { View } from './view';

/** The Crowd view: not served yet, so it only says what it will do. */
export class CrowdView implements View {
  readonly element = h(
    'section',
    { class: 'view view-crowd' },
    upcomingPanel(
      'Crowd: live crowd scenes',
      'See how busy a place is as an animated scene of people. The server does not render crowds yet.',
      [
        'The server renders crowd scenes, people moving through a place, on its own machine.',
        'It streams the rendered frames to this page over a WebSocket, so the browser only has to show them.',
      ],
    ),
  );

  show(): void {
    document.title = 'Crowd · tourmap';
  }

  catalogChanged(): void {
    // Nothing here depends on the imported data yet.
  }
}
