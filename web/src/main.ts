// The web console: every call goes through the contracts' generated types. Unary calls and
// server streams use the Connect protocol (binary), Teleoperate a WebSocket of binary
// TeleoperateRequest/Response messages (services/web_console/teleoperate.py).
import { create, fromBinary, toBinary } from "@bufbuild/protobuf";
import { timestampDate, timestampFromMs, timestampMs } from "@bufbuild/protobuf/wkt";
import { Code, ConnectError, createClient, type Interceptor } from "@connectrpc/connect";
import { createConnectTransport } from "@connectrpc/connect-web";

import {
  type AssistanceConfig, AssistanceConfigSchema, CommandOutcome, ConstraintType, ControlMode,
  type ControlState, DecisionServer, RecordingFormat, ReplayState, TeleopSessionState,
  TeleoperateRequestSchema,
  TeleoperateResponseSchema,
} from "./gen/telerobot/v1/decision_server_pb";
import { ForceSensor } from "./gen/telerobot/v1/force_sensor_pb";
import { ProxyRobot } from "./gen/telerobot/v1/proxy_robot_pb";
import { ReportReceiptRequestSchema, StereoCamera } from "./gen/telerobot/v1/stereo_camera_pb";
import { ReferenceFrame, type RobotState, RobotStatus } from "./gen/telerobot/v1/types_pb";
import { type Point, type Receipt, startVideo } from "./video";

const $ = <T extends HTMLElement = HTMLElement>(id: string) => document.getElementById(id) as T;

// A watch-only console (services/web_console/watch.py) says what it watches here: it shows the
// station's observation through a Zenoh router, and has no control to offer.
const watching = document.querySelector<HTMLMetaElement>('meta[name="telerobot-watch"]')?.content ?? "";
if (watching) {
  document.body.classList.add("watching");
  $("watching").hidden = false;
  $("watching").textContent = `watch only: ${watching}`;
}
const linkUp = watching ? "watching" : "station connected";

// ---- session state --------------------------------------------------------------------------
let token = sessionStorage.getItem("telerobot-token") ?? "";
let leaseId = "";
const LEASE_KEY = "telerobot-lease-id";

const headers: Interceptor = (next) => async (req) => {
  if (token) req.header.set("authorization", `Bearer ${token}`);
  if (leaseId) req.header.set(LEASE_KEY, leaseId);
  return next(req);
};
const transport = createConnectTransport({
  baseUrl: location.origin, useBinaryFormat: true, interceptors: [headers],
});
const station = createClient(DecisionServer, transport);
const robot = createClient(ProxyRobot, transport);
const sensor = createClient(ForceSensor, transport);
const camera = createClient(StereoCamera, transport);

function say(text: string, bad = false) {
  const el = $("message");
  el.textContent = text;
  el.style.color = bad ? "#ff8f8f" : "#ffd27f";
}

function explain(err: unknown): string {
  const e = ConnectError.from(err);
  return `${Code[e.code]}: ${e.rawMessage}`;
}

async function act(what: string, call: () => Promise<unknown>) {
  try {
    await call();
    say(`${what}: done`);
  } catch (err) {
    say(`${what}: ${explain(err)}`, true);
  }
}

/** A server stream kept open: reopened when it ends or fails, after a back-off that starts at
 * half a second and doubles to two while the stream keeps failing at once. */
const REOPEN_MIN_MS = 500;
const REOPEN_MAX_MS = 2000;
const HEALTHY_MS = 10_000;  // a stream that lasted this long failed for a new reason: start over
function follow(name: string, open: (signal: AbortSignal) => Promise<void>) {
  const loop = async () => {
    let backoff = REOPEN_MIN_MS;
    for (;;) {
      const ctl = new AbortController();
      const opened = performance.now();
      try {
        await open(ctl.signal);
      } catch (err) {
        const e = ConnectError.from(err);
        if (e.code === Code.FailedPrecondition && name === "state") {
          showStatusOnly(e.rawMessage);  // no arm connected yet: not a broken link
        } else {
          setLink(false, `${name}: ${explain(err)}`);
        }
      }
      ctl.abort();
      if (performance.now() - opened > HEALTHY_MS) backoff = REOPEN_MIN_MS;
      await new Promise((r) => setTimeout(r, backoff));
      backoff = Math.min(2 * backoff, REOPEN_MAX_MS);
    }
  };
  void loop();
}

