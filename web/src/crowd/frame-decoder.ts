/** The 24-byte little-endian header in front of every binary frame of /crowd/stream. */
export interface FrameHeader {
  /** Per stream, increasing. */
  id: number;
  /** Server time of the frame, ms since the Unix epoch. */
  timestamp: number;
  width: number;
  height: number;
  /** 1 = JPEG. */
  codec: number;
}

export const FRAME_HEADER_BYTES = 24;
const MAGIC = [0x54, 0x4d, 0x46, 0x31]; // "TMF1"
const CODEC_JPEG = 1;

/** A frame as received: header, the image bytes and when it arrived (ms since the epoch, this clock). */
export interface ReceivedFrame {
  header: FrameHeader;
  image: Uint8Array<ArrayBuffer>;
  receivedAt: number;
}

/** Splits a binary message into header and image; throws on a bad magic, codec or length. */
export function parseFrame(buffer: ArrayBuffer, receivedAt: number): ReceivedFrame {
  if (buffer.byteLength <= FRAME_HEADER_BYTES) throw new Error(`a frame of ${buffer.byteLength} bytes has no image`);
  const bytes = new Uint8Array(buffer, 0, 4);
  if (MAGIC.some((byte, i) => bytes[i] !== byte)) throw new Error('a binary message without the TMF1 magic');
  const view = new DataView(buffer);
  const header: FrameHeader = {
    id: view.getUint32(4, true),
    timestamp: view.getFloat64(8, true),
    width: view.getUint16(16, true),
    height: view.getUint16(18, true),
    codec: view.getUint8(20),
  };
  if (header.codec !== CODEC_JPEG) throw new Error(`a frame in codec ${header.codec} (only 1, JPEG, is known)`);
  return { header, image: new Uint8Array(buffer, FRAME_HEADER_BYTES), receivedAt };
}

export interface DecodedFrame extends ReceivedFrame {
  bitmap: ImageBitmap;
}

export interface DecoderHandlers {
  onDecoded(frame: DecodedFrame): void;
  onError(error: unknown, frame: ReceivedFrame): void;
}

/**
 * Decodes JPEG frames one at a time. A frame that arrives while another is decoding waits, and a
 * newer one replaces it (the older is dropped): only the latest frame is decoded next, so a slow
 * decoder skips frames instead of falling behind, and the last frame of a burst is always shown.
 */
export class FrameDecoder {
  private decoding = false;
  private waiting: ReceivedFrame | null = null;
  /** Bumped by reset(): a decode started before it is not delivered. */
  private generation = 0;
  /** Frames replaced before they were decoded. */
  dropped = 0;

  constructor(private readonly handlers: DecoderHandlers) {}

  push(frame: ReceivedFrame): void {
    if (this.decoding) {
      if (this.waiting) this.dropped++;
      this.waiting = frame;
      return;
    }
    void this.decode(frame);
  }

  /** Forgets the waiting frame and the one decoding (another scene, say). */
  reset(): void {
    this.generation++;
    this.waiting = null;
    this.decoding = false;
  }

  private async decode(frame: ReceivedFrame): Promise<void> {
    const generation = this.generation;
    this.decoding = true;
    let bitmap: ImageBitmap | null = null;
    let failure: unknown = null;
    try {
      bitmap = await createImageBitmap(new Blob([frame.image], { type: 'image/jpeg' }));
    } catch (error) {
      failure = error;
    }
    if (generation !== this.generation) {
      bitmap?.close();
      return;
    }
    this.decoding = false;
    if (bitmap) this.handlers.onDecoded({ ...frame, bitmap });
    else this.handlers.onError(failure, frame);
    const next = this.waiting;
    this.waiting = null;
    if (next) void this.decode(next);
  }
}
