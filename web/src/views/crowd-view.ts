import { fetchCrowdScenes } from '../api/client';
import type { CrowdScene, CrowdScenesResponse, CrowdServerMessage, CrowdViewMessage, LastImport } from '../api/types';
import { ControlsPanel } from '../crowd/controls-panel';
import { showModelCredits } from '../crowd/credits';
import { formatCount } from '../crowd/format';
import { FrameDecoder, type DecodedFrame } from '../crowd/frame-decoder';
import { HeatLegend } from '../crowd/heat-legend';
import { OrbitCamera } from '../crowd/orbit-camera';
import { ProgressBox } from '../crowd/progress-box';
import { StatsOverlay } from '../crowd/stats-overlay';
import { StreamCanvas } from '../crowd/stream-canvas';
import { CLOSE_POLICY, CrowdStream, type StreamClose, type StreamState } from '../crowd/stream-client';
import { h } from '../ui/dom';
import { ControlSheet } from '../ui/sheet';
import { MapNotice } from '../ui/notice';
import { StatusOverlay } from '../ui/status';
import { WantedPicker } from '../ui/wanted-picker';
import type { View } from './view';

const HELP_ID = 'crowd-camera-help';
const seconds = (ms: number) => `${Math.max(1, Math.round(ms / 1000))} s`;

/**
 * The Crowd view: a crowd scene rendered by the server and streamed as JPEG frames over
 * /api/v1/crowd/stream, with an orbit camera, the level-of-detail switches and the server's
 * numbers over the picture. The stream runs only while the view is shown (the server streams to
 * a few clients at once).
 *
 * The canvas reports data-status (loading, connecting, preparing, ready, streaming, retrying,
 * refused, error, stopped), data-scene, data-frames and data-frame-id; the stats box data-frame,
 * data-scene, data-mode, data-triangles, data-width, data-height and data-latency-ms.
 */
export class CrowdView implements View {
  readonly element: HTMLElement;
  private readonly picker: WantedPicker<CrowdScene>;
  private readonly summary: HTMLElement;
  private readonly stage: HTMLElement;
  private readonly canvas = new StreamCanvas(HELP_ID);
  private readonly stats = new StatsOverlay();
  private readonly progress = new ProgressBox();
  private readonly heatLegend = new HeatLegend();
  private readonly notice = new MapNotice();
  private readonly status = new StatusOverlay();
  private readonly credits = h('div', { class: 'attribution', 'aria-label': 'Model credits', hidden: true });
  private readonly controls: ControlsPanel;
  private readonly camera: OrbitCamera;
  private readonly stream: CrowdStream;
  private readonly decoder: FrameDecoder;
  private catalog?: CrowdScenesResponse;
  private scene?: CrowdScene;
  /** The scene's first frame is not drawn yet (the progress box stays until it is). */
  private awaitingFirst = true;
  private shown = false;
  /** Pixels of the stage (CSS), from the ResizeObserver. */
  private stageSize = { width: 0, height: 0 };

  constructor(private readonly go: (sceneId: string, replace: boolean) => void) {
    this.picker = new WantedPicker<CrowdScene>({
      id: 'crowd-scene',
      label: (scene) => `${scene.title} — ${scene.characters.toLocaleString('en')} ${scene.id === 'stampede' ? 'animals' : 'people'}`,
      go: (id, replace) => this.go(id, replace),
      open: (scene) => this.openWanted(scene),
      missing: (id) => this.fail(`There is no crowd scene “${id}”`, 'Pick one of the scenes in the list.'),
      empty: () => this.fail('No crowd scenes', 'The server offers no crowd scenes.'),
    });
    this.summary = h('p', { class: 'crowd-summary', 'aria-live': 'polite' });
    this.controls = new ControlsPanel(() => {
      // A change answers the server's complaint about the last one.
      this.notice.clear('server');
      this.heatLegend.shown = this.controls.value.heatmap;
      this.sendView();
    });
    this.camera = new OrbitCamera(this.canvas.element, () => this.sendView());
    this.decoder = new FrameDecoder({
      onDecoded: (frame) => this.drawFrame(frame),
      onError: (error) => console.warn('crowd: a frame could not be decoded', error),
    });
    this.stream = new CrowdStream({
      onState: (state, close) => this.streamState(state, close),
      onMessage: (message) => this.receive(message),
      onFrame: (frame) => this.decoder.push(frame),
      onBadMessage: (problem) => console.warn(`crowd: ignored ${problem}`),
    });

    this.stage = h(
      'div',
      { class: 'map-area crowd-stage' },
      this.canvas.element,
      this.stats.element,
      this.heatLegend.element,
      this.progress.element,
      this.notice.element,
      this.credits,
      this.status.element,
    );
    // The switches: a side panel on desktop, a bottom sheet on phones (see ControlSheet).
    const sheet = new ControlSheet(
      'crowd',
      'Crowd options',
      {
        title: 'A crowd drawn live',
        text: 'A busy place full of walking people, drawn by the server and streamed to you like a video. People far away are drawn with less detail, so big crowds stay smooth.',
        tryThis: 'drag the picture to walk around the crowd, and pinch (or scroll) to come closer.',
      },
      'crowd-side',
      [
        h('div', { class: 'field-row' }, h('label', { class: 'field', for: 'crowd-scene' }, 'Scene'), this.picker.element),
        this.summary,
        this.controls.element,
        h(
          'details',
          { class: 'options crowd-help' },
          h('summary', {}, 'Camera'),
          h(
            'ul',
            { id: HELP_ID, class: 'crowd-help-list' },
            h('li', {}, 'Drag to orbit around the target; the wheel (or a pinch) moves closer or away.'),
            h('li', {}, 'Right-drag or Shift-drag pans.'),
            h('li', {}, 'With the picture focused: W A S D or the arrow keys walk, Q / E go down and up, + / − zoom, Home goes back to the start.'),
          ),
        ),
      ],
    );
    this.element = h('section', { class: 'view view-crowd has-sheet' }, sheet.element, this.stage);

    new ResizeObserver((entries) => {
      const box = entries[entries.length - 1]!.contentRect;
      this.stageSize = { width: box.width, height: box.height };
      this.sendView();
    }).observe(this.stage);
    document.addEventListener('visibilitychange', () => this.syncStream());
    this.canvas.status = 'loading';
    void this.loadScenes();
  }

