// The pictures of the bay screen, as SVG: the flight from the side and from above (older shots faded), the
// face with the impact point, and the dispersion with one ellipse per group (club, player or tag). World frame: x to the target,
// y up, z to the right of the target line (metres).
"use strict";
const Draw = (() => {
  const NS = "http://www.w3.org/2000/svg";
  const el = (name, attrs, text) => {
    const e = document.createElementNS(NS, name);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    if (text !== undefined) e.textContent = text;
    return e;
  };
  const clear = (svg) => { while (svg.firstChild) svg.removeChild(svg.firstChild); };

  // Flights: `lines` oldest first, each [[x, y, z], ...]; `toUnit` turns metres into the unit shown.
  function flights(side, top, lines, toUnit, unit) {
    clear(side); clear(top);
    const W = 600, H = 200, L = 40, R = 10, T = 10, B = 24;
    let xMax = 50, yMax = 10, zMax = 10;
    for (const line of lines) for (const [x, y, z] of line) {
      xMax = Math.max(xMax, x); yMax = Math.max(yMax, y); zMax = Math.max(zMax, Math.abs(z));
    }
    xMax *= 1.05; yMax *= 1.15; zMax *= 1.2;
    const sx = (x) => L + (x / xMax) * (W - L - R);
    const sy = (y) => H - B - (y / yMax) * (H - T - B);
    const sz = (z) => T + (H - T - B) / 2 + (z / zMax) * (H - T - B) / 2;
    const step = niceStep(toUnit(xMax));
    for (const svg of [side, top]) {
      for (let u = 0; u <= toUnit(xMax); u += step) {
        const x = sx(u / toUnit(1));
        svg.appendChild(el("line", { x1: x, x2: x, y1: T, y2: H - B, class: "grid" }));
        svg.appendChild(el("text", { x: x + 2, y: H - 6 }, `${Math.round(u)}${u === 0 ? " " + unit : ""}`));
      }
    }
    side.appendChild(el("line", { x1: L, x2: W - R, y1: sy(0), y2: sy(0), class: "ground" }));
    top.appendChild(el("line", { x1: L, x2: W - R, y1: sz(0), y2: sz(0), class: "ground" }));
    lines.forEach((line, i) => {
      const cls = i === lines.length - 1 ? "flight" : "flight old";
      side.appendChild(el("polyline", { class: cls, points: line.map(([x, y]) => `${sx(x).toFixed(1)},${sy(Math.max(y, 0)).toFixed(1)}`).join(" ") }));
      top.appendChild(el("polyline", { class: cls, points: line.map(([x, , z]) => `${sx(x).toFixed(1)},${sz(z).toFixed(1)}`).join(" ") }));
    });
  }

  function niceStep(span) {
    const raw = span / 6, p = Math.pow(10, Math.floor(Math.log10(raw)));
    for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
    return 10 * p;
  }

  // The face seen from behind the ball: toe to the right, up the face upward (mm from the face centre).
  function face(svg, clubName, hMm, vMm) {
    clear(svg);
    const driver = /driver|wood|hybrid|^d/i.test(clubName || "");
    if (driver) {
      svg.appendChild(el("path", { class: "outline", d: "M -55 18 C -60 -10 -45 -28 -10 -28 L 35 -28 C 62 -28 66 0 58 18 C 50 30 -45 32 -55 18 Z" }));
    } else {
      svg.appendChild(el("path", { class: "outline", d: "M -40 22 L -42 -20 L 30 -30 C 42 -30 46 -18 44 -6 L 40 22 Z" }));
    }
    svg.appendChild(el("line", { x1: -8, x2: 8, y1: 0, y2: 0, class: "grid" }));
    svg.appendChild(el("line", { x1: 0, x2: 0, y1: -8, y2: 8, class: "grid" }));
    svg.appendChild(el("text", { x: 68, y: 37, "text-anchor": "end" }, "toe"));
    svg.appendChild(el("text", { x: -68, y: 37 }, "heel"));
    if (Number.isFinite(hMm) && Number.isFinite(vMm)) {
      svg.appendChild(el("circle", { class: "impact", cx: hMm.toFixed(1), cy: (-vMm).toFixed(1), r: 5 }));
    }
  }

  const COLOURS = ["#4fd18b", "#5ab0ff", "#ffb020", "#ff6f91", "#c792ea", "#f2f5f0", "#7fdbca", "#ff8c42"];

  // Dispersion: `groups` = [{club, points: [[side, carry], ...]}] in the unit shown. Both axes have the same
  // scale, so the spread left and right reads against the spread in carry.
  function dispersion(svg, groups, unit) {
    clear(svg);
    const W = 500, H = 400, L = 44, B = 26, T = 10, R = 10;
    // 95 % of a bivariate normal lies within sqrt(chi2(2, 0.95)) = 2.448 SDs along each principal axis.
    const outlines = groups.map((g) => {
      const e = ellipse(g.points);
      if (!e) return null;
      const k = 2.448, norm = Math.hypot(e.vx, e.vy), u = [e.vx / norm, e.vy / norm], pts = [];
      for (let j = 0; j <= 48; j++) {
        const t = (2 * Math.PI * j) / 48, a = k * Math.sqrt(e.l1) * Math.cos(t), b = k * Math.sqrt(e.l2) * Math.sin(t);
        pts.push([e.ms + a * u[0] - b * u[1], e.mc + a * u[1] + b * u[0]]);
      }
      return pts;
    });
    const all = groups.flatMap((g) => g.points).concat(outlines.filter(Boolean).flat());
    let cLo = Infinity, cHi = -Infinity, sMax = 5;
    for (const [s, c] of all) { cLo = Math.min(cLo, c); cHi = Math.max(cHi, c); sMax = Math.max(sMax, Math.abs(s)); }
    if (!Number.isFinite(cLo)) { cLo = 0; cHi = 100; }
    const w = W - L - R, h = H - T - B;
    const scale = Math.min(w / (2 * sMax * 1.1), h / Math.max((cHi - cLo) * 1.1, 10));
    const cMid = (cLo + cHi) / 2;
    const px = (s) => L + w / 2 + s * scale;
    const py = (c) => T + h / 2 - (c - cMid) * scale;
    const step = niceStep(h / scale);
    for (let c = Math.ceil((cMid - h / 2 / scale) / step) * step; c <= cMid + h / 2 / scale; c += step) {
      svg.appendChild(el("line", { x1: L, x2: W - R, y1: py(c), y2: py(c), class: "grid" }));
      svg.appendChild(el("text", { x: 2, y: py(c) + 5 }, `${Math.round(c)}`));
    }
    svg.appendChild(el("line", { x1: px(0), x2: px(0), y1: T, y2: H - B, class: "ground" }));
    svg.appendChild(el("text", { x: L, y: H - 6 }, `◀ left   (carry up, side across, ${unit})   right ▶`));
    groups.forEach((g, i) => {
      const colour = COLOURS[i % COLOURS.length];
      for (const [s, c] of g.points) svg.appendChild(el("circle", { cx: px(s), cy: py(c), r: 6, fill: colour }));
      if (outlines[i]) {
        const points = outlines[i].map(([s, c]) => `${px(s).toFixed(1)},${py(c).toFixed(1)}`).join(" ");
        svg.appendChild(el("polygon", { points, fill: "none", stroke: colour, "stroke-width": 2.5 }));
      }
      svg.appendChild(el("text", { x: W - R - 4, y: T + 18 + 20 * i, "text-anchor": "end", style: `fill:${colour}` }, g.name));
    });
  }

  // Mean and principal axes of 2-D points (sample covariance); null below three points.
  function ellipse(points) {
    const n = points.length;
    if (n < 3) return null;
    let ms = 0, mc = 0;
    for (const [s, c] of points) { ms += s / n; mc += c / n; }
    let ss = 0, cc = 0, sc = 0;
    for (const [s, c] of points) { ss += (s - ms) ** 2; cc += (c - mc) ** 2; sc += (s - ms) * (c - mc); }
    ss /= n - 1; cc /= n - 1; sc /= n - 1;
    const tr = ss + cc, det = ss * cc - sc * sc, d = Math.sqrt(Math.max(tr * tr / 4 - det, 0));
    const l1 = tr / 2 + d, l2 = Math.max(tr / 2 - d, 0);
    let vx = sc, vy = l1 - ss;
    if (Math.abs(vx) < 1e-12 && Math.abs(vy) < 1e-12) { vx = ss >= cc ? 1 : 0; vy = ss >= cc ? 0 : 1; }
    // Axis lengths in data units; the drawn ellipse is rotated to the first principal axis.
    return { ms, mc, l1, l2, vx, vy };
  }

  return { flights, face, dispersion, ellipse };
})();