function setLink(ok: boolean, text: string) {
  const el = $("link");
  el.textContent = text;
  el.title = text;
  el.className = `pill ${ok ? "ok" : "bad"}`;
}

// ---- arm state ------------------------------------------------------------------------------
let lastState: RobotState | undefined;
const statusName = (s: RobotStatus) => RobotStatus[s] ?? String(s);

// The tool point over the last few seconds, so that a frame gets its ball where the tool was
// when the frame was captured (station's clock).
const TOOL_HISTORY_MS = 3000;
const toolHistory: { t: number; p: Point }[] = [];

function toolPointAt(timeMs: number): Point | undefined {
  let best: { t: number; p: Point } | undefined;
  for (const s of toolHistory) if (!best || Math.abs(s.t - timeMs) < Math.abs(best.t - timeMs)) best = s;
  return best?.p ?? lastState?.toolPose?.positionM;
}

function showState(state: RobotState) {
  lastState = state;
  const tool = state.toolPose?.positionM;
  if (tool && state.sampleTime) {
    const t = timestampMs(state.sampleTime);
    toolHistory.push({ t, p: { x: tool.x, y: tool.y, z: tool.z } });
    while (toolHistory.length && toolHistory[0].t < t - TOOL_HISTORY_MS) toolHistory.shift();
  }
  $("status-reason").textContent = "";
  const status = $("status");
  status.textContent = statusName(state.status);
  status.dataset.status = statusName(state.status);
  status.className = `pill ${state.status === RobotStatus.ESTOPPED || state.status === RobotStatus.FAULT
    ? "bad" : state.status === RobotStatus.READY || state.status === RobotStatus.MOVING ? "ok" : "warn"}`;
  $("joints").textContent = state.jointPositionsRad.map((q) => (q * 180 / Math.PI).toFixed(2)).join("  ");
  const p = state.toolPose?.positionM;
  if (p) $("tool-position").textContent = [p.x, p.y, p.z].map((v) => (v * 1000).toFixed(1)).join("  ");
}

function showStatusOnly(reason: string) {
  const status = $("status");
  status.textContent = /NOT_CONNECTED/.test(reason) ? "NOT_CONNECTED" : "unknown";
  status.dataset.status = status.textContent;
  status.className = "pill warn";
  $("status-reason").textContent = reason;
}

// Which arm the station drives (its description file), asked once: it does not change. (A
// router does not carry it.)
if (!watching) {
  robot.getArmInfo({}).then(
    (arm) => { $("arm-name").textContent = `${arm.name} · ${arm.jointNames.length} joints`; },
    () => { $("arm-name").textContent = "arm unknown"; });
}

follow("state", async (signal) => {
  const period = { seconds: 0n, nanos: 50_000_000 };
  for await (const r of robot.streamState({ period }, { signal })) {
    setLink(true, linkUp);
    if (r.state) showState(r.state);
  }
});

// ---- stereo video with the AR ball -----------------------------------------------------------
// Receipts go out as each pair arrives, without waiting for the answer (video.ts), on a
// WebSocket of their own: as Connect calls they would wait for one of HTTP/1.1's six
// connections to the console, which the page's streams mostly hold (services/web_console/
// receipts.py). Until the socket is open, or when it is refused, they go as Connect calls.
let receiptSocket: WebSocket | undefined;
let receiptBackoff = REOPEN_MIN_MS;
function openReceiptSocket() {
  const url = `${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws/receipts`;
  const s = new WebSocket(url, ["telerobot.v1.receipts", ...(token ? [`bearer.${token}`] : [])]);
  s.binaryType = "arraybuffer";
  s.onopen = () => { receiptSocket = s; receiptBackoff = REOPEN_MIN_MS; };
  s.onclose = () => {
    if (receiptSocket === s) receiptSocket = undefined;
    setTimeout(openReceiptSocket, receiptBackoff);
    receiptBackoff = Math.min(2 * receiptBackoff, REOPEN_MAX_MS);
  };
}
// A watch-only console sends none: the router's video is paced by the station alone.
if (!watching) openReceiptSocket();