  show(sceneId: string | undefined): void {
    this.shown = true;
    this.picker.want(sceneId);
  }

  hide(): void {
    this.shown = false;
    this.syncStream();
  }

  catalogChanged(_lastImport: LastImport | undefined): void {
    // Crowd scenes are not imported data.
  }

  private async loadScenes(): Promise<void> {
    this.status.loading('Loading crowd scenes…');
    try {
      this.catalog = await fetchCrowdScenes();
    } catch (error) {
      this.canvas.status = 'error';
      this.status.error('Could not load the crowd scenes', error, () => void this.loadScenes());
      return;
    }
    this.status.clear();
    const { scenes, modes, limits } = this.catalog;
    this.controls.configure(modes, limits);
    this.stream.setMaxRate(limits.max_fps, limits.max_messages_per_s);
    this.picker.setItems(scenes, this.shown);
  }

  /** The route's scene, from the list (WantedPicker). */
  private openWanted(scene: CrowdScene): void {
    document.title = `${scene.title} · Crowd · tourmap`;
    if (this.scene?.id !== scene.id) this.openScene(scene);
    this.syncStream();
    this.sendView();
  }

  private fail(title: string, detail: string): void {
    this.scene = undefined;
    this.stream.stop();
    this.decoder.reset();
    this.canvas.clear();
    this.progress.hide();
    this.canvas.status = 'error';
    this.status.error(title, new Error(detail));
  }

  private openScene(scene: CrowdScene): void {
    const catalog = this.catalog!;
    this.scene = scene;
    this.status.clear();
    this.notice.clear();
    this.decoder.reset();
    this.canvas.clear();
    this.canvas.element.dataset.scene = scene.id;
    this.canvas.label = `${scene.title}: a crowd rendered by the server`;
    this.camera.reset(scene.default_camera, scene.bounds, scene.occluder_boxes ?? []);
    this.controls.setScene(scene);
    this.stats.clear();
    this.stats.setFullTriangles(scene.triangles);
    this.awaitingFirst = true;
    this.progress.waiting(`Opening ${scene.title}…`);
    this.summary.replaceChildren(
      h('span', {}, scene.description),
      h(
        'span',
        { class: 'crowd-counts' },
        [
          `${scene.characters.toLocaleString('en')} ${scene.id === 'stampede' ? 'animals' : 'people'}`,
          `${scene.models.length} models`,
          scene.triangles ? `${formatCount(scene.triangles)} triangles at full resolution` : '',
          scene.occluders ? `${Number(scene.occluders).toLocaleString('en')} occluders (walls, booths, rocks)` : '',
        ]
          .filter(Boolean)
          .join(' · '),
      ),
    );
    showModelCredits(this.credits, catalog.attribution, scene.models);
  }

  /** Streams while the view is on screen, the tab visible and a scene open. */
  private syncStream(): void {
    const wanted = this.shown && this.scene !== undefined && document.visibilityState === 'visible';
    if (wanted && !this.stream.isRunning) {
      this.stream.start();
      this.sendView();
    } else if (!wanted && this.stream.isRunning) {
      this.stream.stop();
      this.decoder.reset();
    }
  }

  /** The view to render; the stream sends it on the next animation frame (if it changed). */
  private sendView(): void {
    const view = this.viewMessage();
    if (view) this.stream.setView(view);
  }

  private viewMessage(): CrowdViewMessage | null {
    const scene = this.scene;
    const limits = this.catalog?.limits;
    const size = this.renderSize();
    if (!scene || !limits || !size) return null;
    const settings = this.controls.value;
    return {
      type: 'view',
      scene: scene.id,
      mode: settings.mode,
      poe: settings.poe,
      width: size.width,
      height: size.height,
      quality: settings.quality,
      camera: this.camera.camera,
      heatmap: settings.heatmap,
      animate: settings.animate,
      target_fps: settings.smoothFps,
      interacting: this.camera.interacting,
      ...(settings.count !== undefined ? { count: settings.count } : {}),
    };
  }

