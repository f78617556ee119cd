// The monitor page: keeps every asset's state from the server's deltas and draws the
// selected asset's tab. Everything from the network goes into the page as text
// (textContent, attribute values set one by one): never as markup.
"use strict";

const WINDOW = 300;  // seconds of history in the plots
const MAX_POINTS = 4000, MAX_TRAVERSE = 5000, MAX_LOG = 200;
const TABS = ["telemetry", "map", "commands", "images", "log"];
const assets = new Map();  // partition -> state
let selected = null, tab = "telemetry", source = "", ws = null, now = 0, mode = "live", refs = 0;
let notes = [], stale = {}, replay = null, sliding = false;

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (v === null || v === undefined || v === false) continue;
    if (k === "text") e.textContent = String(v); else e.setAttribute(k, v === true ? "" : String(v));
  }
  for (const c of children) if (c !== null && c !== undefined) e.append(c instanceof Node ? c : String(c));
  return e;
}

function fmtValue(v) {
  if (typeof v === "number") return Number.isInteger(v) ? String(v) : String(+v.toFixed(4));
  if (Array.isArray(v)) return v.map(fmtValue).join(", ");
  if (typeof v === "boolean") return v ? "true" : "false";
  return String(v);
}

function stateOf(p) {
  if (!assets.has(p)) assets.set(p, { partition: p, status: { name: p }, commands: null, values: [], position: null,
    traverse: [], points: new Map(), log: [], images: [], acks: [], queue: null, access: null, answers: {},
    target: "", alerts: [], dropped: null });  // target: the queued cmdId INSERT and REPLACE act on, chosen in the queue
  return assets.get(p);
}

function merge(msg) {
  const a = stateOf(msg.partition);
  for (const k of ["status", "values", "position", "images", "acks", "queue", "access", "alerts", "dropped"]) {
    if (k in msg) a[k] = msg[k];
  }
  if ("values" in msg) {  // the server drops rows past the asset's cap: their series go too
    const kept = new Set(a.values.map(r => r.group + "/" + r.key));
    for (const vid of [...a.points.keys()]) if (!kept.has(vid)) a.points.delete(vid);
  }
  if ("commands" in msg && JSON.stringify(msg.commands) !== JSON.stringify(a.commands)) {
    a.commands = msg.commands; a.formsDirty = true;  // forms redrawn only when the dictionary changed
  }
  for (const [vid, t, v] of msg.points || []) {
    if (!a.points.has(vid)) a.points.set(vid, []);
    const s = a.points.get(vid); s.push([t, v]);
    if (s.length > MAX_POINTS) s.splice(0, s.length - MAX_POINTS);
  }
  for (const p of msg.traverse || []) a.traverse.push(p);
  if (a.traverse.length > MAX_TRAVERSE) a.traverse.splice(0, a.traverse.length - MAX_TRAVERSE);
  for (const l of msg.log || []) a.log.push(l);
  if (a.log.length > MAX_LOG) a.log.splice(0, a.log.length - MAX_LOG);
}

// ---- the asset list and the header -------------------------------------------------------
function drawAssets() {
  const nav = document.getElementById("assets");
  document.getElementById("no-assets").hidden = assets.size > 0;
  for (const b of nav.querySelectorAll("button")) if (!assets.has(b.dataset.partition)) b.remove();
  for (const [p, a] of [...assets].sort((x, y) => String(x[1].status.name).localeCompare(String(y[1].status.name)))) {
    let b = [...nav.querySelectorAll("button")].find(x => x.dataset.partition === p);
    if (!b) {
      b = el("button", { type: "button", "data-partition": p, class: "asset" });
      b.addEventListener("click", () => { selected = p; drawAll(true); });
      nav.append(b);
    }
    const gone = a.status.present === false, quiet = stale[p] || gone;
    const sub = [gone ? "gone (no writer left)" : quiet ? "quiet" : "live"];
    if (a.status.partition && a.status.partition !== a.status.name) sub.push("partition " + a.status.partition);
    if (a.status.statusCode !== null && a.status.statusCode !== undefined) sub.push("status " + a.status.statusCode);
    if (a.alerts.length) sub.push("warning: see its page");
    b.replaceChildren(el("span", { class: "dot" + (quiet ? " quiet" : "") }), el("span", { class: "name", text: a.status.name }),
      el("div", { class: "sub", text: sub.join(" · ") }));
    b.classList.toggle("selected", p === selected);
    b.dataset.status = gone ? "gone" : quiet ? "quiet" : "live";
  }
  if (selected === null && assets.size) selected = [...assets.keys()].sort()[0];
}

