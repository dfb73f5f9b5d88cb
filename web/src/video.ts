// The console's stereo video: one H.264 StreamPairs stream with receipts, decoded by WebCodecs
// (both eyes side by side in one picture), drawn into the two eye canvases with the AR ball;
// GetSnapshot JPEG polling where WebCodecs is missing (an insecure context) or keeps failing.
//
// What the operator sees is measured as clients/python/video_meter.py does: a frame counts when
// both eyes are drawn, its age is that moment minus the capture time of the earlier eye (wall
// clock: the station's and this host's). The numbers go to the page and to `window.videoStats`
// (the raw samples, for tests and the curious).
import { timestampMs } from "@bufbuild/protobuf/wkt";
import type { Client } from "@connectrpc/connect";

import {
  ImageEncoding, type StereoCamera, type StereoHeader, type StereoPair,
} from "./gen/telerobot/v1/stereo_camera_pb";

export type Point = { x: number; y: number; z: number };

/** One frame as shown. Times are wall-clock ms: the age (capture -> both eyes drawn), and the
 * age when its bytes arrived; then the time in the decoder (H.264) and in drawing. */
export interface VideoSample {
  shownMs: number;
  ageMs: number;
  receivedAgeMs: number;
  decodeMs: number;
  drawMs: number;
  bytes: number;  // received for this frame
  targetKbit: number;  // the sender's target (H.264)
  renderScale: number;  // of the picture's width and height, what the camera drew (1: all)
  sequence: number;
}

/** Now on the wall clock, in ms (sub-millisecond). */
const wallMs = () => performance.timeOrigin + performance.now();

const KEEP_SAMPLES = 4000;  // a little over 2 minutes at 30 fps
const LIVE_WINDOW_MS = 2000;  // the status line's window

/** The frames shown, and the page's figures over the last LIVE_WINDOW_MS. */
export class VideoStats {
  codec = "";  // "h264 (avc1.PPCCLL)" or "jpeg"
  decoder = "";  // "webcodecs" or "snapshots"
  fallbackReason = "";  // why the page polls JPEG snapshots, if it does
  frames = 0;
  decodeErrors = 0;
  keyframeRequests = 0;
  receipts = 0;
  receiptsBySocket = 0;  // of which went on the receipts WebSocket (the rest as Connect calls)
  skipped = 0;  // decoded frames never drawn: a newer one came while the last was being drawn
  decoderWaits = 0;  // times the page stopped reading the stream while its decoder caught up
  samples: VideoSample[] = [];

  shown(sample: Omit<VideoSample, "shownMs" | "ageMs">, captureMs: number): void {
    const shownMs = wallMs();
    this.samples.push({ ...sample, shownMs, ageMs: shownMs - captureMs });
    if (this.samples.length > KEEP_SAMPLES) this.samples.splice(0, this.samples.length - KEEP_SAMPLES);
    this.frames++;
  }

  /** fps, age percentiles, kbit/s over the last `windowMs`, and the newest target. */
  live(windowMs = LIVE_WINDOW_MS) {
    const now = wallMs();
    const recent = this.samples.filter((s) => s.shownMs >= now - windowMs);
    const ages = recent.map((s) => s.ageMs).sort((a, b) => a - b);
    const pick = (q: number) => (ages.length ? ages[Math.min(ages.length - 1, Math.floor(q * ages.length))] : NaN);
    return {
      fps: recent.length * 1000 / windowMs,
      ageP50: pick(0.5),
      ageP95: pick(0.95),
      kbitPerS: recent.reduce((sum, s) => sum + s.bytes, 0) * 8 / windowMs,
      targetKbit: recent.length ? recent[recent.length - 1].targetKbit : 0,
      renderScale: recent.length ? recent[recent.length - 1].renderScale : NaN,
    };
  }
}

/** The WebCodecs codec string of an H.264 stream, "avc1.PPCCLL", from the first SPS NAL unit
 * of an Annex B access unit (profile_idc, constraint flags, level_idc); undefined without one. */