function sendReceipt(r: Receipt) {
  if (watching) return;
  if (receiptSocket?.readyState === WebSocket.OPEN) {
    receiptSocket.send(toBinary(ReportReceiptRequestSchema, create(ReportReceiptRequestSchema, r)));
    video.receiptsBySocket++;
  } else {
    camera.reportReceipt(r).catch(() => undefined);  // NOT_FOUND: the stream ended meanwhile
  }
}

const video = startVideo({
  camera, follow, sendReceipt, toolPointAt,
  connected: () => setLink(true, linkUp), scalable: !watching,
  left: $<HTMLCanvasElement>("left-eye"), right: $<HTMLCanvasElement>("right-eye"),
  info: $("video-info"),
});

// The figures, twice a second: on the page, and as data-* attributes of #video-stats.
setInterval(() => {
  const live = video.live();
  const shown = (v: number, digits = 0) => (Number.isFinite(v) ? v.toFixed(digits) : "–");
  $("video-age").textContent = shown(live.ageP50);
  $("video-age-p95").textContent = shown(live.ageP95);
  $("fps").textContent = shown(live.fps, 1);
  $("video-kbit").textContent = shown(live.kbitPerS);
  $("video-target").textContent = live.targetKbit ? String(live.targetKbit) : "–";
  $("video-detail").textContent = shown(live.renderScale, 2);
  $("video-codec").textContent = video.decoder ? `${video.codec}, ${video.decoder}` : "–";
  const el = $("video-stats");
  Object.assign(el.dataset, {
    codec: video.codec, decoder: video.decoder, frames: String(video.frames),
    fps: live.fps.toFixed(1), ageP50: shown(live.ageP50, 1), ageP95: shown(live.ageP95, 1),
    kbitPerS: live.kbitPerS.toFixed(0), targetKbitPerS: String(live.targetKbit),
    renderScale: shown(live.renderScale, 3),
    decodeErrors: String(video.decodeErrors), fallback: video.fallbackReason,
  });
}, 500);

// ---- force plot -------------------------------------------------------------------------------
const forceWindowMs = 10_000;
const forces: { t: number; f: [number, number, number] }[] = [];

function plotForces() {
  const canvas = $<HTMLCanvasElement>("force-plot");
  const ctx = canvas.getContext("2d")!;
  const { width, height } = canvas;
  ctx.clearRect(0, 0, width, height);
  const now = Date.now();
  while (forces.length && forces[0].t < now - forceWindowMs) forces.shift();
  const peak = Math.max(5, ...forces.flatMap((s) => s.f.map(Math.abs)));
  ctx.strokeStyle = "#ccc";
  ctx.beginPath();
  ctx.moveTo(0, height / 2);
  ctx.lineTo(width, height / 2);
  ctx.stroke();
  ctx.fillStyle = "#888";
  ctx.fillText(`±${peak.toFixed(1)} N`, 4, 12);
  ["#d62728", "#2ca02c", "#1f77b4"].forEach((color, axis) => {
    ctx.strokeStyle = color;
    ctx.beginPath();
    forces.forEach((s, i) => {
      const x = width - ((now - s.t) / forceWindowMs) * width;
      const y = height / 2 - (s.f[axis] / peak) * (height / 2 - 4);
      if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    });
    ctx.stroke();
  });
}
// Ten times a second, on an animation frame: a 10 s plot moves a pixel or so per redraw, and a
// redraw on every animation frame (60/s) would make the browser composite the page 60 times a
// second, which costs the video its CPU on a small machine.
const PLOT_INTERVAL_MS = 100;
setInterval(() => requestAnimationFrame(plotForces), PLOT_INTERVAL_MS);