function drawHead(a) {
  const head = document.getElementById("asset-head");
  const parts = [el("h2", { text: a.status.name })];
  const bits = ["partition " + a.partition, a.status.present === false ? "gone (no writer left)" :
    stale[a.partition] ? "quiet (no data for 5 s)" : "live"];
  if (a.access) bits.push("controller: " + (a.access.controller || "none"));
  if (a.queue) bits.push("queue " + a.queue.state);
  parts.push(el("div", { class: "sub", text: bits.join(" · ") }));
  if (a.alerts.length) parts.push(el("div", { id: "alerts" }, ...a.alerts.map(t => el("div", { class: "alert", text: t }))));
  head.replaceChildren(...parts);
  const tabs = document.getElementById("tabs");
  if (!tabs.childElementCount) {
    for (const t of TABS) {
      const b = el("button", { type: "button", role: "tab", "data-tab": t, text: t });
      b.addEventListener("click", () => { tab = t; drawAll(true); });
      tabs.append(b);
    }
  }
  for (const b of tabs.children) b.classList.toggle("selected", b.dataset.tab === tab);
}

// ---- tabs ----------------------------------------------------------------------------------
function limitsText(r) {
  const out = [];
  for (const lvl of ["warning", "critical"]) {
    const t = r[lvl]; if (!t) continue;
    const s = [];
    if (t.below !== null && t.below !== undefined) s.push("< " + t.below);
    if (t.above !== null && t.above !== undefined) s.push("> " + t.above);
    out.push(lvl + " " + s.join(" or "));
  }
  return out.join("; ");
}

function drawTelemetry(view, a, rebuild) {
  if (rebuild || !view.querySelector("#values")) {
    view.replaceChildren(el("div", { class: "split" },
      el("div", { class: "card" }, el("h3", { text: "values" }), el("table", { id: "values" }),
        el("div", { id: "rows-dropped", class: "sub" })),
      el("div", { class: "card" }, el("h3", { text: "last " + WINDOW / 60 + " minutes" }), el("div", { id: "plots" }))));
  }
  const order = { agent: 0, position: 1, joint: 3 };
  const values = a.values.slice().sort((x, y) => (order[x.group] ?? 2) - (order[y.group] ?? 2));
  const rows = [el("tr", {}, el("th", { text: "group" }), el("th", { text: "key" }), el("th", { text: "value" }),
    el("th", { text: "unit" }), el("th", { text: "thresholds" }))];
  for (const r of values) {
    rows.push(el("tr", { "data-key": r.group + "/" + r.key },
      el("td", { class: "sub", text: r.group }), el("td", { text: r.key }),
      el("td", { class: "value level-" + r.level, "data-level": r.level, text: fmtValue(r.value) }),
      el("td", { text: r.unit || "" }), el("td", { class: "limits", text: limitsText(r) })));
  }
  document.getElementById("values").replaceChildren(...rows);
  const dropped = document.getElementById("rows-dropped");
  dropped.dataset.rows = a.dropped ? String(a.dropped.rows) : "0";
  dropped.textContent = a.dropped ? a.dropped.rows + " row(s) dropped: an asset keeps as many rows as its configs " +
    "declare (at most " + a.dropped.cap + "), the least recently updated go" : "";
  const plots = document.getElementById("plots");
  const wanted = values.filter(r => r.group !== "joint" && typeof r.value === "number").slice(0, 8);
  const joints = values.filter(r => r.group === "joint").slice(0, 4);
  const width = Math.max(240, Math.min(640, plots.clientWidth - 4));
  for (const r of wanted.concat(joints)) {
    const vid = r.group + "/" + r.key;
    let c = [...plots.children].find(x => x.dataset.series === vid);
    if (!c) { c = el("canvas", { class: "plot", width, height: 110, "data-series": vid }); plots.append(c); }
    if (c.width !== width) c.width = width;
    Plot.series(c, a.points.get(vid) || [], { now, window: WINDOW, title: r.key, unit: r.unit,
      warning: r.warning, critical: r.critical });
  }
}

