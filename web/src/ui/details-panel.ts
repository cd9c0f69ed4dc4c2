import { h } from './dom';

/** The side panel (a bottom sheet on phones) that shows what was picked on the map. */
export class DetailsPanel {
  readonly element: HTMLElement;
  private readonly title: HTMLHeadingElement;
  private readonly body: HTMLDivElement;

  constructor(onClose: () => void) {
    this.title = h('h2', { class: 'details-title' });
    this.body = h('div', { class: 'details-body' });
    const close = h('button', { type: 'button', class: 'details-close', 'aria-label': 'Close details' }, '×');
    close.addEventListener('click', onClose);
    this.element = h(
      'aside',
      { class: 'details-panel', hidden: true, 'aria-live': 'polite', 'data-testid': 'details' },
      h('header', { class: 'details-header' }, this.title, close),
      this.body,
    );
  }

  show(title: string, content: Node[]): void {
    this.title.textContent = title;
    this.body.replaceChildren(...content);
    this.element.hidden = false;
    this.body.scrollTop = 0;
  }

  hide(): void {
    this.element.hidden = true;
  }
}