follow("force", async (signal) => {
  // 50 Hz, 5 samples a message: plenty for a plot, light on the browser.
  for await (const r of sensor.streamWrench({ decimation: 20, batchSize: 5 }, { signal })) {
    for (const s of r.samples) {
      const f = s.wrench?.forceN;
      if (!f || !s.sampleTime) continue;
      forces.push({ t: timestampMs(s.sampleTime), f: [f.x, f.y, f.z] });
      $("force-now").textContent = `${Math.hypot(f.x, f.y, f.z).toFixed(2)} N`;
    }
  }
});

// ---- control lock -------------------------------------------------------------------------------
function showControl(state: ControlState | undefined) {
  if (!state) return;
  const names = (hs: { operatorId: string }[]) => hs.map((h) => h.operatorId).join(", ") || "none";
  $("lock-holders").textContent = names(state.holders);
  $("lock-waiters").textContent = names(state.waiters);
}

function setLease(id: string) {
  leaseId = id;
  const el = $("lock-state");
  el.textContent = id ? "held by this tab" : "not held";
  el.dataset.held = id ? "yes" : "no";
  $<HTMLButtonElement>("lock-release").disabled = !id;
  if (!id) stopDriving("the lock was released");
}

let queueAbort: AbortController | undefined;
async function acquire(wait: boolean) {
  queueAbort?.abort();
  queueAbort = new AbortController();
  if (wait) $("lock-state").textContent = "waiting in the queue…";
  try {
    const r = await station.acquireControl({
      operatorId: $<HTMLInputElement>("operator").value, mode: ControlMode.EXCLUSIVE, wait,
    }, { signal: queueAbort.signal, timeoutMs: wait ? 600_000 : undefined });  // a queue may be long
    setLease(r.leaseId);
    showControl(r.state);
    say(`lock granted to ${r.operatorId}`);
  } catch (err) {
    setLease(leaseId);
    say(`take the lock: ${explain(err)}`, true);
  }
}
$("lock-acquire").onclick = () => acquire(false);
$("lock-queue").onclick = () => acquire(true);
$("lock-release").onclick = async () => {
  queueAbort?.abort();
  const id = leaseId;
  setLease("");
  await act("release", async () => showControl((await station.releaseControl({ leaseId: id })).state));
};
// Every authorized call renews the lease; an idle tab renews it itself.
setInterval(async () => {
  if (!leaseId) return;
  try {
    await station.renewControl({ leaseId });
  } catch (err) {
    setLease("");
    say(`the lock was lost: ${explain(err)}`, true);
  }
}, 1500);

// ---- arm and sensor buttons ------------------------------------------------------------------
$("arm-connect").onclick = () => act("connect", () => robot.connect({}));
$("arm-initialize").onclick = () => act("initialize", () => robot.initialize({}));
$("arm-reset").onclick = () => act("reset", () => robot.reset({}));
$("sensor-start").onclick = () => act("start sensor", () => sensor.startReading({}));
$("sensor-tare").onclick = () => act("tare", () => sensor.tare({ duration: { seconds: 0n, nanos: 100_000_000 } }));

async function emergencyStop() {
  stopDriving("emergency stop");
  try {
    const r = await robot.emergencyStop({ reason: "web console STOP button" });
    say(`STOPPED: ${statusName(r.status)}`, true);
  } catch (err) {
    say(`STOP failed: ${explain(err)}; use the emergency-stop band`, true);
  }
}
$("estop").onclick = emergencyStop;