function drawMap(view, a, rebuild) {
  if (rebuild || !view.querySelector("#map")) {
    view.replaceChildren(el("div", { class: "cards" },
      el("div", { class: "card" }, el("h3", { text: "site map" }), el("canvas", { id: "map", width: 640, height: 520 })),
      el("div", { class: "card" }, el("h3", { text: "position" }), el("table", { id: "pos" }))));
  }
  const c = document.getElementById("map");
  c.dataset.points = a.traverse.length;
  const others = [...assets.values()].filter(o => o !== a && (o.position || o.traverse.length))
    .map(o => ({ name: o.status.name, traverse: o.traverse, pos: o.position }));
  Plot.map(c, a.traverse, a.position, others);
  const p = a.position;
  const rows = p ? [["x (north)", p.xyz[0], "m"], ["y (east)", p.xyz[1], "m"], ["z (down)", p.xyz[2], "m"],
    ["heading", typeof p.heading === "number" ? p.heading * 180 / Math.PI : p.heading, "deg"],
    ["traverse points", a.traverse.length, ""]] : [];
  document.getElementById("pos").replaceChildren(...(rows.length ? rows.map(([k, v, u]) =>
    el("tr", {}, el("td", { text: k }), el("td", { class: "value", text: fmtValue(v) }), el("td", { text: u })))
    : [el("tr", {}, el("td", { class: "muted", text: "no position yet" }))]));
}

function input(p) {
  const attrs = { name: p.name, "data-type": p.type, title: p.description || p.type };
  const dflt = p.has_default ? p.default : null;
  if (p.allowed && p.allowed.length) {
    const s = el("select", attrs);
    for (const v of p.allowed) s.append(el("option", { value: v, text: v, selected: dflt === v }));
    return s;
  }
  if (p.type === "RAPID_BOOL") {
    const s = el("select", attrs);
    for (const v of ["false", "true"]) s.append(el("option", { value: v, text: v, selected: String(dflt) === v }));
    return s;
  }
  if (["RAPID_FLOAT", "RAPID_DOUBLE", "RAPID_INT", "RAPID_LONGLONG"].includes(p.type)) {
    const integer = p.type === "RAPID_INT" || p.type === "RAPID_LONGLONG";
    return el("input", Object.assign(attrs, { type: "number", step: integer ? "1" : "any", min: p.min, max: p.max,
      value: dflt, required: !p.has_default, placeholder: integer ? "integer" : "number" }));
  }
  if (p.type === "RAPID_VEC3d" || p.type === "RAPID_MAT33f") {
    return el("input", Object.assign(attrs, { type: "text", class: "vector", value: dflt === null ? null : dflt.join(","),
      placeholder: p.type === "RAPID_VEC3d" ? "x,y,z" : "9 numbers, row by row", required: !p.has_default }));
  }
  return el("input", Object.assign(attrs, { type: "text", maxlength: 127, value: dflt }));
}

function commandForm(a, sub, c, queue) {
  // novalidate: the server checks every value and says why one is refused
  const f = el("form", { class: "command", "data-command": sub.subsystem + "/" + c.name, novalidate: true });
  const flags = [c.abortable ? "abortable" : "", c.suspendable ? "suspendable" : ""].filter(Boolean).join(", ");
  f.append(el("div", {}, el("span", { class: "title", text: c.name }),
    el("span", { class: "sub", text: (flags ? "  (" + flags + ")" : "") + (c.description ? "  " + c.description : "") })));
  for (const p of c.parameters) {
    const range = p.min !== null || p.max !== null ? " [" + (p.min ?? "-inf") + ", " + (p.max ?? "inf") + "]" : "";
    f.append(el("label", {}, el("span", { text: p.name }), input(p),
      el("span", { class: "sub", text: (p.unit || "") + range })));
  }
  let action = null;
  if (queue) {
    action = el("select", { name: "queue-action" });
    for (const v of ["BYPASS", "APPEND", "INSERT", "REPLACE"]) action.append(el("option", { value: v, text: v }));
    f.append(el("label", {}, el("span", { class: "sub", text: "queue" }), action));
  }
  const send = el("button", { type: "submit", class: "send", disabled: !source, text: "send" });
  const answer = el("span", { class: "answer" });
  f.append(send, answer);
  f.addEventListener("submit", ev => {
    ev.preventDefault();
    if (!source) { answer.textContent = "choose a command source first"; answer.className = "answer refused"; return; }
    const args = {};
    for (const i of f.querySelectorAll("[data-type]")) args[i.name] = i.value;
    const act = action ? action.value : "BYPASS";
    sendCommand(a, answer, sub.subsystem, c.name, args, act, act === "INSERT" || act === "REPLACE" ? a.target : "");
  });
  return f;
}

