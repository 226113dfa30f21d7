// The bay screen's connection and state: one WebSocket to the daemon (`/ws`), reconnected after a restart or a
// refusal (the daemon at its cap of pages) with a growing, randomised delay, so refused screens come back one
// by one and never push a live one out; every rig's shots (the last MAX_SHOTS), flights and comparisons kept
// bounded so a page left open for a day does not grow; the controls sent as messages the daemon turns into
// zenoh puts, or, on a read-only page (beyond loopback, opened without the token), not offered.
"use strict";
const MAX_SHOTS = 1000, MAX_FLIGHTS = 12, MAX_COMPARISONS = 50, MAX_LATENCIES = 1000;
const BACKOFF_FIRST_MS = 250, BACKOFF_LAST_MS = 15000;
const bay = {
  rigs: [], rig: null, view: "shot", data: {}, connected: false, sort: { key: "shot", up: false }, filter: "", by: "club",
  // Whether the daemon takes this page's controls; connections tried after the first.
  controls: true, reconnects: 0,
  // Launch published (the daemon's clock when the launch reached the screen's subscriber) to numbers drawn
  // (the first animation frame after the page text changed), per shot, ms.
  latencies: [],
  // Page load: navigation start to the page's first snapshot drawn, ms.
  firstDrawMs: null,
};
window.bay = bay;
const $ = (id) => document.getElementById(id);

function rigData(name) {
  if (!bay.data[name]) bay.data[name] = { shots: [], flights: [], comparisons: [], excluded: new Set(), labels: {}, units: "imperial", summary: null, status: null };
  return bay.data[name];
}
const trim = (a, n) => { if (a.length > n) a.splice(0, a.length - n); };

function onMessage(m) {
  if (m.type === "hello") {
    backoffMs = BACKOFF_FIRST_MS;
    setControls(m.controls !== false);
    bay.rigs = m.rigs;
    const fromHash = decodeURIComponent(location.hash.slice(1));
    if (!bay.rig || !bay.rigs.includes(bay.rig)) bay.rig = bay.rigs.includes(fromHash) ? fromHash : bay.rigs[0];
    for (const r of Object.keys(bay.data)) if (!bay.rigs.includes(r)) delete bay.data[r];
    return drawRigs();
  }
  const r = rigData(m.rig);
  switch (m.type) {
    case "snapshot":
      r.shots = m.shots; trim(r.shots, MAX_SHOTS);
      r.flights = m.flights; r.comparisons = m.comparisons; r.excluded = new Set(m.excluded);
      r.labels = m.labels || {}; r.units = m.units; r.summary = m.summary; r.status = m.status;
      break;
    case "shot": {
      const flight = m.flight; delete m.flight;
      r.shots.push(m); trim(r.shots, MAX_SHOTS);
      if (flight) { r.flights.push({ shot: m.shot, line: flight }); trim(r.flights, MAX_FLIGHTS); }
      break;
    }
    case "flight": r.flights.push({ shot: m.shot, line: m.line }); trim(r.flights, MAX_FLIGHTS); break;
    case "summary": r.summary = m; break;
    case "excluded": r.excluded = new Set(m.shots); break;
    case "comparison": r.comparisons.push(m.comparison); trim(r.comparisons, MAX_COMPARISONS); break;
    case "labels": r.labels = m.labels || {}; break;
    case "units": r.units = m.units; break;
    case "status": r.status = m.status; break;
  }
  if (m.rig !== bay.rig && m.type !== "shot" && m.type !== "snapshot") return;
  // The status changes only the rig's club line; labels only their line (the tables are not redrawn under a
  // click).
  if (m.type === "status") return drawClub(r);
  if (m.type === "labels") return drawLabels(r);
  draw(m.rig);
  if (m.type === "shot" && m.rig === bay.rig) {
    const published = m.published_ns / 1e6;
    requestAnimationFrame(() => {
      bay.latencies.push(performance.timeOrigin + performance.now() - published);
      trim(bay.latencies, MAX_LATENCIES);
    });
  }
  if (m.type === "snapshot" && bay.firstDrawMs === null && m.rig === bay.rig) {
    requestAnimationFrame(() => { bay.firstDrawMs = performance.now(); });
  }
}

function drawRigs() {
  const nav = $("rigs");
  nav.innerHTML = bay.rigs.map((name) => {
    const r = bay.data[name], s = r && r.shots[r.shots.length - 1];
    const last = s ? Views.fmt(s.m[Views.key("ball_speed", r.units)], "ball_speed", r.units) : "";
    return `<button type="button" data-rig="${Views.escape(name)}" class="${name === bay.rig ? "on" : ""}">${Views.escape(name)}<span class="last">${last}</span></button>`;
  }).join("");
}