export function codecFromAnnexB(data: Uint8Array): string | undefined {
  const hex = (b: number) => b.toString(16).padStart(2, "0").toUpperCase();
  for (let i = 0; i + 6 < data.length; i++) {
    if (data[i] === 0 && data[i + 1] === 0 && data[i + 2] === 1) {
      if ((data[i + 3] & 0x1f) === 7) return `avc1.${hex(data[i + 4])}${hex(data[i + 5])}${hex(data[i + 6])}`;
      i += 2;
    }
  }
  return undefined;
}

/** Where a base-frame point lands in an eye's image (its 3x4 projection), if in front of it. */
function project(P: number[], p: Point): [number, number] | undefined {
  if (P.length !== 12) return undefined;
  const u = P[0] * p.x + P[1] * p.y + P[2] * p.z + P[3];
  const v = P[4] * p.x + P[5] * p.y + P[6] * p.z + P[7];
  const w = P[8] * p.x + P[9] * p.y + P[10] * p.z + P[11];
  return w > 1e-6 ? [u / w, v / w] : undefined;
}

/** One eye's canvas: an image, then the AR ball at the tool point. */
class Eye {
  private image: ImageData | undefined;

  constructor(readonly canvas: HTMLCanvasElement) {}

  /** RGBA pixels of a w x h image, to be filled and then put by `show`. */
  pixels(w: number, h: number): ImageData {
    if (this.image?.width !== w || this.image.height !== h) this.image = new ImageData(w, h);
    return this.image;
  }

  /** Puts `image` (this eye's `pixels`, or a region of a drawable source) and the ball. */
  show(image: ImageData | { source: CanvasImageSource; sx: number; sy: number; w: number; h: number },
       P: number[], point: Point | undefined, sequence: bigint) {
    const w = image instanceof ImageData ? image.width : image.w;
    const h = image instanceof ImageData ? image.height : image.h;
    const canvas = this.canvas;
    if (canvas.width !== w) canvas.width = w;
    if (canvas.height !== h) canvas.height = h;
    const ctx = canvas.getContext("2d")!;
    if (image instanceof ImageData) ctx.putImageData(image, 0, 0);
    else ctx.drawImage(image.source, image.sx, image.sy, w, h, 0, 0, w, h);
    const uv = point && project(P, point);
    if (uv) {  // the AR ball at the tool point, as the station measured it then
      ctx.beginPath();
      ctx.arc(uv[0], uv[1], Math.max(4, w / 60), 0, 2 * Math.PI);
      ctx.fillStyle = "rgba(255, 200, 0, 0.8)";
      ctx.fill();
      ctx.strokeStyle = "#000";
      ctx.stroke();
    }
    canvas.dataset.sequence = String(sequence);
  }
}

/** What the page knows of a frame in the decoder. */
interface Pending {
  pair: StereoPair;
  header: StereoHeader;
  bytes: number;
  receivedMs: number;
  decodedMs: number;
}

const captureMsOf = (pair: StereoPair) => Math.min(
  pair.leftCaptureTime ? timestampMs(pair.leftCaptureTime) : Infinity,
  pair.rightCaptureTime ? timestampMs(pair.rightCaptureTime) : Infinity);

/** Draws decoded side-by-side frames into the two eyes, one at a time: a frame decoded while
 * the last is still being drawn waits, and a newer one replaces it (drawing never queues).
 * Each frame is converted to RGB once, by VideoFrame.copyTo (a canvas's drawImage of a
 * VideoFrame converts the whole picture per call, twice the work for two eyes); where copyTo
 * cannot convert, drawImage. */
class FramePainter {
  private busy = false;
  private next: { frame: VideoFrame; pending: Pending } | undefined;
  private canConvert = true;

  constructor(private left: Eye, private right: Eye, private stats: VideoStats,
              private toolPointAt: (timeMs: number) => Point | undefined) {}

  offer(frame: VideoFrame, pending: Pending) {
    if (this.next) {
      this.next.frame.close();
      this.stats.skipped++;
    }
    this.next = { frame, pending };
    if (!this.busy) void this.drain();
  }

  /** Drops the frame waiting to be drawn (the stream ended). */
  clear() {
    this.next?.frame.close();
    this.next = undefined;
  }

