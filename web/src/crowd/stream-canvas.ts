import { h } from '../ui/dom';

/**
 * The <canvas> the stream is drawn on. Its backing store takes each frame's size when the frame
 * is drawn (so a resize never blanks it before the next frame arrives); CSS fits it into the
 * stage. Focusable: the camera's keys work while it has focus.
 *
 * For tests it reports data-frames (frames drawn), data-frame-id (the last one's id) and
 * data-status (set by the view).
 */
export class StreamCanvas {
  readonly element: HTMLCanvasElement;
  private readonly context: CanvasRenderingContext2D;
  frames = 0;

  constructor(describedBy: string) {
    this.element = h('canvas', {
      class: 'crowd-canvas',
      width: 16,
      height: 9,
      tabindex: 0,
      // application: screen readers pass the camera keys through; the label says what is shown.
      role: 'application',
      'aria-roledescription': '3D view',
      'aria-describedby': describedBy,
      'data-testid': 'crowd-canvas',
      'data-frames': 0,
    });
    this.context = this.element.getContext('2d', { alpha: false })!;
    this.clear();
  }

  set status(status: string) {
    this.element.dataset.status = status;
  }

  get status(): string {
    return this.element.dataset.status ?? '';
  }

  set label(text: string) {
    this.element.setAttribute('aria-label', text);
  }

  /** Draws a frame and closes the bitmap. */
  draw(bitmap: ImageBitmap, frameId: number): void {
    if (this.element.width !== bitmap.width || this.element.height !== bitmap.height) {
      this.element.width = bitmap.width;
      this.element.height = bitmap.height;
    }
    this.context.drawImage(bitmap, 0, 0);
    bitmap.close();
    this.frames++;
    this.element.dataset.frames = String(this.frames);
    this.element.dataset.frameId = String(frameId);
  }

  /** Blanks the canvas (another scene is coming). */
  clear(): void {
    this.context.fillStyle = '#1d2733';
    this.context.fillRect(0, 0, this.element.width, this.element.height);
    delete this.element.dataset.frameId;
  }
}
