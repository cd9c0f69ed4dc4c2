import { isAbort } from '../api/client';

/**
 * One request at a time, the newest wins: starting one aborts the one in flight, and an answer
 * that arrives after a newer request started (or after cancel) is dropped.
 */
export class LatestRequest<R> {
  private controller?: AbortController;
  private generation = 0;

  get busy(): boolean {
    return this.controller !== undefined;
  }

  run(send: (signal: AbortSignal) => Promise<R>, onResult: (result: R) => void, onError: (error: unknown) => void): void {
    this.controller?.abort();
    const controller = new AbortController();
    const generation = ++this.generation;
    this.controller = controller;
    send(controller.signal).then(
      (result) => {
        if (generation !== this.generation) return;
        this.controller = undefined;
        onResult(result);
      },
      (error: unknown) => {
        if (generation !== this.generation || isAbort(error)) return;
        this.controller = undefined;
        onError(error);
      },
    );
  }

  cancel(): void {
    this.generation++;
    this.controller?.abort();
    this.controller = undefined;
  }
}
