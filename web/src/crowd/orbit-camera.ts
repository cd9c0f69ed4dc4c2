import type { CrowdBounds, CrowdCamera, Vec3 } from '../api/types';

/** Radians per pixel of drag. */
const ORBIT_SPEED = 0.008;
/** Distance factor per pixel of wheel. */
const DOLLY_SPEED = 0.0015;
const MIN_PITCH = (-80 * Math.PI) / 180;
const MAX_PITCH = (89 * Math.PI) / 180;
const MIN_DISTANCE = 0.3;
/** Key moves: the scene's diagonal times this per second (at least 1 m/s); Shift: 3 times faster. */
const KEY_SPEED = 0.2;
/** The target stays within the scene's bounds grown by this share of their size. */
const BOUNDS_MARGIN = 0.5;

type Move = 'forward' | 'back' | 'left' | 'right' | 'up' | 'down';
const MOVE_KEYS: Record<string, Move> = {
  KeyW: 'forward',
  ArrowUp: 'forward',
  KeyS: 'back',
  ArrowDown: 'back',
  KeyA: 'left',
  ArrowLeft: 'left',
  KeyD: 'right',
  ArrowRight: 'right',
  KeyE: 'up',
  PageUp: 'up',
  KeyQ: 'down',
  PageDown: 'down',
};

const add = (a: Vec3, b: Vec3, s = 1): Vec3 => [a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s];
const sub = (a: Vec3, b: Vec3): Vec3 => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const length = (a: Vec3) => Math.hypot(a[0], a[1], a[2]);
const normalize = (a: Vec3): Vec3 => {
  const l = length(a) || 1;
  return [a[0] / l, a[1] / l, a[2] / l];
};
const cross = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const clamp = (value: number, min: number, max: number) => Math.min(max, Math.max(min, value));
const round = (value: number) => Math.round(value * 1e4) / 1e4;

/**
 * An orbit camera on an element: drag orbits around the target, the wheel (or a pinch) dollies,
 * right-drag, middle-drag or Shift-drag pans; with the element focused, WASD / arrow keys move
 * the target on the ground, Q/E (PageDown/PageUp) down and up, +/- dolly and Home goes back to
 * the scene's camera. Every change calls onChange (at most once per animation frame for keys).
 */
export class OrbitCamera {
  private target: Vec3 = [0, 0, 0];
  private distance = 10;
  private yaw = 0;
  private pitch = 0;
  private fov = 60;
  private bounds: CrowdBounds = { min: [-1, -1, -1], max: [1, 1, 1] };
  private home?: CrowdCamera;
  private readonly pointers = new Map<number, { x: number; y: number; pan: boolean }>();
  private readonly keys = new Set<Move>();
  private fast = false;
  private keyFrame = 0;
  private keyTime = 0;
  /** The user moved the camera since the last reset. */
  moved = false;

  constructor(
    private readonly element: HTMLElement,
    private readonly onChange: (camera: CrowdCamera) => void,
  ) {
    element.addEventListener('pointerdown', (event) => this.pointerDown(event));
    element.addEventListener('pointermove', (event) => this.pointerMove(event));
    element.addEventListener('pointerup', (event) => this.pointerUp(event));
    element.addEventListener('pointercancel', (event) => this.pointerUp(event));
    element.addEventListener('contextmenu', (event) => event.preventDefault());
    element.addEventListener('wheel', (event) => this.wheel(event), { passive: false });
    element.addEventListener('keydown', (event) => this.keyDown(event));
    element.addEventListener('keyup', (event) => this.keyUp(event));
    element.addEventListener('blur', () => this.stopKeys());
  }

  /** Puts the camera where the scene says (no onChange: the caller sends the view itself). */
  reset(camera: CrowdCamera, bounds: CrowdBounds): void {
    this.home = camera;
    this.bounds = bounds;
    this.target = [...camera.target];
    this.fov = camera.fov;
    const offset = sub(camera.eye, camera.target);
    this.distance = Math.max(MIN_DISTANCE, length(offset));
    this.yaw = Math.atan2(offset[0], offset[2]);
    this.pitch = clamp(Math.asin(clamp(offset[1] / this.distance, -1, 1)), MIN_PITCH, MAX_PITCH);
    this.moved = false;
    this.stopKeys();
  }

  get camera(): CrowdCamera {
    const eye = add(this.target, this.offset());
    return { eye: eye.map(round) as Vec3, target: this.target.map(round) as Vec3, fov: this.fov };
  }

  private offset(): Vec3 {
    const c = Math.cos(this.pitch);
    return [this.distance * c * Math.sin(this.yaw), this.distance * Math.sin(this.pitch), this.distance * c * Math.cos(this.yaw)];
  }

  private get sceneSize(): number {
    return Math.max(1, length(sub(this.bounds.max, this.bounds.min)));
  }

  private changed(): void {
    this.moved = true;
    this.onChange(this.camera);
  }

  // ---- Moves ----

  private orbit(dx: number, dy: number): void {
    this.yaw -= dx * ORBIT_SPEED;
    this.pitch = clamp(this.pitch + dy * ORBIT_SPEED, MIN_PITCH, MAX_PITCH);
  }

  private dolly(factor: number): void {
    this.distance = clamp(this.distance * factor, MIN_DISTANCE, 4 * this.sceneSize);
  }

