import type { LastImport, LayoutImprovedEvent, ServerEvent } from './types';

export type ConnectionState = 'connecting' | 'live' | 'offline';

export interface EventStreamHandlers {
  /** Data was imported while we listened (or while we were disconnected). */
  onCatalogChange(lastImport: LastImport | undefined): void;
  /** A default layout was improved in the background (events missed while offline are not replayed). */
  onLayoutImproved(event: LayoutImprovedEvent): void;
  onStateChange(state: ConnectionState): void;
}

const FIRST_RETRY_MS = 1000;
const MAX_RETRY_MS = 30000;
/** The server closes a WebSocket that has been silent for a few minutes: ping well before. */
const PING_INTERVAL_MS = 45000;

/**
 * Listens to /api/v1/events (catalog changes, layouts improved in the background) and
 * reconnects with exponential backoff (plus jitter, so many clients do not hammer a restarted
 * server in step) whenever the socket closes.
 */
export class EventStream {
  private retryMs = FIRST_RETRY_MS;
  private catalogVersion?: number;
  private retryTimer = 0;

  constructor(private readonly handlers: EventStreamHandlers) {}

  start(): void {
    this.connect();
    // Back online (a phone leaving a tunnel): reconnect now rather than after the backoff.
    window.addEventListener('online', () => {
      if (!this.retryTimer) return;
      window.clearTimeout(this.retryTimer);
      this.retryTimer = 0;
      this.retryMs = FIRST_RETRY_MS;
      this.connect();
    });
  }

  private connect(): void {
    const url = new URL('/api/v1/events', window.location.href);
    url.protocol = url.protocol === 'https:' ? 'wss:' : 'ws:';
    this.handlers.onStateChange('connecting');
    const socket = new WebSocket(url);
    let pinger: number | undefined;
    socket.addEventListener('open', () => {
      pinger = window.setInterval(() => socket.send(JSON.stringify({ type: 'ping' })), PING_INTERVAL_MS);
    });
    socket.addEventListener('message', (message) => this.receive(message));
    socket.addEventListener('close', () => {
      window.clearInterval(pinger);
      this.handlers.onStateChange('offline');
      this.scheduleReconnect();
    });
  }

  private receive(message: MessageEvent): void {
    let event: ServerEvent;
    try {
      event = JSON.parse(String(message.data)) as ServerEvent;
    } catch {
      return;
    }
    if (event.type === 'hello') {
      this.retryMs = FIRST_RETRY_MS;
      this.handlers.onStateChange('live');
      // An import may have happened while we were disconnected.
      const missed = this.catalogVersion !== undefined && event.catalog_version !== this.catalogVersion;
      this.catalogVersion = event.catalog_version;
      if (missed) this.handlers.onCatalogChange(undefined);
    } else if (event.type === 'catalog') {
      this.catalogVersion = event.catalog_version;
      this.handlers.onCatalogChange(event.last_import);
    } else if (event.type === 'layout_improved') {
      this.handlers.onLayoutImproved(event);
    }
  }

  private scheduleReconnect(): void {
    const delay = this.retryMs * (0.75 + Math.random() * 0.5);
    this.retryMs = Math.min(this.retryMs * 2, MAX_RETRY_MS);
    this.retryTimer = window.setTimeout(() => {
      this.retryTimer = 0;
      this.connect();
    }, delay);
  }
}
