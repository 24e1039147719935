// The live page: a Foxglove WebSocket client (subprotocol foxglove.websocket.v1)
// of the server that serves it. It subscribes to every channel advertised but
// the raw images (it takes their /compressed twins) and draws each sensor's
// frames under each setting, its fused image and static frame, a plot per
// metric over the last minutes, and the rig's status.
// window.vkfuseLive is what the tests read (tests/serve).
"use strict";

const PLOT_SECONDS = 180;
const METRICS = [["sharpness", "Sharpness"], ["contrast", "RMS contrast"], ["background_diff", "Difference with background"]];
const COLOURS = ["#4d7cfe", "#3fb950", "#d29922", "#f85149", "#a371f7", "#39c5cf", "#ff7b72", "#e3b341"];

const live = {
  channels: new Map(),   // channel id -> {topic, kind, token}
  subscriptions: new Map(),  // subscription id -> channel id
  sensors: new Map(),    // serial token -> sensor card
  cycles: new Map(),     // message time (ns, as text) -> cycle
  series: new Map(),     // serial -> {metric: [[t, v]...]}
  rig: null, frozen: false, drawn: 0, metricMessages: 0, statusMessages: 0, errors: [],
};
window.vkfuseLive = {
  // Every sensor's fused image and one image per setting drawn at least once.
  ready: () => live.rig !== null && [...live.sensors.values()].every((s) => [...s.figures.values()].every((f) => f.drawn)),
  freeze: () => { live.frozen = true; },
  unfreeze: () => { live.frozen = false; },
  // What each canvas shows: its topic, the cycle it is from, its pixels (RGBA, base64).
  canvases: () => [...document.querySelectorAll("canvas[data-topic]")].map((c) => ({
    topic: c.dataset.topic, cycle: Number(live.cycles.get(c.dataset.stamp) ?? -1), width: c.width, height: c.height,
    rgba: base64(c.getContext("2d").getImageData(0, 0, c.width, c.height).data),
  })),
  points: () => Math.min(...[...live.series.values()].flatMap((m) => Object.values(m).map((p) => p.length))),
  stats: () => ({ drawn: live.drawn, metrics: live.metricMessages, status: live.statusMessages, errors: live.errors }),
};

function base64(bytes) {
  let text = "";
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) if (k === "class") e.className = v; else e.setAttribute(k, v);
  for (const c of children) e.append(c);
  return e;
}

// sensor_msgs/msg/CompressedImage (png or jpeg) in CDR, decoded by the browser
// (colour management off: a PNG's samples reach the canvas as they are).
function decodeCompressed(view) {
  let at = 4;
  const u32 = () => { at += (4 - ((at - 4) % 4)) % 4; const v = view.getUint32(at, true); at += 4; return v; };
  u32(); u32();  // stamp
  const skip = () => { const n = u32(); at += n; };  // a string (after u32() has moved past its length)
  skip();        // frame_id
  const formatLength = u32();
  const format = new TextDecoder().decode(new Uint8Array(view.buffer, view.byteOffset + at, Math.max(formatLength - 1, 0)));
  at += formatLength;
  const n = u32();
  const blob = new Blob([new Uint8Array(view.buffer, view.byteOffset + at, n)], { type: `image/${format}` });
  return createImageBitmap(blob, { colorSpaceConversion: "none", premultiplyAlpha: "none" });
}

function sensorCard(token, info) {
  if (live.sensors.has(token)) return live.sensors.get(token);
  const state = el("span", { class: "state" }, "waiting");
  const images = el("div", { class: "images" });
  const card = el("section", { class: "sensor" }, el("h2", {}, info ? `${info.serial}` : token, el("span", { class: "model" }, info ? ` ${info.model}` : ""), state), images);
  document.getElementById("sensors").append(card);
  const s = { card, images, state, figures: new Map() };
  live.sensors.set(token, s);
  return s;
}

function figure(sensor, topic, caption, kind) {
  if (sensor.figures.has(topic)) return sensor.figures.get(topic);
  const canvas = el("canvas", { "data-topic": topic });
  const label = el("figcaption");
  label.innerHTML = caption;
  const cycle = el("span", { class: "cycle" });
  label.append(cycle);
  const f = { canvas, label, cycle, drawn: false, el: el("figure", { class: kind }, canvas, label) };
  sensor.figures.set(topic, f);
  // Fused first, then the settings in sequence order, as channels were advertised.
  sensor.images.append(f.el);
  return f;
}

