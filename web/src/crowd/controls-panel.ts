import type { CrowdLimits, CrowdMode, CrowdScene } from '../api/types';
import { h } from '../ui/dom';
import { formatPoe } from './format';

/** How many rendered pixels per CSS pixel of the canvas ('device': the screen's own pixels). */
export type Resolution = 'device' | 1 | 0.5 | 0.25;

export interface CrowdSettings {
  mode: CrowdMode;
  /** Pixels of error: the screen-space error the LOD cut allows. */
  poe: number;
  heatmap: boolean;
  animate: boolean;
  resolution: Resolution;
  quality: number;
  /** Frames per second to hold while moving (lower resolution and detail); 0: always full quality. */
  smoothFps: number;
  /** Characters; undefined: the scene's default. */
  count?: number;
}

const MODE_LABELS: Record<string, { label: string; title: string }> = {
  nolod: { label: 'Full', title: 'Every person in full detail (NoLOD)' },
  vdr: { label: 'Simplify', title: 'Distant people with fewer triangles (view-dependent level of detail, VDR)' },
  'vdr+oc': { label: 'Fastest', title: 'Distant people simplified and hidden ones not drawn at all (VDR + occlusion culling)' },
};

const RESOLUTIONS: { value: Resolution; label: string }[] = [
  { value: 'device', label: 'Sharpest' },
  { value: 1, label: 'Normal' },
  { value: 0.5, label: 'Half (faster)' },
  { value: 0.25, label: 'Quarter (fastest)' },
];

/** The PoE slider spans 0.1 … 16 pixels on a log scale (within the server's limits). */
const POE_RANGE = { min: 0.1, max: 16 };
const POE_STEPS = 1000;
const DEFAULTS: CrowdSettings = { mode: 'vdr+oc', poe: 0.5, heatmap: false, animate: true, resolution: 1, quality: 75, smoothFps: 15 };

const SMOOTHNESS: { value: number; label: string }[] = [
  { value: 15, label: 'Smooth (15 fps)' },
  { value: 24, label: 'Smoother (24 fps)' },
  { value: 0, label: 'Always sharp' },
];

const significant = (value: number, digits: number) => Number(value.toPrecision(digits));

/** Mode, pixel error, heat map, animation, resolution, JPEG quality and crowd size of the Crowd view. */
export class ControlsPanel {
  readonly element: HTMLElement;
  private readonly state: CrowdSettings = { ...DEFAULTS };
  private readonly modeSwitch: HTMLElement;
  private readonly modeButtons = new Map<CrowdMode, HTMLButtonElement>();
  private readonly poe: HTMLInputElement;
  private readonly poeOutput: HTMLOutputElement;
  private readonly heatmap: HTMLInputElement;
  private readonly heatNote: HTMLElement;
  private readonly animate: HTMLInputElement;
  private readonly resolution: HTMLSelectElement;
  private readonly quality: HTMLInputElement;
  private readonly qualityOutput: HTMLOutputElement;
  private readonly count: HTMLInputElement;
  private readonly smooth: HTMLSelectElement;
  private poeRange = { ...POE_RANGE };

