import type { CrowdServerMessage, CrowdViewMessage } from '../api/types';
import { parseFrame, type ReceivedFrame } from './frame-decoder';

/**
 * connecting: opening the socket; open: the socket is up; retrying: it closed unexpectedly and
 * is opened again after a delay; refused: the server streams to as many clients as it may (close
 * 1013) and is asked again after a longer delay; stopped: closed by us.
 */
export type StreamState = 'connecting' | 'open' | 'retrying' | 'refused' | 'stopped';

export interface StreamClose {
  code: number;
  reason: string;
  /** When the next attempt starts (ms from now). */
  retryInMs: number;
}

export interface StreamHandlers {
  onState(state: StreamState, close?: StreamClose): void;
  onMessage(message: CrowdServerMessage): void;
  onFrame(frame: ReceivedFrame): void;
  /** A message that is not what the protocol says (logged by the view, never fatal). */
  onBadMessage(problem: string): void;
}

const FIRST_RETRY_MS = 1000;
const MAX_RETRY_MS = 30000;
/** After a refusal (too many streams) the first retry waits longer: others are watching. */
const FIRST_REFUSED_RETRY_MS = 10000;
/** Close code of the server's "too many streams" refusal (RFC 6455: try again later). */
export const CLOSE_TRY_AGAIN_LATER = 1013;
/** Close code of the server's "policy violation" (flooding, oversized messages). */
export const CLOSE_POLICY = 1008;
/** The server renders at most 30 frames per second (unless its limits say otherwise): views are sent no faster. */
const DEFAULT_MAX_RATE = 30;

/** Wall-clock time in ms since the epoch, finer than Date.now(). */
export const wallClock = () => performance.timeOrigin + performance.now();

/**
 * The /api/v1/crowd/stream WebSocket: sends the latest view (at most one message per animation
 * frame and as many per second as the server renders frames, nothing when it did not change, the whole view again after every
 * reconnect), parses what the server sends, and reconnects with exponential backoff plus jitter
 * when the socket closes without being asked to.
 */
export class CrowdStream {
  private socket: WebSocket | null = null;
  private view: CrowdViewMessage | null = null;
  private lastSent = '';
  private lastSentAt = -Infinity;
  private minSendIntervalMs = 1000 / DEFAULT_MAX_RATE;
  private flushFrame = 0;
  private retryTimer = 0;
  private retryMs = FIRST_RETRY_MS;
  private running = false;
  /** The server served this socket (progress, a frame…): the backoff starts over. */
  private answered = false;

  constructor(private readonly handlers: StreamHandlers) {}

  get isRunning(): boolean {
    return this.running;
  }

  /** Opens the socket (if not open); the view set meanwhile is sent once it is up. */
  start(): void {
    if (this.running) return;
    this.running = true;
    this.retryMs = FIRST_RETRY_MS;
    this.connect();
  }

  /** Closes the socket and stops reconnecting. */
  stop(): void {
    this.running = false;
    window.clearTimeout(this.retryTimer);
    cancelAnimationFrame(this.flushFrame);
    this.flushFrame = 0;
    const socket = this.socket;
    this.socket = null;
    if (socket) {
      socket.onclose = null;
      socket.onmessage = null;
      socket.close(1000, 'view closed');
    }
    this.handlers.onState('stopped');
  }

  /** Connects now instead of waiting for the scheduled retry. */
  retryNow(): void {
    if (!this.running || this.socket) return;
    window.clearTimeout(this.retryTimer);
    this.connect();
  }

  /**
   * The server's rates: frames per second it renders, view messages per second it takes before
   * closing the stream. Views go no faster than the first, and at half the second at most.
   */
  setMaxRate(maxFps = DEFAULT_MAX_RATE, maxMessagesPerSecond = 2 * DEFAULT_MAX_RATE): void {
    const rate = Math.max(1, Math.min(maxFps, maxMessagesPerSecond / 2));
    this.minSendIntervalMs = 1000 / rate;
  }

  /** The view to render: sent on the next animation frame unless it is what was sent last. */
  setView(view: CrowdViewMessage): void {
    this.view = view;
    this.scheduleFlush();
  }

  private scheduleFlush(): void {
    if (this.flushFrame) return;
    this.flushFrame = requestAnimationFrame(() => {
      this.flushFrame = 0;
      this.flush();
    });
  }

  private flush(): void {
    const socket = this.socket;
    if (!this.view || !socket || socket.readyState !== WebSocket.OPEN) return;
    const text = JSON.stringify(this.view);
    if (text === this.lastSent) return;
    // Faster than the server renders is only more messages: wait for a later animation frame.
    if (performance.now() - this.lastSentAt < this.minSendIntervalMs) {
      this.scheduleFlush();
      return;
    }
    socket.send(text);
    this.lastSent = text;
    this.lastSentAt = performance.now();
  }

  private connect(): void {
    const url = new URL('/api/v1/crowd/stream', window.location.href);
    url.protocol = url.protocol === 'https:' ? 'wss:' : 'ws:';
    this.handlers.onState('connecting');
    const socket = new WebSocket(url);
    socket.binaryType = 'arraybuffer';
    this.socket = socket;
    this.answered = false;
    socket.onopen = () => {
      // A new connection knows nothing: the whole view goes first.
      this.lastSent = '';
      this.lastSentAt = -Infinity;
      this.handlers.onState('open');
      this.flush();
    };
    socket.onmessage = (message) => this.receive(message);
    socket.onclose = (event) => {
      if (this.socket !== socket) return;
      this.socket = null;
      if (!this.running) return;
      const refused = event.code === CLOSE_TRY_AGAIN_LATER;
      if (refused) this.retryMs = Math.max(this.retryMs, FIRST_REFUSED_RETRY_MS);
      const delay = this.retryMs * (0.75 + Math.random() * 0.5);
      this.retryMs = Math.min(this.retryMs * 2, MAX_RETRY_MS);
      this.handlers.onState(refused ? 'refused' : 'retrying', { code: event.code, reason: event.reason, retryInMs: delay });
      this.retryTimer = window.setTimeout(() => this.connect(), delay);
    };
  }

  private receive(message: MessageEvent): void {
    const receivedAt = wallClock();
    if (message.data instanceof ArrayBuffer) {
      let frame: ReceivedFrame;
      try {
        frame = parseFrame(message.data, receivedAt);
      } catch (error) {
        this.handlers.onBadMessage(error instanceof Error ? error.message : String(error));
        return;
      }
      this.served();
      // Flow control: the server sends the next frame once this one is acknowledged, so frames
      // never queue up in socket buffers on a slow link (the newest view is what gets rendered).
      const socket = this.socket;
      if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify({ type: 'ack', frame: frame.header.id }));
      this.handlers.onFrame(frame);
      return;
    }
    let parsed: unknown;
    try {
      parsed = JSON.parse(String(message.data));
    } catch {
      this.handlers.onBadMessage('a text message that is not JSON');
      return;
    }
    const type = (parsed as { type?: unknown } | null)?.type;
    if (type === 'progress' || type === 'ready' || type === 'stats' || type === 'error') {
      // An error alone (a bad view) does not say the stream works.
      if (type !== 'error') this.served();
      this.handlers.onMessage(parsed as CrowdServerMessage);
    } else {
      this.handlers.onBadMessage(`a message of unknown type ${JSON.stringify(type)}`);
    }
  }

  private served(): void {
    if (this.answered) return;
    this.answered = true;
    this.retryMs = FIRST_RETRY_MS;
  }
}