function setupChannels(channels) {
  const rig = live.rig;
  for (const c of channels) {
    const m = c.topic.match(/^\/vkfuse\/([A-Za-z0-9_]+)\/(fused\/compressed|metrics|lit\/(led(?:_\d+)+)\/compressed)$/);
    const ch = { topic: c.topic, kind: m ? m[2].split("/")[0] : c.topic.slice(8), token: m ? m[1] : null };
    live.channels.set(c.id, ch);
    if (!m || !rig) continue;
    const k = rig.sensors.findIndex((s) => s.token === ch.token);
    const sensor = sensorCard(ch.token, rig.sensors[k]);
    if (ch.kind === "fused") figure(sensor, c.topic, `<b>fused</b> ${rig.method}`, "fused");
    if (ch.kind === "lit") {
      const levels = m[3].slice(4).split("_").join(",");
      const slot = rig.sequence.indexOf(levels);
      const isStatic = slot === rig.static_slot;
      figure(sensor, c.topic, `<b>${levels}</b>${isStatic ? " static" : ""}`, isStatic ? "static" : "lit");
    }
  }
}

// Images are drawn once per animation frame, the newest of each canvas only:
// a burst of messages costs one draw, and a hidden tab none.
const toDraw = new Map();  // topic -> [channel, stamp, image]
function draw(ch, stamp, image) {
  if (live.frozen) {
    image.close();
    return;
  }
  if (!toDraw.size) requestAnimationFrame(flush);
  const replaced = toDraw.get(ch.topic);
  if (replaced) replaced[2].close();
  toDraw.set(ch.topic, [ch, stamp, image]);
}

function flush() {
  for (const [ch, stamp, image] of toDraw.values()) paint(ch, stamp, image);
  toDraw.clear();
}

function paint(ch, stamp, image) {
  const sensor = live.sensors.get(ch.token);
  if (!sensor || live.frozen) return;
  const f = sensor.figures.get(ch.topic);
  const c = f.canvas;
  if (c.width !== image.width || c.height !== image.height) { c.width = image.width; c.height = image.height; }
  c.getContext("2d").drawImage(image, 0, 0);
  image.close();
  c.dataset.stamp = stamp;
  // Text changed only when it differs: every change costs the page a layout.
  const cycle = live.cycles.get(stamp);
  const text = cycle === undefined ? "" : ` · cycle ${cycle}`;
  if (f.cycle.textContent !== text) f.cycle.textContent = text;
  f.drawn = true;
  live.drawn++;
}

function plots() {
  const box = document.getElementById("plots");
  if (box.childElementCount) return;
  for (const [key, title] of METRICS) {
    const legend = el("div", { class: "legend" });
    const canvas = el("canvas", { "data-metric": key, width: 600, height: 160 });
    box.append(el("div", { class: "plot" }, el("h3", {}, title), canvas, legend));
  }
}

function drawPlots() {
  const now = performance.now() / 1000;
  // The last PLOT_SECONDS, or since the first point while there is less.
  let first = now;
  for (const m of live.series.values()) for (const pts of Object.values(m)) if (pts.length) first = Math.min(first, pts[0][0]);
  const span = Math.min(PLOT_SECONDS, Math.max(10, now - first));
  for (const [key] of METRICS) {
    const canvas = document.querySelector(`canvas[data-metric="${key}"]`);
    const ctx = canvas.getContext("2d");
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    let lo = Infinity, hi = -Infinity;
    for (const m of live.series.values()) for (const [, v] of m[key] ?? []) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    if (!isFinite(lo)) continue;
    if (hi - lo < 1e-12) { hi += 1e-6; lo -= 1e-6; }
    ctx.fillStyle = "#8d8d99"; ctx.font = "11px system-ui";
    ctx.fillText(hi.toPrecision(4), 4, 12); ctx.fillText(lo.toPrecision(4), 4, canvas.height - 4);
    let i = 0;
    const legend = canvas.nextSibling;
    legend.innerHTML = "";
    for (const [serial, m] of live.series) {
      const colour = COLOURS[i++ % COLOURS.length];
      legend.append(el("span", {}, el("i", { style: `background:${colour}` }), serial));
      const pts = (m[key] ?? []).filter(([t]) => now - t < span);
      ctx.strokeStyle = colour; ctx.lineWidth = 1.5; ctx.beginPath();
      pts.forEach(([t, v], n) => {
        const x = canvas.width - (now - t) / span * canvas.width;
        const y = canvas.height - 6 - (v - lo) / (hi - lo) * (canvas.height - 18);
        n ? ctx.lineTo(x, y) : ctx.moveTo(x, y);
      });
      ctx.stroke();
    }
  }
}