function draw(rigName) {
  drawRigs();
  if (rigName !== bay.rig) return;
  const r = rigData(bay.rig);
  $("units").value = r.units;
  drawLabels(r);
  drawClub(r);
  $("csv").href = `/rig/${encodeURIComponent(bay.rig)}/session.csv`;
  $("csv").setAttribute("download", `${bay.rig}-session.csv`);
  if (bay.view === "shot") Views.shot(r, r.units);
  else Views.session(r, r.units, bay.sort, bay.filter, bay.by);
}

// The rig's club now, from its status: name and the first 8 hex digits of its club file's SHA-256.
function drawClub(r) {
  const c = r.status && r.status.club;
  $("rig-club").textContent = c ? `${c.name}${c.sha256 ? ` · ${c.sha256.slice(0, 8)}` : ""}` : "";
  $("rig-club").title = c ? `${c.file} (SHA-256 ${c.sha256})` : "";
}

function drawLabels(r) {
  const l = r.labels || {};
  $("labels-now").textContent = [l.player, ...(l.tags || [])].filter(Boolean).join(" · ");
}

// A read-only page (the daemon listens beyond loopback and this screen was opened without its token): the
// controls are shown disabled, with what to do.
function setControls(on) {
  bay.controls = on;
  for (const el of document.querySelectorAll("#controls input, #controls select, #controls button")) el.disabled = !on;
  $("read-only").hidden = on;
  document.body.classList.toggle("read-only", !on);
}

let socket = null, backoffMs = BACKOFF_FIRST_MS;
function connect() {
  const ws = new WebSocket(`${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws`);
  socket = ws;
  ws.onopen = () => { bay.connected = true; status("live", true); };
  ws.onmessage = (e) => { try { onMessage(JSON.parse(e.data)); } catch (err) { console.error(err); } };
  ws.onclose = () => {
    // Closed, or refused before it opened (the daemon stopped, or serving all the pages it takes): each try
    // waits twice as long as the last (to 15 s), a random half of it either way so screens spread out.
    bay.connected = false;
    bay.reconnects += 1;
    status("reconnecting…", false);
    setTimeout(connect, backoffMs * (0.5 + Math.random()));
    backoffMs = Math.min(backoffMs * 2, BACKOFF_LAST_MS);
  };
}
function status(text, up) { const c = $("connection"); c.textContent = text; c.className = up ? "up" : "down"; }
function send(control) {
  if (!bay.controls) return;
  if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify({ rig: bay.rig, ...control }));
}

Views.init();
$("rigs").addEventListener("click", (e) => {
  const b = e.target.closest("button[data-rig]");
  if (!b) return;
  bay.rig = b.dataset.rig; location.hash = encodeURIComponent(bay.rig); draw(bay.rig);
});
$("views").addEventListener("click", (e) => {
  const b = e.target.closest("button[data-view]");
  if (!b) return;
  bay.view = b.dataset.view;
  for (const x of document.querySelectorAll("#views button")) x.classList.toggle("on", x === b);
  $("shot-view").hidden = bay.view !== "shot";
  $("session-view").hidden = bay.view !== "session";
  draw(bay.rig);
});
$("units").addEventListener("change", (e) => send({ op: "units", units: e.target.value }));
$("club-set").addEventListener("click", () => { const c = $("club").value.trim(); if (c) send({ op: "club", club: c }); });
$("labels-set").addEventListener("click", () => send({
  op: "labels", player: $("player").value.trim() || null,
  tags: $("tags").value.split(",").map((t) => t.trim()).filter(Boolean),
}));
$("controls").addEventListener("submit", (e) => e.preventDefault());
$("club-filter").addEventListener("change", (e) => { bay.filter = e.target.value; draw(bay.rig); });
$("group-by").addEventListener("change", (e) => { bay.by = e.target.value; bay.filter = ""; draw(bay.rig); });
$("shots").addEventListener("click", (e) => {
  const th = e.target.closest("th[data-sort]");
  if (th) {
    bay.sort = { key: th.dataset.sort, up: bay.sort.key === th.dataset.sort ? !bay.sort.up : false };
    return draw(bay.rig);
  }
  const b = e.target.closest("button[data-exclude]");
  if (b) {
    const shot = Number(b.dataset.exclude);
    send({ op: "exclude", shot, excluded: !rigData(bay.rig).excluded.has(shot) });
  }
});
connect();
