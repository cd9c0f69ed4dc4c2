import { h } from './dom';

/** Below this width the controls are a bottom sheet over a full-screen map (see sheet.css). */
export const PHONE_WIDTH = '(max-width: 720px)';

export interface IntroText {
  /** What the view shows, in a tourist's words. */
  title: string;
  text: string;
  /** One thing to try first. */
  tryThis: string;
}

const seenKey = (view: string) => `tourmap.intro.${view}`;

function introSeen(view: string): boolean {
  try {
    return window.localStorage.getItem(seenKey(view)) === 'seen';
  } catch {
    return false; // storage blocked: the introduction shows each visit
  }
}

function rememberIntro(view: string): void {
  try {
    window.localStorage.setItem(seenKey(view), 'seen');
  } catch {
    // storage blocked: nothing to remember it in
  }
}

const isPhone = () => window.matchMedia(PHONE_WIDTH).matches;

/**
 * A view's controls: a side panel on desktop, a bottom sheet on phones (folded to its bar by
 * default, so the map fills the screen). The top of it holds the view's one-screen
 * introduction, shown on the first visit (remembered in localStorage) and again from the "?"
 * button. The element keeps `extraClass` (the view's own panel class) and reports data-open.
 */
export class ControlSheet {
  readonly element: HTMLElement;
  readonly body: HTMLElement;
  private readonly handle: HTMLButtonElement;
  private readonly intro: HTMLElement;
  private readonly introHeading: HTMLElement;

  constructor(private readonly view: string, label: string, intro: IntroText, extraClass: string, content: (HTMLElement | null)[]) {
    const bodyId = `sheet-body-${view}`;
    this.handle = h(
      'button',
      { type: 'button', class: 'sheet-handle', 'aria-expanded': 'false', 'aria-controls': bodyId },
      h('span', { class: 'sheet-grip', 'aria-hidden': 'true' }),
      h('span', { class: 'sheet-label' }, label),
    );
    this.handle.addEventListener('click', () => this.setOpen(this.element.dataset.open !== 'true'));
    const help = h('button', { type: 'button', class: 'help-button', 'aria-label': `About this view: ${intro.title}`, title: 'What is this?' }, '?');
    help.addEventListener('click', () => this.showIntro(true));

    this.introHeading = h('h2', { class: 'intro-title', tabindex: -1 }, intro.title);
    const close = h('button', { type: 'button', class: 'button intro-close' }, 'Got it');
    close.addEventListener('click', () => this.dismissIntro());
    this.intro = h(
      'section',
      { class: 'intro', 'aria-label': 'Introduction', 'data-testid': `intro-${view}`, hidden: true },
      this.introHeading,
      h('p', {}, intro.text),
      h('p', { class: 'intro-try' }, h('strong', {}, 'Try this: '), intro.tryThis),
      close,
    );
    this.body = h('div', { class: 'sheet-body', id: bodyId }, this.intro, ...content);
    this.element = h(
      'aside',
      { class: `sheet view-side ${extraClass}`, 'aria-label': label, 'data-open': 'false', 'data-testid': 'control-sheet' },
      h('div', { class: 'sheet-bar' }, this.handle, h('span', { class: 'sheet-title' }, label), help),
      this.body,
    );
    if (!introSeen(view)) this.showIntro(false);
  }

  /** Unfolds (or folds) the sheet; on desktop it is always unfolded. */
  setOpen(open: boolean): void {
    this.element.dataset.open = String(open);
    this.handle.setAttribute('aria-expanded', String(open));
  }

  private showIntro(focus: boolean): void {
    this.intro.hidden = false;
    this.setOpen(true);
    if (focus) {
      this.body.scrollTop = 0;
      this.introHeading.focus();
    }
  }

  private dismissIntro(): void {
    this.intro.hidden = true;
    rememberIntro(this.view);
    if (isPhone()) {
      this.setOpen(false);
      this.handle.focus();
    }
  }
}