function onMetrics(stamp, m) {
  live.metricMessages++;
  live.cycles.set(stamp, m.cycle);
  if (live.cycles.size > 512) live.cycles.delete(live.cycles.keys().next().value);
  const series = live.series.get(m.sensor) ?? {};
  live.series.set(m.sensor, series);
  const t = performance.now() / 1000;
  for (const [key] of METRICS) {
    if (typeof m[key] !== "number") continue;
    (series[key] ??= []).push([t, m[key]]);
    while (series[key].length && t - series[key][0][0] > PLOT_SECONDS) series[key].shift();
  }
  const token = [...live.sensors.keys()].find((k) => live.rig.sensors.find((s) => s.token === k)?.serial === m.sensor);
  const sensor = live.sensors.get(token);
  if (sensor) {
    const how = m.status !== "ok" ? m.status : m.idle ? "idle" : m.reused ? "reused" : `fused ${Math.round(m.fused_fraction * 100)} %`;
    const text = `cycle ${m.cycle} · ${how}`, cls = `state ${m.status === "timeout" ? "late" : m.status}`;
    if (sensor.state.textContent !== text) sensor.state.textContent = text;
    if (sensor.state.className !== cls) sensor.state.className = cls;
  }
}

let statusShown = 0;
function onStatus(s) {
  live.statusMessages++;
  // Four times a second is as fast as anyone reads it; each update costs a layout.
  const now = performance.now();
  if (now - statusShown < 250) return;
  statusShown = now;
  const pct = (x) => `${(100 * x).toFixed(0)} %`;
  const late = s.sensors.filter((x) => x.status !== "ok").length;
  const text = `cycle ${s.cycle} · ${s.cycles_per_s.toFixed(1)} cycles/s · fused ${pct(s.fused_fraction)} · ` +
    `idle ${pct(s.idle_fraction)} · reused ${pct(s.reused_fraction)} · capture ${s.ms_capture.toFixed(1)} ms · ` +
    `fuse ${s.ms_fuse.toFixed(1)} ms`;
  const box = document.getElementById("status");
  if (!box.firstChild) box.append(el("span"), el("span", { class: "err" }), el("div", { class: "err" }));
  const [line, lateBox, errors] = box.children;
  if (line.textContent !== text) line.textContent = text;
  const lateText = late ? ` · ${late} late or failed` : "";
  if (lateBox.textContent !== lateText) lateBox.textContent = lateText;
  const errorText = s.errors.join("\n");
  if (errors.textContent !== errorText) errors.textContent = errorText;
}

function connect() {
  const ws = new WebSocket(`ws://${location.host}/`, ["foxglove.websocket.v1"]);
  ws.binaryType = "arraybuffer";
  const badge = document.getElementById("connection");
  ws.onopen = () => { badge.textContent = "connected"; badge.className = "badge ok"; };
  ws.onclose = () => { badge.textContent = "disconnected"; badge.className = "badge bad"; };
  let pending = null;
  ws.onmessage = (event) => {
    if (typeof event.data === "string") {
      const msg = JSON.parse(event.data);
      if (msg.op === "advertise") {
        pending = msg.channels;
        // The rig description first: it names the sensors and the sequence.
        const rigChannel = msg.channels.find((c) => c.topic === "/vkfuse/rig");
        // Every topic but the raw images: their twins (/compressed: the
        // fused image's PNG, lossless; each frame's JPEG) carry what a person
        // sees in far fewer bytes, which is most of what a browser on the
        // rig's own host costs it.
        const wanted = msg.channels.filter((c) => !/\/(fused|lit\/led(_\d+)+)$/.test(c.topic));
        const subs = wanted.map((c, i) => ({ id: i + 1, channelId: c.id }));
        subs.forEach((s) => live.subscriptions.set(s.id, s.channelId));
        for (const c of msg.channels) live.channels.set(c.id, { topic: c.topic, kind: c.topic === "/vkfuse/rig" ? "rig" : null });
        ws.send(JSON.stringify({ op: "subscribe", subscriptions: subs }));
        if (!rigChannel) live.errors.push("no /vkfuse/rig channel");
      } else if (msg.op === "status" && msg.level >= 2) {
        live.errors.push(msg.message);
      }
      return;
    }
    const view = new DataView(event.data);
    if (view.getUint8(0) !== 1) return;
    const channel = live.subscriptions.get(view.getUint32(1, true));
    const stamp = view.getBigUint64(5, true).toString();
    const payload = new DataView(event.data, 13);
    const ch = live.channels.get(channel);
    if (!ch) return;
    if (ch.kind === "rig") {
      live.rig = JSON.parse(new TextDecoder().decode(payload));
      plots();
      setupChannels(pending);
      return;
    }
    if (!live.rig) return;
    if (ch.kind === "fused" || ch.kind === "lit") decodeCompressed(payload).then((bitmap) => draw(ch, stamp, bitmap));
    else if (ch.kind === "metrics") onMetrics(stamp, JSON.parse(new TextDecoder().decode(payload)));
    else if (ch.kind === "status") onStatus(JSON.parse(new TextDecoder().decode(payload)));
  };
}

setInterval(() => { if (live.rig && !live.frozen) drawPlots(); }, 1000);
connect();
