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
/** The target stays within the scene's bounds grown by this share of their size (and not under the ground). */
const BOUNDS_MARGIN = 0.5;
/** The eye the user steers stays this high above the ground plane (y = 0), in metres. */
const EYE_MIN_HEIGHT = 0.5;
/** After being pushed out of a wall towards the target, the eye may be no lower than this. */
const EYE_FLOOR = 0.2;
/** The eye keeps this far from an occluder box (metres): the renderer's near plane is 0.1 m. */
const BOX_MARGIN = 0.3;
/** Pushes out of boxes tried before a move is refused (walls meet at corners: one push can land in the next). */
const MAX_PUSHES = 16;
/** A pushed eye ends up this far outside the box it left. */
const PUSH_EPSILON = 1e-3;

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

/** Whether `p` is strictly inside `box` grown by `margin`. */
function inside(p: Vec3, box: CrowdBounds, margin: number): boolean {
  return [0, 1, 2].every((axis) => p[axis]! > box.min[axis]! - margin && p[axis]! < box.max[axis]! + margin);
}

/** The interval [t0, t1] of the line origin + t * dir inside `box` grown by `margin` (slab method), or null. */
function lineInterval(origin: Vec3, dir: Vec3, box: CrowdBounds, margin: number): [number, number] | null {
  let t0 = -Infinity;
  let t1 = Infinity;
  for (let axis = 0; axis < 3; axis++) {
    const lo = box.min[axis]! - margin - origin[axis]!;
    const hi = box.max[axis]! + margin - origin[axis]!;
    const d = dir[axis]!;
    if (Math.abs(d) < 1e-12) {
      if (lo > 0 || hi < 0) return null;
      continue;
    }
    const a = lo / d;
    const b = hi / d;
    t0 = Math.max(t0, Math.min(a, b));
    t1 = Math.min(t1, Math.max(a, b));
  }
  return t0 <= t1 ? [t0, t1] : null;
}

interface OrbitState {
  target: Vec3;
  distance: number;
  yaw: number;
  pitch: number;
}

/**
 * An orbit camera on an element: drag orbits around the target, the wheel (or a pinch) dollies,
 * right-drag, middle-drag or Shift-drag pans; with the element focused, WASD / arrow keys move
 * the target on the ground, Q/E (PageDown/PageUp) down and up, +/- dolly and Home goes back to
 * the scene's camera. Every change calls onChange (at most once per animation frame for keys).
 *
 * The eye stays above the ground (the pitch and distance are clamped so it is EYE_MIN_HEIGHT up)
 * and out of the scene's occluder boxes: an eye that would be inside one is pulled along the view
 * ray towards the target to the box's near side (or, when the target is inside the box too, out
 * past its far side); the distance the user chose is kept, so the eye returns when the wall no
 * longer is in the way. A move that cannot be resolved so is not made. The element reports the
 * eye and target as data-eye and data-target ("x,y,z").
 */
export class OrbitCamera {
  private target: Vec3 = [0, 0, 0];
  private distance = 10;
  private yaw = 0;
  private pitch = 0;
  private fov = 60;
  private bounds: CrowdBounds = { min: [-1, -1, -1], max: [1, 1, 1] };
  private occluders: CrowdBounds[] = [];
  private home?: CrowdCamera;
  private readonly pointers = new Map<number, { x: number; y: number; pan: boolean }>();
  private readonly keys = new Set<Move>();
  private fast = false;
  private keyFrame = 0;
  private keyTime = 0;
  /** The user moved the camera since the last reset. */
  moved = false;
  /** Wheel turns count as one interaction until the wheel rests this long. */
  private static readonly WHEEL_REST_MS = 200;
  private wheelTimer = 0;

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

  /**
   * Puts the camera where the scene says (no onChange: the caller sends the view itself). The
   * occluder boxes, when given, replace the previous ones.
   */
  reset(camera: CrowdCamera, bounds: CrowdBounds, occluders?: CrowdBounds[]): void {
    this.home = camera;
    this.bounds = bounds;
    if (occluders) this.occluders = occluders;
    this.target = [...camera.target];
    this.fov = camera.fov;
    const offset = sub(camera.eye, camera.target);
    this.distance = Math.max(MIN_DISTANCE, length(offset));
    this.yaw = Math.atan2(offset[0], offset[2]);
    this.pitch = clamp(Math.asin(clamp(offset[1] / this.distance, -1, 1)), MIN_PITCH, MAX_PITCH);
    this.keepAboveGround();
    this.moved = false;
    this.stopKeys(false);
    this.publish();
  }

  get camera(): CrowdCamera {
    const eye = this.eye() ?? add(this.target, this.offset());
    return { eye: eye.map(round) as Vec3, target: this.target.map(round) as Vec3, fov: this.fov };
  }

  private offset(distance = this.distance): Vec3 {
    const c = Math.cos(this.pitch);
    return [distance * c * Math.sin(this.yaw), distance * Math.sin(this.pitch), distance * c * Math.cos(this.yaw)];
  }

