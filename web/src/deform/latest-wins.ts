import { isAbort } from '../api/client';

export interface Exchange<B, R> {
  body: B;
  result: R;
  /** Milliseconds from sending the request to having parsed the answer. */
  roundTripMs: number;
}

export interface LatestWinsHandlers<B, R> {
  onResult(exchange: Exchange<B, R>): void;
  onError(error: unknown, body: B): void;
  /** Called whenever a request starts or ends (for a "working…" hint). */
  onBusy?(busy: boolean): void;
}

/**
 * Keeps at most one request in flight and never queues: `want` records the latest state, and
 * when the answer to the request in flight arrives, the latest state is sent if it differs from
 * what was answered. Intermediate states that were never sent are skipped (latest wins).
 * States are compared by their JSON, so callers pass fresh plain objects.
 */
export class LatestWins<B, R> {
  private wanted: { body: B; key: string } | null = null;
  private inFlight: { key: string; controller: AbortController } | null = null;
  /** The state of the last answer (or error): asking for it again sends nothing. */
  private settledKey: string | null = null;
  private generation = 0;

  constructor(
    private readonly send: (body: B, signal: AbortSignal) => Promise<R>,
    private readonly handlers: LatestWinsHandlers<B, R>,
  ) {}

  get busy(): boolean {
    return this.inFlight !== null;
  }

  /** The state to show now; null: nothing to request (a request in flight is answered but dropped). */
  want(body: B | null, force = false): void {
    if (body === null) {
      this.wanted = null;
      return;
    }
    const key = JSON.stringify(body);
    this.wanted = { body, key };
    if (force) this.settledKey = null;
    this.pump();
  }

  /** Forgets everything: a request in flight is cancelled and its answer never delivered. */
  reset(): void {
    this.generation++;
    this.inFlight?.controller.abort();
    this.inFlight = null;
    this.wanted = null;
    this.settledKey = null;
    this.handlers.onBusy?.(false);
  }

  private pump(): void {
    const wanted = this.wanted;
    if (this.inFlight || !wanted || wanted.key === this.settledKey) return;
    const controller = new AbortController();
    const generation = this.generation;
    this.inFlight = { key: wanted.key, controller };
    this.handlers.onBusy?.(true);
    const started = performance.now();
    this.send(wanted.body, controller.signal).then(
      (result) => this.finish(generation, wanted, () => {
        // Only deliver what is still wanted: a state cleared meanwhile stays cleared.
        if (this.wanted) this.handlers.onResult({ body: wanted.body, result, roundTripMs: performance.now() - started });
      }),
      (error: unknown) => this.finish(generation, wanted, () => {
        if (!isAbort(error) && this.wanted) this.handlers.onError(error, wanted.body);
      }),
    );
  }

  private finish(generation: number, sent: { key: string }, deliver: () => void): void {
    if (generation !== this.generation) return;
    this.inFlight = null;
    // A state cleared meanwhile (want(null)) must be sent again if it comes back.
    this.settledKey = this.wanted ? sent.key : null;
    // Send the newest state first, so the server works while we draw this answer.
    this.pump();
    if (!this.inFlight) this.handlers.onBusy?.(false);
    deliver();
  }
}
