// What the bay screen shows: metric keys and units (as the daemon's session module names them), the shot view
// and the session view. Numbers are page text, so a test or a screen reader reads what the golfer sees.
"use strict";
const Views = (() => {
  const QUANTITY = {
    club_speed: "speed", attack_angle: "angle", club_path: "angle", face_angle: "angle", face_to_path: "angle",
    dynamic_loft: "angle", spin_loft: "angle", swing_plane: "angle", swing_direction: "angle", low_point: "short",
    ball_speed: "speed", smash_factor: "ratio", launch_angle: "angle", launch_direction: "angle", spin_rate: "spin",
    spin_axis: "angle", carry: "distance", total: "distance", side: "distance", apex: "height", land_angle: "angle",
    hang_time: "time",
  };
  // Per quantity: key suffix, unit shown, decimals.
  const UNITS = {
    imperial: { speed: ["mph", "mph", 1], distance: ["yd", "yd", 1], height: ["ft", "ft", 0], short: ["in", "in", 1],
      angle: ["deg", "°", 1], spin: ["rpm", "rpm", 0], ratio: ["", "", 2], time: ["s", "s", 1] },
    metric: { speed: ["mps", "m/s", 1], distance: ["m", "m", 1], height: ["m", "m", 1], short: ["cm", "cm", 1],
      angle: ["deg", "°", 1], spin: ["rpm", "rpm", 0], ratio: ["", "", 2], time: ["s", "s", 1] },
  };
  const NAMES = {
    ball_speed: "Ball speed", launch_angle: "Launch angle", launch_direction: "Launch direction", spin_rate: "Spin rate",
    spin_axis: "Spin axis", carry: "Carry", total: "Total", side: "Side", apex: "Apex", land_angle: "Land angle",
    club_speed: "Club speed", attack_angle: "Attack angle", club_path: "Club path", face_angle: "Face angle",
    face_to_path: "Face to path", dynamic_loft: "Dynamic loft", smash_factor: "Smash factor",
  };
  const BALL = ["launch_angle", "launch_direction", "spin_rate", "spin_axis", "carry", "total", "side", "apex", "land_angle"];
  const CLUB = ["club_speed", "attack_angle", "club_path", "face_angle", "face_to_path", "dynamic_loft", "smash_factor"];
  const WARNINGS = {
    spin_axis_beyond_45_deg: "Spin axis beyond 45° – check the strike",
    negative_backspin: "Negative backspin – likely a mishit",
    smash_out_of_range: "Smash factor out of range – check the strike",
  };

  const key = (base, units) => { const s = UNITS[units][QUANTITY[base]][0]; return s ? `${base}_${s}` : base; };
  const unit = (base, units) => UNITS[units][QUANTITY[base]][1];
  const fmt = (v, base, units) => (v === null || v === undefined || !Number.isFinite(v)) ? "–" : v.toFixed(UNITS[units][QUANTITY[base]][2]);
  const value = (shot, base, units) => shot.m[key(base, units)];
  // A metric's one-sigma uncertainty on the shot (`± 2.1`), empty where it carries none.
  const sigma = (shot, base, units) => {
    const s = shot && shot.u ? shot.u[key(base, units)] : undefined;
    return Number.isFinite(s) ? `± ${fmt(s, base, units)}` : "";
  };
  const $ = (id) => document.getElementById(id);

  function tiles(container, bases) {
    container.textContent = "";
    for (const b of bases) {
      const t = document.createElement("div");
      t.className = "tile";
      t.innerHTML = `<span class="name">${NAMES[b]}</span><span class="value" id="v-${b}">–</span> <span class="sigma" id="s-${b}"></span> <span class="unit" id="u-${b}"></span>`;
      container.appendChild(t);
    }
  }

  function init() {
    tiles($("ball-tiles"), BALL);
    tiles($("club-tiles"), CLUB);
  }

  // The last shot, large.
  function shot(rig, units) {
    const s = rig.shots[rig.shots.length - 1];
    for (const b of ["ball_speed", ...BALL, ...CLUB]) {
      $(`v-${b}`).textContent = s ? fmt(value(s, b, units), b, units) : "–";
      $(`s-${b}`).textContent = sigma(s, b, units);
      $(`u-${b}`).textContent = unit(b, units);
    }
    $("shot-number").textContent = s ? s.shot : "–";
    $("shot-club").textContent = s ? s.club : "";
    $("shot-player").textContent = s && s.labels && s.labels.player ? ` · ${s.labels.player}` : "";
    const w = $("warnings");
    const warnings = s ? s.warnings : [];
    w.hidden = warnings.length === 0;
    w.textContent = warnings.map((x) => WARNINGS[x] || x.replaceAll("_", " ")).join(" · ");
    const toUnit = units === "imperial" ? (m) => m / 0.9144 : (m) => m;
    Draw.flights($("side"), $("top"), rig.flights.map((f) => f.line), toUnit, units === "imperial" ? "yd" : "m");
    Draw.face($("face"), s ? s.club_file : "", s ? s.impact_h_mm : NaN, s ? s.impact_v_mm : NaN);
    comparison(rig);
  }

  function comparison(rig) {
    const c = rig.comparisons[rig.comparisons.length - 1];
    $("comparison").hidden = !c;
    if (!c) return;
    $("cmp-device").textContent = c.device;
    $("cmp-shot").textContent = c.shot;
    const rows = [["Ball speed (mph)", "ball_speed_mph", 1], ["Launch angle (°)", "launch_angle_deg", 1],
      ["Launch direction (°)", "launch_direction_deg", 1], ["Backspin (rpm)", "backspin_rpm", 0], ["Sidespin (rpm)", "sidespin_rpm", 0]];
    const f = (v, d) => Number.isFinite(v) ? v.toFixed(d) : "–";
    $("cmp-rows").innerHTML = rows.map(([name, k, d]) =>
      `<tr><th>${name}</th><td>${f(c.predicted[k], d)}</td><td>${f(c.measured[k], d)}</td><td>${f(c.residual[k], d)}</td></tr>`).join("");
  }

  const TABLE = ["ball_speed", "launch_angle", "spin_rate", "carry", "total", "side", "club_speed", "smash_factor"];
  const SUMMARY = ["ball_speed", "launch_angle", "spin_rate", "carry", "total", "side", "club_speed", "smash_factor"];

  // The groups a shot is in, as `impactd session --by` forms them: its club, its player, or each of its tags
  // (`-` for none).
  function groupsOf(s, by) {
    const l = s.labels || {};
    if (by === "player") return [l.player || "-"];
    if (by === "tag") return l.tags && l.tags.length ? [...new Set(l.tags)] : ["-"];
    return [s.club];
  }

  // The session: averages per club, player or tag, the shot table (sortable, per group, exclude with a click),
  // dispersion per group.
  function session(rig, units, sort, filter, by) {
    const names = [...new Set(rig.shots.flatMap((s) => groupsOf(s, by)))];
    const select = $("club-filter");
    const want = [by, ...names].join("\n");
    if (select.dataset.groups !== want) {
      select.innerHTML = `<option value="">all</option>` + names.map((c) => `<option>${escape(c)}</option>`).join("");
      select.dataset.groups = want;
      select.value = names.includes(filter) ? filter : "";
    }
    const inGroup = (s) => !filter || groupsOf(s, by).includes(filter);
    const heading = { club: "Club", player: "Player", tag: "Tag" }[by];
    $("group-name").textContent = heading.toLowerCase();
    const summary = $("summary");
    summary.tHead.innerHTML = `<tr><th>${heading}</th><th>Shots</th>${SUMMARY.map((b) => `<th>${NAMES[b]} (${unit(b, units) || "–"})</th>`).join("")}</tr>`;
    summary.tBodies[0].innerHTML = (rig.summary && rig.summary.by ? rig.summary.by[by] : []).map((g) =>
      `<tr><td>${escape(g.group)}</td><td>${g.shots}</td>${SUMMARY.map((b) => {
        const st = g.stats[key(b, units)];
        return `<td>${st ? `${fmt(st.mean, b, units)} ± ${fmt(st.sd, b, units)}` : "–"}</td>`;
      }).join("")}</tr>`).join("");

    const table = $("shots");
    const cols = [["shot", "Shot"], ["club", "Club"], ...TABLE.map((b) => [b, `${NAMES[b]}${unit(b, units) ? ` (${unit(b, units)})` : ""}`])];
    table.tHead.innerHTML = `<tr>${cols.map(([k, name]) => `<th data-sort="${k}" class="${sort.key === k ? "sorted" + (sort.up ? " up" : "") : ""}">${name}</th>`).join("")}<th></th></tr>`;
    let rows = rig.shots.filter(inGroup);
    const sortValue = (s) => sort.key === "shot" ? s.shot : sort.key === "club" ? s.club : value(s, sort.key, units);
    rows = rows.slice().sort((a, b) => {
      const x = sortValue(a), y = sortValue(b);
      const c = typeof x === "string" ? x.localeCompare(y) : (x ?? -Infinity) - (y ?? -Infinity);
      return sort.up ? c : -c;
    });
    table.tBodies[0].innerHTML = rows.map((s) => {
      const out = rig.excluded.has(s.shot);
      return `<tr data-shot="${s.shot}" class="${out ? "excluded" : ""}"><td>${s.shot}</td><td>${escape(s.club)}</td>${TABLE.map((b) =>
        `<td>${fmt(value(s, b, units), b, units)}${sigma(s, b, units) ? `<span class="sigma"> ${sigma(s, b, units)}</span>` : ""}</td>`).join("")}<td><button type="button" data-exclude="${s.shot}">${out ? "Include" : "Exclude"}</button></td></tr>`;
    }).join("");

    const groups = names.filter((g) => !filter || g === filter).map((name) => ({
      name,
      points: rig.shots.filter((s) => groupsOf(s, by).includes(name) && !rig.excluded.has(s.shot))
        .map((s) => [value(s, "side", units), value(s, "carry", units)]).filter(([a, b]) => Number.isFinite(a) && Number.isFinite(b)),
    }));
    Draw.dispersion($("dispersion"), groups, unit("carry", units));
  }

  function escape(t) {
    return String(t).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" })[c]);
  }

  return { init, shot, session, escape, fmt, key, groupsOf };
})();