  /** Raises the pitch (and if need be the distance) so the eye the user steers is EYE_MIN_HEIGHT above the ground. */
  private keepAboveGround(): void {
    const rise = EYE_MIN_HEIGHT - this.target[1];
    if (this.target[1] + this.distance * Math.sin(this.pitch) >= EYE_MIN_HEIGHT) return;
    const sinMax = Math.sin(MAX_PITCH);
    if (rise > this.distance * sinMax) this.distance = rise / sinMax;
    this.pitch = Math.max(this.pitch, Math.asin(clamp(rise / this.distance, -1, 1)));
  }

  /**
   * The eye: at the chosen distance, or pulled out of the occluder box it would be in (see the
   * class comment); null when no place on the view ray is free (the move is then not made).
   */
  private eye(): Vec3 | null {
    const direction = normalize(this.offset(1));
    const free = (distance: number) => this.occluders.find((box) => inside(add(this.target, direction, distance), box, BOX_MARGIN)) === undefined;
    const push = (towards: boolean): number | null => {
      let distance = this.distance;
      for (let i = 0; i < MAX_PUSHES; i++) {
        const box = this.occluders.find((candidate) => inside(add(this.target, direction, distance), candidate, BOX_MARGIN));
        if (!box) return distance;
        const span = lineInterval(this.target, direction, box, BOX_MARGIN);
        if (!span) return null;
        distance = towards ? span[0] - PUSH_EPSILON : span[1] + PUSH_EPSILON;
        if (distance <= 0) return null;
      }
      return free(distance) ? distance : null;
    };
    const distance = push(true) ?? push(false);
    if (distance === null) return null;
    const eye = add(this.target, direction, distance);
    return eye[1] >= EYE_FLOOR ? eye : null;
  }

  private snapshot(): OrbitState {
    return { target: [...this.target], distance: this.distance, yaw: this.yaw, pitch: this.pitch };
  }

  /** Keeps the eye above ground; undoes the move since `before` when the eye has no free place. */
  private settle(before: OrbitState): void {
    this.keepAboveGround();
    if (this.eye() === null) Object.assign(this, before);
  }

  private publish(): void {
    const { eye, target } = this.camera;
    this.element.dataset.eye = eye.join(',');
    this.element.dataset.target = target.join(',');
  }

  private get sceneSize(): number {
    return Math.max(1, length(sub(this.bounds.max, this.bounds.min)));
  }

  private changed(): void {
    this.moved = true;
    this.publish();
    this.onChange(this.camera);
  }

  /**
   * The user is moving the camera: a pointer is down, a move key is held or the wheel turned in
   * the last WHEEL_REST_MS. Sent with the view ("interacting"), so the server keeps frames light
   * meanwhile and sends the sharp one as soon as the user lets go.
   */
  get interacting(): boolean {
    return this.pointers.size > 0 || this.keys.size > 0 || this.wheelTimer !== 0;
  }

  /** An input ended: when it was the last one, the view goes again (now not interacting). */
  private inputEnded(): void {
    if (!this.interacting) this.onChange(this.camera);
  }

  // ---- Moves ----

  private orbit(dx: number, dy: number): void {
    const before = this.snapshot();
    this.yaw -= dx * ORBIT_SPEED;
    this.pitch = clamp(this.pitch + dy * ORBIT_SPEED, MIN_PITCH, MAX_PITCH);
    this.settle(before);
  }

  private dolly(factor: number): void {
    const before = this.snapshot();
    this.distance = clamp(this.distance * factor, MIN_DISTANCE, 4 * this.sceneSize);
    this.settle(before);
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
    const before = this.snapshot();
    const { min, max } = this.bounds;
    this.target = this.target.map((value, axis) => {
      const margin = (max[axis]! - min[axis]!) * BOUNDS_MARGIN + 1;
      // Not under the ground: a target below it drags the eye down there too.
      const low = axis === 1 ? Math.max(0, min[axis]! - margin) : min[axis]! - margin;
      return clamp(value + delta[axis]!, low, max[axis]! + margin);
    }) as Vec3;
    this.settle(before);
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
    if (!this.pointers.delete(event.pointerId)) return;
    this.inputEnded();
  }

  private wheel(event: WheelEvent): void {
    event.preventDefault();
    const pixels = event.deltaY * (event.deltaMode === WheelEvent.DOM_DELTA_LINE ? 16 : event.deltaMode === WheelEvent.DOM_DELTA_PAGE ? 400 : 1);
    window.clearTimeout(this.wheelTimer);
    this.wheelTimer = window.setTimeout(() => {
      this.wheelTimer = 0;
      this.inputEnded();
    }, OrbitCamera.WHEEL_REST_MS);
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
    this.fast = event.shiftKey;
    if (move && this.keys.delete(move)) this.inputEnded();
  }

  private stopKeys(notify = true): void {
    const held = notify && this.keys.size > 0;
    this.keys.clear();
    cancelAnimationFrame(this.keyFrame);
    this.keyFrame = 0;
    if (held) this.inputEnded();
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