// The server checks everything again (commanding.py) and answers `ref` with the cmdId or why not.
function sendCommand(a, answer, subsystem, command, args, action, target) {
  const ref = ++refs;
  a.answers[ref] = answer;
  answer.textContent = "sending..."; answer.className = "answer";
  delete answer.dataset.cmdid;  // (the last command's, from this form)
  ws.send(JSON.stringify({ type: "command", ref, partition: a.partition, subsystem, command, args, source, action,
    target }));
}

// A queued (or running) record: choose it as INSERT/REPLACE's target, or DELETE it.
function queueRecord(a, r) {
  const row = el("div", { class: "record", "data-record": r.cmdId },
    el("span", { text: r.command + " " + r.status + " " }), el("span", { class: "sub", text: "[" + r.cmdId + "] " }));
  const pick = el("button", { type: "button", class: "target", text: a.target === r.cmdId ? "target" : "as target" });
  pick.addEventListener("click", () => { a.target = a.target === r.cmdId ? "" : r.cmdId; drawAll(false); });
  const del = el("button", { type: "button", class: "delete", disabled: !source || mode !== "live", text: "delete" });
  del.addEventListener("click", () => {
    const slash = r.command.indexOf("/");
    sendCommand(a, document.getElementById("queue-answer"), r.command.slice(0, slash), r.command.slice(slash + 1), {},
      "DELETE", r.cmdId);
  });
  row.append(pick, del);
  return row;
}

function ackItem(x) {
  const chips = x.acks.map(k => {
    const final = k.status === "COMPLETED";
    const label = k.status + (final || k.completed !== "NOT" ? " " + k.completed : "") + (k.message ? ": " + k.message : "");
    return el("span", { class: "ack" + (final ? (k.completed === "OK" ? " final-OK" : " final-bad") : ""), text: label });
  });
  return el("li", { "data-cmdid": x.cmdId }, el("span", { text: (x.command || "?") + " " }),
    el("span", { class: "sub", text: "[" + x.cmdId + (x.source ? ", from " + x.source : "") + "] " }), ...chips);
}