// ---- assistance ---------------------------------------------------------------------------------
let assistance: AssistanceConfig = create(AssistanceConfigSchema, {});
function showAssistance(a: AssistanceConfig | undefined) {
  if (!a) return;
  assistance = a;
  const scale = a.scaling?.translationScale ?? 0;
  $<HTMLInputElement>("assist-scaling").checked = scale > 0 && scale !== 1;
  $<HTMLInputElement>("assist-planar").checked = a.constraint?.type === ConstraintType.PLANAR;
  $<HTMLInputElement>("assist-floating").checked = !!a.floatingToolFrame?.enabled;
  $("assist-state").textContent =
    `scale ${scale || 1}, constraint ${ConstraintType[a.constraint?.type ?? 0]}, ` +
    `floating ${a.floatingToolFrame?.enabled ? "on" : "off"}, force control ${a.forceControl?.enabled ? "on" : "off"}`;
}
async function setAssistance() {
  const next = create(AssistanceConfigSchema, assistance);
  next.scaling = $<HTMLInputElement>("assist-scaling").checked
    ? { $typeName: "telerobot.v1.Scaling", translationScale: 0.5, rotationScale: 0.5 } : undefined;
  next.constraint = $<HTMLInputElement>("assist-planar").checked
    ? { $typeName: "telerobot.v1.MotionConstraint", type: ConstraintType.PLANAR,
        axis: { $typeName: "telerobot.v1.Vector3", x: 0, y: 0, z: 1 }, frame: ReferenceFrame.BASE }
    : undefined;
  next.floatingToolFrame = { $typeName: "telerobot.v1.FloatingToolFrame",
    enabled: $<HTMLInputElement>("assist-floating").checked, pointM: lastState?.toolPose?.positionM };
  try {
    showAssistance((await station.setAssistance({ assistance: next })).assistance);
    say("assistance set");
  } catch (err) {
    showAssistance(assistance);
    say(`assistance: ${explain(err)}`, true);
  }
}
for (const id of ["assist-scaling", "assist-planar", "assist-floating"]) $(id).onchange = setAssistance;
station.getAssistance({}).then((r) => showAssistance(r.assistance), () => undefined);

// ---- record and replay ----------------------------------------------------------------------------
async function listRecordings() {
  try {
    const r = await station.listRecordings({});
    const select = $<HTMLSelectElement>("rec-list");
    select.replaceChildren(...r.recordings.map((rec) => new Option(rec.name, rec.name)));
  } catch { /* shown by the buttons */ }
}
$("rec-start").onclick = () => act("record", () => {
  // A task makes the recording a demonstration episode, which is recorded as MCAP.
  const task = $<HTMLInputElement>("rec-task").value.trim();
  return station.startRecording({ name: $<HTMLInputElement>("rec-name").value, task,
    format: task ? RecordingFormat.MCAP : RecordingFormat.UNSPECIFIED });
});
$("rec-stop").onclick = () => act("stop recording", async () => {
  await station.stopRecording({ outcome: Number($<HTMLSelectElement>("rec-outcome").value) });
  await listRecordings();
});
$("replay-start").onclick = () => act("replay", () => station.startReplay({ name: $<HTMLSelectElement>("rec-list").value, speed: 1 }));
$("replay-stop").onclick = () => act("stop replay", () => station.stopReplay({}));
if (!watching) void listRecordings();