  private async drain() {
    this.busy = true;
    try {
      while (this.next) {
        const { frame, pending } = this.next;
        this.next = undefined;
        try {
          await this.paint(frame, pending);
        } finally {
          frame.close();
        }
      }
    } finally {
      this.busy = false;
    }
  }

  private async paint(frame: VideoFrame, p: Pending) {
    const drawStart = wallMs();
    const { header, pair } = p;
    const w = header.widthPx, h = header.heightPx;
    const captureMs = captureMsOf(pair);
    const point = this.toolPointAt(captureMs);
    const P = [header.left?.projection ?? [], header.right?.projection ?? []];
    let images: [ImageData, ImageData] | undefined;
    if (this.canConvert) {
      images = [this.left.pixels(w, h), this.right.pixels(w, h)];
      try {
        await Promise.all(images.map((image, eye) => frame.copyTo(image.data, {
          rect: { x: eye * w, y: 0, width: w, height: h }, format: "RGBA" })));
      } catch {
        this.canConvert = false;  // this browser's copyTo does not convert to RGBA
        images = undefined;
      }
    }
    if (images) {
      this.left.show(images[0], P[0], point, pair.sequence);
      this.right.show(images[1], P[1], point, pair.sequence);
    } else {
      this.left.show({ source: frame, sx: 0, sy: 0, w, h }, P[0], point, pair.sequence);
      this.right.show({ source: frame, sx: w, sy: 0, w, h }, P[1], point, pair.sequence);
    }
    this.stats.shown({
      receivedAgeMs: p.receivedMs - captureMs, decodeMs: p.decodedMs - p.receivedMs,
      drawMs: wallMs() - drawStart, bytes: p.bytes, targetKbit: pair.targetKbitPerS,
      renderScale: pair.renderScale || 1,  // 0: not said, the full picture
      sequence: Number(pair.sequence),
    }, captureMs);
  }
}

export interface Receipt {
  streamId: string;
  sequence: bigint;
  receivedBytes: bigint;
  wantKeyframe: boolean;
}

export interface VideoOptions {
  camera: Client<typeof StereoCamera>;
  /** Keeps a stream open (reopened with a back-off when it ends), as the page's others. */
  follow: (name: string, open: (signal: AbortSignal) => Promise<void>) => void;
  /** Sends one receipt without waiting for its answer. */
  sendReceipt: (receipt: Receipt) => void;
  /** The tool point the station measured nearest to a wall-clock time (ms). */
  toolPointAt: (timeMs: number) => Point | undefined;
  connected: () => void;
  /** Whether the stream can be asked for a picture that fits the canvases (the station's own
   * camera); a router's video comes at the size the station publishes. */
  scalable: boolean;
  left: HTMLCanvasElement;
  right: HTMLCanvasElement;
  info: HTMLElement;
}

// The decoder may fail this often within DECODE_ERROR_WINDOW_MS before the page falls back to
// JPEG snapshots for good.
const MAX_DECODE_ERRORS = 3;
const DECODE_ERROR_WINDOW_MS = 30_000;
// Frames the decoder may hold waiting before the page stops reading the stream (about 70 ms
// at 30 fps), and how often it looks again where the decoder has no "dequeue" event.
const MAX_DECODE_QUEUE = 2;
const DEQUEUE_POLL_MS = 10;
// Snapshots: at most ~15 pairs/s; each is asked for once the last one is drawn, so a slow
// browser or link always gets the newest pair.
const SNAPSHOT_MIN_INTERVAL_MS = 66;

/** The size per eye to stream: the source's, shrunk to the `shownPx` device pixels its canvas
 * is shown across, even for H.264. Pixels beyond those shown cost the page decoding and
 * drawing, and show nothing more (WebRTC's sinks ask for their size the same way). */
export function streamSize(sourceW: number, sourceH: number, shownPx: number): [number, number] {
  const scale = shownPx > 0 ? Math.min(1, shownPx / sourceW) : 1;
  const even = (v: number) => Math.max(2, 2 * Math.floor(v / 2));
  return [even(sourceW * scale), even(sourceH * scale)];
}