function drawCommands(view, a, rebuild) {
  if (rebuild || a.formsDirty || !view.querySelector("#forms")) {
    a.formsDirty = false;
    const forms = el("div", { id: "forms" });
    const cmds = a.commands || { subsystems: [], origin: null };
    const queue = cmds.subsystems.some(s => s.type === "Queue");
    forms.append(el("div", { class: "sub", text: cmds.origin === "live" ? "from the live CommandConfig" +
      (cmds.subsystems.length ? "" : " (no subsystems)") : cmds.origin === "descriptor" ?
      "from the descriptor (no live CommandConfig yet: not sendable)" : "no command dictionary" }));
    if (cmds.refused) forms.append(el("div", { id: "commands-refused", class: "alert", text: "not sendable: " + cmds.refused }));
    for (const s of cmds.subsystems) {
      const box = el("div", { class: "subsystem" }, el("h3", { text: s.subsystem + "  (" + s.type + ")" }));
      for (const c of s.commands) box.append(commandForm(a, s, c, queue));
      forms.append(box);
    }
    view.replaceChildren(el("div", { class: "split" }, el("div", { class: "card" }, el("h3", { text: "commands" }), forms),
      el("div", { class: "card" }, el("h3", { text: "acks" }), el("div", { id: "acks", class: "acks" }),
        el("h3", { text: "queue" }), el("div", { id: "queue" }), el("h3", { text: "access control" }), el("div", { id: "access" }))));
  }
  for (const b of view.querySelectorAll("button.send")) b.disabled = !source || mode !== "live";
  document.getElementById("acks").replaceChildren(el("ul", {}, ...a.acks.map(ackItem)));
  const q = a.queue;
  const queued = q ? [...q.active, ...q.pending] : [];
  if (a.target && !queued.some(r => r.cmdId === a.target)) a.target = "";  // it ran, or left the queue
  // redrawn only when it changed: a button replaced under the pointer would lose its click
  const key = JSON.stringify([q, a.target, source, mode]);
  const box = document.getElementById("queue");
  if (box.dataset.key === key) return drawAccess(a);
  box.dataset.key = key;
  const qrows = q ? [el("div", {}, el("span", { class: "sub", text: "active and pending: " }),
    queued.length ? null : el("span", { text: "none" })), ...queued.map(r => queueRecord(a, r)),
  el("div", {}, el("span", { class: "sub", text: "completed: " }),
    el("span", { text: q.completed.length ? q.completed.map(r => r.command + " " + r.status).join("; ") : "none" })),
  el("div", { id: "queue-target", "data-target": a.target, text: "INSERT after / REPLACE: " + (a.target || "choose a target") }),
  el("span", { id: "queue-answer", class: "answer" })] : [];
  const kept = document.getElementById("queue-answer");  // an answer still to come keeps its span
  box.replaceChildren(...(q ? [el("div", { "data-queue": q.state, text: "state: " + q.state }), ...qrows]
    : [el("span", { class: "muted", text: "no QueueState" })]));
  if (kept && q) document.getElementById("queue-answer").replaceWith(kept);
  drawAccess(a);
}

function drawAccess(a) {
  const ac = a.access;
  document.getElementById("access").replaceChildren(ac ? el("div", {},
    el("div", { "data-controller": ac.controller, text: "controller: " + (ac.controller || "none") }),
    el("div", { text: "requestors: " + (ac.requestors.join(", ") || "none") })) : el("span", { class: "muted", text: "no AccessControlState" }));
}

function drawImages(view, a) {
  const box = view.querySelector(".images") || el("div", { class: "images" });
  if (!box.isConnected) view.replaceChildren(box);
  if (!a.images.length) { box.replaceChildren(el("span", { class: "muted", text: "no image sensor" })); return; }
  for (const m of a.images) {
    let fig = [...box.children].find(x => x.dataset && x.dataset.sensor === m.sensor);
    if (!fig) { fig = el("figure", { "data-sensor": m.sensor }, el("img", { alt: m.sensor }), el("figcaption")); box.append(fig); }
    box.querySelector(".muted")?.remove();
    const img = fig.querySelector("img");
    if (m.seq && img.dataset.seq !== String(m.seq)) {
      img.dataset.seq = String(m.seq);
      img.src = "/picture/" + encodeURIComponent(a.partition) + "/" + encodeURIComponent(m.sensor) + "?v=" + m.seq;
    }
    fig.querySelector("figcaption").textContent = m.sensor + " (" + m.type + ") " + m.width + "x" + m.height +
      (m.mime ? ", " + m.mime + ", " + m.bytes + " bytes" : ", no picture yet") +
      (m.t ? ", " + new Date(m.t * 1000).toISOString().slice(11, 19) + " UTC" : "");
  }
}

function drawLog(view, a) {
  const lines = a.log.slice().reverse().map(([t, level, cat, text]) => el("div", { class: "lvl-" + level },
    el("span", { class: "sub", text: new Date(t * 1000).toISOString().slice(11, 19) + " " + level + " " + cat + "  " }),
    el("span", { class: "text", text })));
  view.replaceChildren(el("div", { class: "log", id: "log" }, ...(lines.length ? lines : [el("span", { class: "muted", text: "no text message" })])));
}

function drawAll(rebuild) {
  drawAssets();
  const a = selected !== null ? assets.get(selected) : null;
  if (!a) return;
  drawHead(a);
  const view = document.getElementById("view");
  if (rebuild) view.replaceChildren();
  view.dataset.tab = tab;
  ({ telemetry: drawTelemetry, map: drawMap, commands: drawCommands, images: drawImages, log: drawLog })[tab](view, a, rebuild);
  document.getElementById("notes").replaceChildren(...notes.map(n => el("div", { text: n })));
}