  /** Moves the target so the point under the pointer (at the target's depth) follows it. */
  private pan(dx: number, dy: number): void {
    const height = this.element.clientHeight || 1;
    const perPixel = (2 * this.distance * Math.tan((this.fov * Math.PI) / 360)) / height;
    const forward = normalize(sub([0, 0, 0], this.offset()));
    const right = normalize(cross(forward, [0, 1, 0]));
    const up = cross(right, forward);
    this.moveTarget(add(add([0, 0, 0], right, -dx * perPixel), up, dy * perPixel));
  }

  private moveTarget(delta: Vec3): void {
    const { min, max } = this.bounds;
    this.target = this.target.map((value, axis) => {
      const margin = (max[axis]! - min[axis]!) * BOUNDS_MARGIN + 1;
      return clamp(value + delta[axis]!, min[axis]! - margin, max[axis]! + margin);
    }) as Vec3;
  }

  // ---- Pointer ----

  private pointerDown(event: PointerEvent): void {
    if (event.pointerType === 'mouse' && event.button > 2) return;
    // No preventDefault: the press focuses the element (for the keys) the way a click does.
    this.element.setPointerCapture(event.pointerId);
    const pan = event.button === 1 || event.button === 2 || event.shiftKey;
    this.pointers.set(event.pointerId, { x: event.clientX, y: event.clientY, pan });
  }

  private pointerMove(event: PointerEvent): void {
    const pointer = this.pointers.get(event.pointerId);
    if (!pointer) return;
    const dx = event.clientX - pointer.x;
    const dy = event.clientY - pointer.y;
    if (dx === 0 && dy === 0) return;
    if (this.pointers.size >= 2) {
      // Two fingers: the spread dollies, the midpoint pans.
      const [a, b] = [...this.pointers.values()] as [typeof pointer, typeof pointer];
      const before = Math.hypot(a.x - b.x, a.y - b.y);
      pointer.x = event.clientX;
      pointer.y = event.clientY;
      const after = Math.hypot(a.x - b.x, a.y - b.y);
      if (before > 0 && after > 0) this.dolly(before / after);
      this.pan(dx / 2, dy / 2);
    } else {
      pointer.x = event.clientX;
      pointer.y = event.clientY;
      if (pointer.pan || event.shiftKey) this.pan(dx, dy);
      else this.orbit(dx, dy);
    }
    this.changed();
  }

  private pointerUp(event: PointerEvent): void {
    this.pointers.delete(event.pointerId);
  }

  private wheel(event: WheelEvent): void {
    event.preventDefault();
    const pixels = event.deltaY * (event.deltaMode === WheelEvent.DOM_DELTA_LINE ? 16 : event.deltaMode === WheelEvent.DOM_DELTA_PAGE ? 400 : 1);
    this.dolly(Math.exp(clamp(pixels, -300, 300) * DOLLY_SPEED));
    this.changed();
  }

  // ---- Keys ----

  private keyDown(event: KeyboardEvent): void {
    if (event.altKey || event.ctrlKey || event.metaKey) return;
    const move = MOVE_KEYS[event.code];
    if (move) {
      event.preventDefault();
      this.fast = event.shiftKey;
      if (!this.keys.has(move)) {
        this.keys.add(move);
        if (!this.keyFrame) {
          this.keyTime = performance.now();
          this.keyFrame = requestAnimationFrame((now) => this.keyStep(now));
        }
      }
      return;
    }
    if (event.key === '+' || event.key === '=' || event.key === '-') {
      event.preventDefault();
      this.dolly(event.key === '-' ? 1.15 : 1 / 1.15);
      this.changed();
    } else if (event.key === 'Home' && this.home) {
      event.preventDefault();
      this.reset(this.home, this.bounds);
      this.changed();
    }
  }

  private keyUp(event: KeyboardEvent): void {
    const move = MOVE_KEYS[event.code];
    if (move) this.keys.delete(move);
    this.fast = event.shiftKey;
  }

  private stopKeys(): void {
    this.keys.clear();
    cancelAnimationFrame(this.keyFrame);
    this.keyFrame = 0;
  }

  /** Moves the target while keys are held: on the ground along the view's heading, or up and down. */
  private keyStep(now: number): void {
    const seconds = Math.min(0.1, (now - this.keyTime) / 1000);
    this.keyTime = now;
    const step = Math.max(1, this.sceneSize * KEY_SPEED) * (this.fast ? 3 : 1) * seconds;
    const heading: Vec3 = [-Math.sin(this.yaw), 0, -Math.cos(this.yaw)];
    const side: Vec3 = [Math.cos(this.yaw), 0, -Math.sin(this.yaw)];
    let delta: Vec3 = [0, 0, 0];
    for (const move of this.keys) {
      if (move === 'forward') delta = add(delta, heading, step);
      else if (move === 'back') delta = add(delta, heading, -step);
      else if (move === 'right') delta = add(delta, side, step);
      else if (move === 'left') delta = add(delta, side, -step);
      else if (move === 'up') delta = add(delta, [0, step, 0]);
      else delta = add(delta, [0, -step, 0]);
    }
    if (seconds > 0) {
      this.moveTarget(delta);
      this.changed();
    }
    this.keyFrame = this.keys.size > 0 ? requestAnimationFrame((next) => this.keyStep(next)) : 0;
  }
}