// ---- events ------------------------------------------------------------------------------------
function logEvent(text: string) {
  const li = document.createElement("li");
  li.textContent = text;
  const list = $("events");
  list.prepend(li);
  while (list.children.length > 50) list.lastElementChild?.remove();
}
follow("events", async (signal) => {
  station.getControlState({}).then((r) => showControl(r.state), () => undefined);
  for await (const e of station.streamEvents({}, { signal })) {
    const when = e.eventTime ? timestampDate(e.eventTime).toLocaleTimeString() : "";
    const ev = e.event;
    if (ev.case === "controlChanged") showControl(ev.value.state);
    if (ev.case === "assistanceChanged") showAssistance(ev.value.assistance);
    if (ev.case === "replayProgress") {
      $("replay-state").textContent = `${ev.value.name}: ${ReplayState[ev.value.state]} ${ev.value.detail}`;
    }
    if (ev.case === "watchdogHold") $("drive-state").dataset.watchdog = ev.value.reason;
    let detail = "";
    if (ev.case === "watchdogHold" || ev.case === "controlChanged") detail = ev.value.reason;
    if (ev.case === "recordingFailed") {
      detail = `${ev.value.name}: ${ev.value.reason}`;
      say(`recording ${ev.value.name} stopped by itself: ${ev.value.reason}`, true);
    }
    if (ev.case === "teleopSession") {
      detail = `${TeleopSessionState[ev.value.state]} ${ev.value.operatorId} ${ev.value.reason}`;
    }
    if (ev.case === "robot") {
      const r = ev.value.event;
      if (r.case === "moved") continue;  // one per move: too many to list
      if (r.case === "statusChanged") detail = `${statusName(r.value.status)} ${r.value.reason}`;
      else if (r.case === "error") detail = `${r.value.reason} ${r.value.message}`;
      else detail = r.case ?? "";
    }
    logEvent(`${when} ${ev.case ?? "?"} ${detail}`);
  }
});

// ---- driving: one Teleoperate session over a WebSocket --------------------------------------------
const TICK_MS = 20;           // 50 Hz: a command when moving, a heartbeat otherwise
const WATCHDOG_MS = 500;      // the station holds the arm after this long without a message
let socket: WebSocket | undefined;
let ticker: number | undefined;
let sequence = 0n;
let sent = 0, acked = 0;
const sendTimes = new Map<bigint, number>();
const jogs = new Set<string>();  // "x+", "z-", ... held by keys or buttons

function driveState(text: string, cls: string) {
  const el = $("drive-state");
  el.textContent = text;
  el.className = `pill ${cls}`;
  $("drive-toggle").textContent = socket ? "Stop driving" : "Start driving";
}

function stopDriving(why: string) {
  if (ticker !== undefined) clearInterval(ticker);
  ticker = undefined;
  jogs.clear();
  if (socket) {
    const s = socket;
    socket = undefined;
    // The session ends for good (no resume window: the arm is held now, and a replay or
    // another session may start at once); then a clean close.
    if (s.readyState === WebSocket.OPEN) {
      s.send(toBinary(TeleoperateRequestSchema, create(TeleoperateRequestSchema, {
        message: { case: "end", value: {} } })));
    }
    s.close(1000, why.slice(0, 100));
    driveState("off", "");
  }
}

function send(message: Parameters<typeof create<typeof TeleoperateRequestSchema>>[1]) {
  if (socket?.readyState !== WebSocket.OPEN) return;
  socket.send(toBinary(TeleoperateRequestSchema, create(TeleoperateRequestSchema, message)));
}

function velocity(): [number, number, number] {
  const v: [number, number, number] = [0, 0, 0];
  for (const j of jogs) v["xyz".indexOf(j[0])] += j[1] === "+" ? 1 : -1;
  const pad = navigator.getGamepads?.().find((g) => g);
  $("gamepad").textContent = pad ? pad.id : "no gamepad";
  if (pad) {  // left stick: x, y; right stick vertical: z; a 0.15 dead zone
    const dz = (a: number) => (Math.abs(a) < 0.15 ? 0 : a);
    v[0] += -dz(pad.axes[1] ?? 0);
    v[1] += -dz(pad.axes[0] ?? 0);
    v[2] += -dz(pad.axes[3] ?? 0);
  }
  return v;
}

function tick() {
  const v = velocity();
  const speed = Number($<HTMLSelectElement>("speed").value) / 1000;  // m/s
  const step = (TICK_MS / 1000) * speed;
  const now = Date.now();
  if (v.some((c) => c !== 0)) {
    sequence += 1n;
    sendTimes.set(sequence, performance.now());
    send({ message: { case: "command", value: {
      sequence, sendTime: timestampFromMs(now),
      deltaPositionM: { x: v[0] * step, y: v[1] * step, z: v[2] * step },
    } } });
    $("sent").textContent = String(++sent);
  } else {
    send({ message: { case: "heartbeat", value: { sendTime: timestampFromMs(now) } } });
  }
}