  constructor(private readonly onChange: () => void) {
    this.modeSwitch = h('div', { class: 'mode-switch', role: 'group', 'aria-label': 'Drawing', 'data-testid': 'crowd-mode' });
    this.poe = h('input', {
      type: 'range',
      id: 'crowd-poe',
      min: 0,
      max: POE_STEPS,
      step: 1,
      'data-testid': 'crowd-poe',
      'aria-describedby': 'crowd-poe-help',
    });
    this.poeOutput = h('output', { for: 'crowd-poe', class: 'num' });
    this.heatmap = h('input', { type: 'checkbox', 'data-testid': 'crowd-heatmap' });
    this.heatNote = h('p', { class: 'note', hidden: true }, 'Each group of people is coloured by how much detail it is drawn with, from coarse to full (a level-of-detail heat map).');
    this.animate = h('input', { type: 'checkbox', checked: true, 'data-testid': 'crowd-animate' });
    this.resolution = h(
      'select',
      { id: 'crowd-resolution', 'data-testid': 'crowd-resolution' },
      ...RESOLUTIONS.map(({ value, label }) => h('option', { value: String(value) }, label)),
    );
    this.resolution.value = String(DEFAULTS.resolution);
    this.quality = h('input', { type: 'range', id: 'crowd-quality', min: 10, max: 95, step: 1, value: DEFAULTS.quality, 'data-testid': 'crowd-quality' });
    this.qualityOutput = h('output', { for: 'crowd-quality', class: 'num' }, String(DEFAULTS.quality));
    this.smooth = h(
      'select',
      { id: 'crowd-smooth', 'data-testid': 'crowd-smooth', 'aria-describedby': 'crowd-smooth-help' },
      ...SMOOTHNESS.map(({ value, label }) => h('option', { value: String(value) }, label)),
    );
    this.smooth.value = String(DEFAULTS.smoothFps);
    this.smooth.addEventListener('change', () => {
      this.state.smoothFps = Number(this.smooth.value);
      this.onChange();
    });
    this.count = h('input', { type: 'number', id: 'crowd-count', class: 'number-input', min: 1, step: 1, 'data-testid': 'crowd-count' });

    this.setPoe(DEFAULTS.poe);
    this.poe.addEventListener('input', () => {
      this.state.poe = this.poeFromSlider();
      this.showPoe();
      this.onChange();
    });
    this.heatmap.addEventListener('change', () => {
      this.state.heatmap = this.heatmap.checked;
      this.heatNote.hidden = !this.heatmap.checked;
      this.onChange();
    });
    this.animate.addEventListener('change', () => {
      this.state.animate = this.animate.checked;
      this.onChange();
    });
    this.resolution.addEventListener('change', () => {
      const value = this.resolution.value;
      this.state.resolution = value === 'device' ? 'device' : (Number(value) as Resolution);
      this.onChange();
    });
    this.quality.addEventListener('input', () => {
      this.state.quality = Number(this.quality.value);
      this.qualityOutput.textContent = this.quality.value;
      this.onChange();
    });
    // The crowd size rebuilds the scene on the server: sent when the number is committed.
    this.count.addEventListener('change', () => {
      const value = Math.round(Number(this.count.value));
      const min = Number(this.count.min);
      const max = Number(this.count.max);
      if (this.count.value.trim() === '' || !Number.isFinite(value)) {
        this.state.count = undefined;
      } else {
        this.state.count = Math.min(max, Math.max(min, value));
        this.count.value = String(this.state.count);
      }
      this.onChange();
    });

    const slider = (label: string, input: HTMLInputElement, output: HTMLOutputElement) =>
      h('div', { class: 'slider-row' }, h('label', { for: input.id }, label), input, output);
    // What a visitor changes stays in view; the crowd size and the JPEG quality go behind Advanced.
    this.element = h(
      'div',
      { class: 'crowd-controls' },
      h('div', { class: 'field-row' }, h('span', { class: 'field', 'aria-hidden': 'true' }, 'Drawing'), this.modeSwitch),
      slider('Simplify', this.poe, this.poeOutput),
      h(
        'p',
        { class: 'note', id: 'crowd-poe-help' },
        'How far, on screen, a simplified person may stray from the full one (pixels of error, PoE). More: fewer triangles, faster.',
      ),
      h('label', { class: 'check' }, this.animate, 'Animate the crowd'),
      h('label', { class: 'check' }, this.heatmap, 'Colour by detail'),
      this.heatNote,
      h('label', { class: 'inline-field', for: 'crowd-resolution' }, 'Sharpness', this.resolution),
      h(
        'details',
        { class: 'advanced', 'data-testid': 'crowd-advanced' },
        h('summary', {}, 'Advanced'),
        h(
          'div',
          { class: 'advanced-body' },
          h('label', { class: 'inline-field', for: 'crowd-smooth' }, 'While moving', this.smooth),
          h(
            'p',
            { class: 'note', id: 'crowd-smooth-help' },
            'While you move or the crowd walks, the picture is drawn smaller and simpler to keep this frame rate; when you stop, a sharp one follows.',
          ),
          h('label', { class: 'inline-field', for: 'crowd-count' }, 'People', this.count),
          slider('JPEG quality', this.quality, this.qualityOutput),
        ),
      ),
    );
    this.setModes(['nolod', 'vdr', 'vdr+oc']);
  }

  get value(): Readonly<CrowdSettings> {
    return this.state;
  }

  /** The modes and limits the server announced. */
  configure(modes: CrowdMode[], limits: CrowdLimits): void {
    this.setModes(modes);
    this.poeRange = { min: Math.max(POE_RANGE.min, limits.poe.min), max: Math.min(POE_RANGE.max, limits.poe.max) };
    this.setPoe(this.state.poe);
    this.quality.min = String(limits.quality.min);
    this.quality.max = String(limits.quality.max);
    this.state.quality = Math.min(limits.quality.max, Math.max(limits.quality.min, this.state.quality));
    this.quality.value = String(this.state.quality);
    this.qualityOutput.textContent = this.quality.value;
  }

  /** A scene was picked: its crowd size range, and its default size. */
  setScene(scene: CrowdScene): void {
    this.count.min = String(scene.count.min);
    this.count.max = String(scene.count.max);
    this.count.value = String(scene.count.default);
    this.count.title = `${scene.count.min.toLocaleString('en')} to ${scene.count.max.toLocaleString('en')} characters`;
    this.state.count = undefined;
  }

  private setModes(modes: CrowdMode[]): void {
    this.modeButtons.clear();
    this.modeSwitch.replaceChildren(
      ...modes.map((mode) => {
        const known = MODE_LABELS[mode] ?? { label: mode.toUpperCase(), title: mode };
        const button = h('button', { type: 'button', class: 'mode-button', 'data-mode': mode, title: known.title }, known.label);
        button.addEventListener('click', () => this.setMode(mode));
        this.modeButtons.set(mode, button);
        return button;
      }),
    );
    if (!modes.includes(this.state.mode) && modes[0]) this.state.mode = modes[0];
    this.showMode();
  }

  private setMode(mode: CrowdMode): void {
    if (mode === this.state.mode) return;
    this.state.mode = mode;
    this.showMode();
    this.onChange();
  }

  private showMode(): void {
    for (const [mode, button] of this.modeButtons) button.setAttribute('aria-pressed', String(mode === this.state.mode));
    this.modeSwitch.dataset.value = this.state.mode;
  }

  private poeFromSlider(): number {
    const { min, max } = this.poeRange;
    return significant(min * (max / min) ** (Number(this.poe.value) / POE_STEPS), 3);
  }

  private setPoe(poe: number): void {
    const { min, max } = this.poeRange;
    this.state.poe = Math.min(max, Math.max(min, poe));
    this.poe.value = String(Math.round((POE_STEPS * Math.log(this.state.poe / min)) / Math.log(max / min)));
    this.showPoe();
  }

  private showPoe(): void {
    const text = `${formatPoe(this.state.poe)} px`;
    this.poeOutput.textContent = text;
    this.poe.setAttribute('aria-valuetext', text);
    this.poe.dataset.value = String(this.state.poe);
  }
}