export function startVideo(o: VideoOptions): VideoStats {
  const stats = new VideoStats();
  (window as unknown as { videoStats: VideoStats }).videoStats = stats;
  const left = new Eye(o.left), right = new Eye(o.right);
  const painter = new FramePainter(left, right, stats, o.toolPointAt);
  let fallback = typeof VideoDecoder === "undefined"
    ? "WebCodecs VideoDecoder is missing (it needs a secure context: https or localhost)" : "";
  const errorTimes: number[] = [];

  const infoLine = (header: StereoHeader, how: string) => {
    o.info.textContent = `${header.widthPx}×${header.heightPx} per eye, ${header.source}, ${how}`;
  };

  /** One H.264 stream, until it ends, fails, or the decoder fails too often (then `fallback`). */
  async function streamH264(signal: AbortSignal) {
    stats.codec = "h264";
    stats.decoder = "webcodecs";
    let header: StereoHeader | undefined;
    let received = 0n;
    let decoder: VideoDecoder | undefined;
    let codec = "";
    let waitingForKey = true;  // until a key frame reaches a configured decoder
    let askedForKey = false;
    let newest = 0n;  // the newest sequence received
    const inDecoder = new Map<number, Pending>();  // by the chunk's timestamp: the sequence
    const local = new AbortController();  // ends this stream when the decoder gives up
    signal.addEventListener("abort", () => local.abort(), { once: true });

    const receipt = (sequence: bigint, wantKeyframe: boolean) => {
      if (!header?.streamId) return;
      stats.receipts++;
      if (wantKeyframe) stats.keyframeRequests++;
      o.sendReceipt({ streamId: header.streamId, sequence, receivedBytes: received, wantKeyframe });
    };

    const lost = (why: string) => {  // the decoder lost its reference: a key frame, please
      stats.decodeErrors++;
      const now = performance.now();
      errorTimes.push(now);
      while (errorTimes.length && errorTimes[0] < now - DECODE_ERROR_WINDOW_MS) errorTimes.shift();
      if (decoder && decoder.state !== "closed") decoder.close();
      decoder = undefined;
      inDecoder.clear();
      if (errorTimes.length >= MAX_DECODE_ERRORS) {
        fallback = `the H.264 decoder failed ${errorTimes.length} times (${why})`;
        local.abort();
        return;
      }
      waitingForKey = true;
      askedForKey = true;
      receipt(newest, true);
    };

    const newDecoder = (codecString: string, h: StereoHeader) => {
      const d: VideoDecoder = new VideoDecoder({
        output: (frame) => {
          const pending = inDecoder.get(frame.timestamp);
          for (const key of inDecoder.keys()) if (key <= frame.timestamp) inDecoder.delete(key);
          if (!pending || d !== decoder) {
            frame.close();
            return;
          }
          pending.decodedMs = wallMs();
          painter.offer(frame, pending);
        },
        error: (e) => { if (d === decoder) lost(e.message); },
      });
      // Annex B input (SPS and PPS in band, on every key frame): no description.
      d.configure({ codec: codecString, optimizeForLatency: true,
        codedWidth: 2 * h.widthPx, codedHeight: h.heightPx });
      return d;
    };

    try {
      const source = o.scalable
        ? (await o.camera.getStreamInfo({}, { signal: local.signal })).header : undefined;
      const [widthPx, heightPx] = source
        ? streamSize(source.widthPx, source.heightPx, o.left.clientWidth * devicePixelRatio)
        : [0, 0];  // 0: the source's own size
      const stream = o.camera.streamPairs(
        { encoding: ImageEncoding.H264, receipts: true, widthPx, heightPx },
        { signal: local.signal });
      for await (const r of stream) {
        if (r.content.case === "header") {
          header = r.content.value;
          infoLine(header, "H.264, WebCodecs");
          o.connected();
          continue;
        }
        if (r.content.case !== "pair" || !header) continue;
        const pair = r.content.value;
        const receivedMs = wallMs();
        const bytes = pair.leftImage.length + pair.rightImage.length + pair.videoFrame.length;
        received += BigInt(bytes);
        newest = pair.sequence;
        receipt(pair.sequence, false);  // first, as it arrives: the path's timing, not ours
        if (waitingForKey && !pair.keyframe) {
          if (!askedForKey) { askedForKey = true; receipt(pair.sequence, true); }
          continue;
        }
        if (pair.keyframe) {
          const c = codecFromAnnexB(pair.videoFrame);
          if (!c) { lost("a key frame without an SPS"); continue; }
          if (!decoder || c !== codec) {
            if (decoder && decoder.state !== "closed") decoder.close();
            codec = c;
            decoder = newDecoder(c, header);
            stats.codec = `h264 (${c})`;
          }
          waitingForKey = false;
          askedForKey = false;
        }
        if (!decoder || decoder.state !== "configured") { lost("the decoder closed"); continue; }
        inDecoder.set(Number(pair.sequence), { pair, header, bytes, receivedMs, decodedMs: 0 });
        try {
          decoder.decode(new EncodedVideoChunk({
            type: pair.keyframe ? "key" : "delta", timestamp: Number(pair.sequence),
            data: pair.videoFrame,
          }));
        } catch (e) {
          lost(String(e));
        }
        // A decoder that falls behind (a busy machine) would queue frames without end, unseen
        // by the sender: the receipts left as the frames arrived. Read the next pair only once
        // it has room, so that pairs wait in the transport instead, their receipts come later
        // and the sender paces the stream to what this page decodes.
        const d = decoder;
        while (d && d === decoder && d.state === "configured" && d.decodeQueueSize > MAX_DECODE_QUEUE) {
          stats.decoderWaits++;
          await new Promise<void>((dequeued) => {
            const done = () => {
              d.removeEventListener("dequeue", done);
              clearTimeout(timer);
              dequeued();
            };
            const timer = setTimeout(done, DEQUEUE_POLL_MS);  // a browser without the event
            d.addEventListener("dequeue", done);
          });
        }
      }
    } catch (err) {
      if (!local.signal.aborted || signal.aborted) throw err;  // else: the decoder gave up
    } finally {
      if (decoder && decoder.state !== "closed") decoder.close();
      decoder = undefined;
      painter.clear();
    }
  }

  /** GetSnapshot JPEG pairs, each asked for once the last one is drawn. */
  async function pollSnapshots(signal: AbortSignal) {
    stats.codec = "jpeg";
    stats.decoder = "snapshots";
    stats.fallbackReason = fallback;
    for (;;) {
      const asked = performance.now();
      const r = await o.camera.getSnapshot({ encoding: ImageEncoding.JPEG, jpegQuality: 70 }, { signal });
      const receivedMs = wallMs();
      const header = r.header, pair = r.pair;
      if (!header || !pair) continue;
      o.connected();
      infoLine(header, `JPEG snapshots (${fallback})`);
      const drawStart = wallMs();
      const captureMs = captureMsOf(pair);
      const point = o.toolPointAt(captureMs);
      const bitmaps = await Promise.all([pair.leftImage, pair.rightImage].map((data) =>
        createImageBitmap(new Blob([data as Uint8Array<ArrayBuffer>], { type: "image/jpeg" }))));
      const eyes = [[left, header.left], [right, header.right]] as const;
      eyes.forEach(([eye, calibration], i) => {
        const b = bitmaps[i];
        eye.show({ source: b, sx: 0, sy: 0, w: b.width, h: b.height }, calibration?.projection ?? [],
          point, pair.sequence);
        b.close();
      });
      stats.shown({
        receivedAgeMs: receivedMs - captureMs, decodeMs: 0, drawMs: wallMs() - drawStart,
        bytes: pair.leftImage.length + pair.rightImage.length, targetKbit: 0,
        renderScale: pair.renderScale || 1, sequence: Number(pair.sequence),
      }, captureMs);
      const wait = SNAPSHOT_MIN_INTERVAL_MS - (performance.now() - asked);
      if (wait > 0) await new Promise((done) => setTimeout(done, wait));
    }
  }

  o.follow("video", async (signal) => {
    if (!fallback) await streamH264(signal);
    if (fallback) await pollSnapshots(signal);  // for good, once it came to that
  });
  return stats;
}