  /** The stage's size in rendered pixels (the resolution setting), within the server's limits, same aspect. */
  private renderSize(): { width: number; height: number } | null {
    const limits = this.catalog?.limits;
    const { width, height } = this.stageSize;
    if (!limits || width < 1 || height < 1) return null;
    const resolution = this.controls.value.resolution;
    const scale = resolution === 'device' ? window.devicePixelRatio || 1 : resolution;
    const fit = Math.min(1, limits.max_width / (width * scale), limits.max_height / (height * scale));
    return {
      width: Math.max(limits.min_width, Math.min(limits.max_width, Math.round(width * scale * fit))),
      height: Math.max(limits.min_height, Math.min(limits.max_height, Math.round(height * scale * fit))),
    };
  }

  // ---- What the stream says ----

  private streamState(state: StreamState, close?: StreamClose): void {
    if (state === 'stopped') {
      this.canvas.status = 'stopped';
      return;
    }
    if (state === 'connecting') {
      if (this.awaitingFirst) this.progress.waiting('Connecting to the renderer…');
      if (this.canvas.status !== 'refused' && this.canvas.status !== 'retrying') this.canvas.status = 'connecting';
      return;
    }
    if (state === 'open') {
      // A refusal or an interruption stays on screen until the server serves this socket.
      if (this.canvas.status !== 'refused') this.canvas.status = this.awaitingFirst ? 'connecting' : 'streaming';
      if (this.awaitingFirst) this.progress.waiting('Waiting for the server…', 'The first view of a scene can take a while: the server prepares it.');
      return;
    }
    const retry = () => this.stream.retryNow();
    const when = close ? seconds(close.retryInMs) : 'a moment';
    if (state === 'refused') {
      // Not our fault and not a glitch: the picture is covered until a slot frees.
      this.canvas.status = 'refused';
      this.progress.hide();
      const max = this.catalog?.limits.max_streams;
      this.status.error(
        'The renderer is busy',
        new Error(
          `The server streams crowds to ${max ? `at most ${max} viewers` : 'a few viewers'} at once and all are in use` +
            ` (“${close?.reason || 'too many streams'}”). tourmap asks again in ${when}.`,
        ),
        retry,
      );
      return;
    }
    this.canvas.status = 'retrying';
    const reason = close?.reason ? `: “${close.reason}”` : '';
    console.info(`crowd: stream closed (code ${close?.code ?? '?'}${reason})`);
    const why = close?.code === CLOSE_POLICY ? 'The server stopped the stream: too many changes at once.' : 'The connection to the renderer was lost.';
    this.notice.error('connection', 'Stream interrupted', new Error(`${why} Reconnecting in ${when}.`), retry);
  }

  /** The server answered on this socket: whatever said it did not is gone. */
  private served(): void {
    this.notice.clear('connection');
    if (this.canvas.status === 'refused' || this.canvas.status === 'retrying') {
      this.status.clear();
      this.canvas.status = this.awaitingFirst ? 'connecting' : 'streaming';
    }
  }

  private receive(message: CrowdServerMessage): void {
    const scene = this.scene;
    if (!scene) return;
    if (message.type !== 'error') this.served();
    switch (message.type) {
      case 'progress':
        if (message.scene !== scene.id) return;
        this.canvas.status = 'preparing';
        this.progress.show(message, scene.title);
        return;
      case 'ready':
        if (message.scene !== scene.id) return;
        this.stats.setFullTriangles(message.triangles);
        if (this.awaitingFirst) {
          this.canvas.status = 'ready';
          this.progress.waiting('Rendering the first frame…');
        }
        // The server's camera, unless the user already moved.
        if (!this.camera.moved && message.default_camera && message.bounds) {
          this.camera.reset(message.default_camera, message.bounds);
          this.sendView();
        }
        return;
      case 'stats':
        if (message.scene !== scene.id) return;
        this.stats.show(message);
        if (this.awaitingFirst) this.firstFrameShown();
        return;
      case 'error': {
        const { code, message: text, field } = message.error;
        // The refusal's close (1013) follows: streamState shows it.
        if (code === 'too_many_streams') return;
        const title = code === 'bad_request' ? 'The server did not take the last change' : 'The server cannot render the scene';
        const advice = code === 'bad_request' ? ' The previous view stays.' : ' Change the view to try again.';
        this.notice.error('server', title, new Error(`${text}${field ? ` (${field})` : ''} [${code}].${advice}`));
        if (this.awaitingFirst) this.progress.hide();
        return;
      }
    }
  }

  private drawFrame(frame: DecodedFrame): void {
    this.served();
    this.canvas.draw(frame.bitmap, frame.header.id);
    this.stats.frameDrawn(
      { latencyMs: frame.receivedAt - frame.header.timestamp, width: frame.header.width, height: frame.header.height },
      this.decoder.dropped,
    );
    if (!this.awaitingFirst) this.canvas.status = 'streaming';
  }

  private firstFrameShown(): void {
    this.awaitingFirst = false;
    this.progress.hide();
    this.canvas.status = 'streaming';
  }
}