function startDriving() {
  if (!leaseId) { say("take the lock first", true); return; }
  const url = `${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws/teleoperate`;
  const protocols = ["telerobot.v1.teleoperate", ...(token ? [`bearer.${token}`] : [])];
  const s = new WebSocket(url, protocols);
  s.binaryType = "arraybuffer";
  socket = s;
  driveState("opening", "warn");
  s.onopen = () => {
    send({ message: { case: "init", value: {
      operatorId: $<HTMLInputElement>("operator").value, leaseId, mapping: ReferenceFrame.BASE,
      watchdogTimeout: { seconds: 0n, nanos: WATCHDOG_MS * 1_000_000 },
    } } });
  };
  s.onmessage = (m) => {
    const r = fromBinary(TeleoperateResponseSchema, new Uint8Array(m.data as ArrayBuffer));
    if (r.message.case === "ready") {
      driveState("driving", "ok");
      ticker = window.setInterval(tick, TICK_MS);
    } else if (r.message.case === "ack") {
      const ack = r.message.value;
      const t0 = sendTimes.get(ack.sequence);
      if (t0 !== undefined) {
        $("rtt").textContent = (performance.now() - t0).toFixed(1);
        sendTimes.delete(ack.sequence);
      }
      $("acked").textContent = String(++acked);
      $("outcome").textContent = `${CommandOutcome[ack.outcome]} ${ack.detail}`;
    }
  };
  s.onclose = (e) => {
    if (socket === s) {
      socket = undefined;
      if (ticker !== undefined) clearInterval(ticker);
      ticker = undefined;
      driveState("off", e.code === 1000 ? "" : "bad");
      if (e.code !== 1000) say(`driving ended: ${e.code >= 4000 ? Code[e.code - 4000] ?? e.code : e.code} ${e.reason}`, true);
    }
  };
}
$("drive-toggle").onclick = () => (socket ? stopDriving("stopped by the operator") : startDriving());

const KEYS: Record<string, string> = { w: "x+", s: "x-", a: "y+", d: "y-", r: "z+", f: "z-" };
addEventListener("keydown", (e) => {
  if ((e.target as HTMLElement).tagName === "INPUT") return;
  if ((e.key === " " || e.key === "Escape") && !watching) {
    e.preventDefault();
    void emergencyStop();
    return;
  }
  const jog = KEYS[e.key.toLowerCase()];
  if (jog) { jogs.add(jog); e.preventDefault(); }
});
addEventListener("keyup", (e) => { const jog = KEYS[e.key.toLowerCase()]; if (jog) jogs.delete(jog); });
addEventListener("blur", () => jogs.clear());
for (const b of document.querySelectorAll<HTMLButtonElement>("[data-jog]")) {
  const jog = b.dataset.jog!;
  b.onpointerdown = () => jogs.add(jog);
  for (const ev of ["pointerup", "pointerleave", "pointercancel"] as const) b.addEventListener(ev, () => jogs.delete(jog));
}
// A hidden tab must not keep driving: end the session, so the station holds the arm at once.
document.addEventListener("visibilitychange", () => { if (document.hidden) stopDriving("the tab was hidden"); });
addEventListener("pagehide", () => stopDriving("the tab was closed"));

setLease("");

// ---- bearer tokens ---------------------------------------------------------------------------
if (document.querySelector<HTMLMetaElement>('meta[name="telerobot-auth"]')?.content === "token") {
  $("auth").hidden = false;
  $<HTMLInputElement>("token").value = token;
  $("auth").onsubmit = (e) => {
    e.preventDefault();
    token = $<HTMLInputElement>("token").value.trim();
    sessionStorage.setItem("telerobot-token", token);
    say(token ? "token set" : "token cleared");
  };
}