// ---- the connection ------------------------------------------------------------------------
function answer(msg) {
  const a = assets.get(msg.partition);
  const span = a && a.answers[msg.ref];
  if (!span) return;
  delete a.answers[msg.ref];
  span.textContent = msg.type === "sent" ? "sent as " + msg.cmdId : "not sent: " + msg.reason;
  span.className = "answer " + msg.type;
  if (msg.type === "sent") span.dataset.cmdid = msg.cmdId;
}

function showReplay(r) {
  replay = r;
  document.getElementById("replay").hidden = false;
  document.getElementById("replay-play").textContent = r.playing ? "pause" : "play";
  if (!sliding) document.getElementById("replay-slider").value = Math.round((r.t - r.start) / Math.max(1e-9, r.end - r.start) * 1000);
  document.getElementById("replay-time").textContent = new Date(r.t * 1000).toISOString().slice(0, 19).replace("T", " ") +
    " UTC  (" + (r.t - r.start).toFixed(1) + " / " + (r.end - r.start).toFixed(1) + " s)";
}

function connect() {
  // the token this page was served with: the server accepts no WebSocket without it
  const token = document.querySelector('meta[name="monitor-token"]').content;
  ws = new WebSocket((location.protocol === "https:" ? "wss://" : "ws://") + location.host + "/ws?token=" +
    encodeURIComponent(token));
  ws.onopen = () => { const c = document.getElementById("conn"); c.textContent = "connected"; c.className = "conn-up"; };
  ws.onclose = () => {
    const c = document.getElementById("conn"); c.className = "conn-down";
    c.textContent = "disconnected: retrying (reload the page if the monitor was restarted)";
    setTimeout(connect, 1000);
  };
  ws.onmessage = ev => {
    const msg = JSON.parse(ev.data);
    if (msg.type === "hello") {
      mode = msg.mode; assets.clear();
      document.getElementById("mode").textContent = msg.mode === "live" ? "live, DDS domain " + msg.domain : "replay of " + msg.file;
      if (msg.mode === "replay") { document.getElementById("source-form").hidden = true; showReplay(msg); }
    } else if (msg.type === "reset") {
      assets.clear();  // a replay seek: the state is rebuilt from the recording's start
    } else if (msg.type === "delta") {
      now = msg.now; stale = msg.stale; notes = msg.notes || [];
      for (const m of msg.assets || []) merge(m);
      if (msg.replay) showReplay(msg.replay);
      drawAll(false);
      document.body.dataset.updated = String(msg.now);
    } else if (msg.type === "sent" || msg.type === "refused") answer(msg);
  };
}

function chooseSource(ev) {
  ev.preventDefault();
  const v = document.getElementById("source").value.trim();
  source = v;
  const now = document.getElementById("source-now");
  now.textContent = v ? "commanding as " + v : "no source chosen: commands disabled";
  now.classList.toggle("chosen", !!v);
  drawAll(false);
}

function sourcesList() {
  const all = new Set();
  for (const a of assets.values()) for (const s of (a.commands && a.commands.sources) || []) all.add(s);
  const dl = document.getElementById("sources");
  if (dl.childElementCount !== all.size) dl.replaceChildren(...[...all].sort().map(s => el("option", { value: s })));
}

function replayControls() {
  const slider = document.getElementById("replay-slider");
  slider.addEventListener("input", () => { sliding = true; });
  slider.addEventListener("change", () => {
    sliding = false;
    if (replay) ws.send(JSON.stringify({ type: "seek", t: replay.start + slider.value / 1000 * (replay.end - replay.start) }));
  });
  document.getElementById("replay-play").addEventListener("click", () => {
    ws.send(JSON.stringify({ type: replay && replay.playing ? "pause" : "play" }));
  });
}

document.addEventListener("DOMContentLoaded", () => {
  document.getElementById("source-form").addEventListener("submit", chooseSource);
  replayControls();
  setInterval(sourcesList, 1000);
  connect();
});
