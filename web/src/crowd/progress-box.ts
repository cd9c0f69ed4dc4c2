import type { CrowdProgressMessage } from '../api/types';
import { h } from '../ui/dom';

const STAGES: Record<string, string> = {
  'loading models': 'Loading the models',
  'building hierarchy': 'Building the cluster hierarchy',
  uploading: 'Uploading to the renderer',
};

/**
 * The box in the middle of the stream while the server prepares a scene (the first time can take
 * a while: models are loaded and their cluster hierarchies built): the stage, the model and a bar.
 */
export class ProgressBox {
  readonly element: HTMLElement;
  private readonly title: HTMLElement;
  private readonly detail: HTMLElement;
  private readonly bar: HTMLProgressElement;

  constructor() {
    this.title = h('strong', {});
    this.detail = h('span', { class: 'crowd-progress-detail' });
    this.bar = h('progress', { max: 1, 'aria-label': 'Scene preparation' });
    this.element = h(
      'div',
      { class: 'crowd-progress', role: 'status', 'aria-live': 'polite', hidden: true, 'data-testid': 'crowd-progress' },
      h('span', { class: 'spinner', 'aria-hidden': 'true' }),
      h('div', { class: 'crowd-progress-text' }, this.title, this.detail, this.bar),
    );
  }

  /** A plain waiting message (connecting, waiting for the first frame). */
  waiting(text: string, detail = ''): void {
    this.title.textContent = text;
    this.detail.textContent = detail;
    this.bar.hidden = true;
    this.bar.removeAttribute('value');
    this.element.hidden = false;
    delete this.element.dataset.stage;
  }

  show(progress: CrowdProgressMessage, sceneTitle: string): void {
    this.title.textContent = `Preparing ${sceneTitle}: ${STAGES[progress.stage] ?? progress.stage}`;
    const counted = progress.total > 0 ? `${progress.done} of ${progress.total}` : '';
    this.detail.textContent = [progress.model, counted].filter(Boolean).join(' · ');
    this.bar.hidden = !(progress.total > 0);
    if (progress.total > 0) {
      this.bar.max = progress.total;
      this.bar.value = Math.min(progress.done, progress.total);
    }
    this.element.dataset.stage = progress.stage;
    this.element.hidden = false;
  }

  hide(): void {
    this.element.hidden = true;
  }
}
