// ga_rotors viewer: draws a run on one 2-D canvas per orientation path, at the slider's time.
// Data come from #view-data (written by ga_rotors.view.page). Conventions: q = (w, x, y, z),
// v_space = q v_body q*, R = w − x e23 − y e31 − z e12 = cos(α/2) − I u sin(α/2).
// Drawing: an orthographic camera (z up) turned by dragging; every polygon and short line
// piece is sorted by depth and painted back to front; labels and the pivot go on top.
(function () {
  "use strict";
  const D = JSON.parse(document.getElementById("view-data").textContent);
  const n = D.t.length;
  const slider = document.getElementById("slider");
  const playButton = document.getElementById("play");
  const timeLabel = document.getElementById("time");
  const readouts = document.getElementById("readouts");
  const COLOUR = {};
  D.elements.forEach((e) => { COLOUR[e.key] = e.colour; });
  const TONES = [[0xc3, 0xca, 0xd2], [0x8f, 0x99, 0xa5]]; // the body's two tones
  const SPACE = "#9a9a9a"; // space axes
  const VIEW_RADIUS = 1.65; // drawing units from the centre to the canvas' nearer edge
  // A body moving through space gets its ω, L, plane and sphere at a smaller, fixed size.
  const G = D.glyph || 1;
  const PLANE_RADIUS = 1.0 * G, ARC_RADIUS = 0.9 * G, PIECE = 0.08;
  const camera = { azimuth: D.camera.azimuth, elevation: D.camera.elevation };

  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const norm = (a) => Math.hypot(a[0], a[1], a[2]);
  const unit = (a) => mul(a, 1 / norm(a));
  const lerp = (a, b, s) => add(a, mul(sub(b, a), s));

  function rotate(q, v) {
    // q v q* through t = 2 (u × v): v + w t + u × t.
    const w = q[0], ux = q[1], uy = q[2], uz = q[3];
    const tx = 2 * (uy * v[2] - uz * v[1]);
    const ty = 2 * (uz * v[0] - ux * v[2]);
    const tz = 2 * (ux * v[1] - uy * v[0]);
    return [
      v[0] + w * tx + (uy * tz - uz * ty),
      v[1] + w * ty + (uz * tx - ux * tz),
      v[2] + w * tz + (ux * ty - uy * tx),
    ];
  }

  function fmt(x, digits) {
    const s = x.toFixed(digits);
    return s === (-0).toFixed(digits) ? (0).toFixed(digits) : s;
  }

  function signed(x) { return (x < 0 ? "− " : "+ ") + fmt(Math.abs(x), 4); }

  function rotorText(q) {
    return `${fmt(q[0], 4)} ${signed(-q[1])} e23 ${signed(-q[2])} e31 ${signed(-q[3])} e12`;
  }

  function rgb(c, shade) {
    return `rgb(${Math.round(c[0] * shade)},${Math.round(c[1] * shade)},${Math.round(c[2] * shade)})`;
  }

  function hexRgba(hex, alpha) {
    const v = parseInt(hex.slice(1), 16);
    return `rgba(${(v >> 16) & 255},${(v >> 8) & 255},${v & 255},${alpha})`;
  }

  function basis() {
    const a = (camera.azimuth * Math.PI) / 180, e = (camera.elevation * Math.PI) / 180;
    const eye = [Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e)];
    const right = [-Math.sin(a), Math.cos(a), 0];
    return { eye, right, up: cross(eye, right) };
  }

  // One panel per path: its canvas, sized to its box in CSS pixels (sharp on HiDPI screens).
  const panels = D.paths.map((p, index) => {
    const figure = document.querySelector(`figure.panel[data-path="${CSS.escape(p.name)}"]`);
    const canvas = figure.querySelector("canvas");
    return { path: p, index, canvas, ctx: canvas.getContext("2d"), width: 0, height: 0 };
  });

  function resize(panel) {
    const box = panel.canvas.getBoundingClientRect();
    const ratio = window.devicePixelRatio || 1;
    panel.width = box.width;
    panel.height = box.height;
    panel.canvas.width = Math.max(1, Math.round(box.width * ratio));
    panel.canvas.height = Math.max(1, Math.round(box.height * ratio));
    panel.ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  }

  // A drawing under construction: depth-sorted items, then labels and markers on top.
  function scene(panel) {
    const B = basis();
    const s = Math.min(panel.width, panel.height) / (2 * VIEW_RADIUS);
    const cx = panel.width / 2, cy = panel.height / 2;
    const project = (p) => [cx + s * dot(p, B.right), cy - s * dot(p, B.up), -dot(p, B.eye)];
    return { B, s, cx, cy, project, under: [], items: [], labels: [], marks: [], anchors: {} };
  }

  // A line from a to b (space) in short pieces, so that depth sorting interleaves it with
  // the body's faces; the pieces share one style. Pieces are PIECE long from a (the last
  // one shorter), so parallel vectors from one point are cut at the same distances.
  // Returns the pieces' depths; ``over`` (depths of another line's pieces) lifts each piece
  // just in front of the same piece of that line: ω stays visible along a nearly parallel L.
  function segments(S, a, b, style, pieces, over) {
    const len = norm(sub(b, a));
    const k = pieces || Math.max(1, Math.ceil(len / PIECE));
    const at = (j) => (pieces ? j / k : Math.min(1, (j * PIECE) / len));
    const depths = [];
    let prev = S.project(a);
    for (let j = 1; j <= k; j++) {
      const next = S.project(lerp(a, b, at(j)));
      let z = (prev[2] + next[2]) / 2 + (style.bias || 0);
      // In front of the other line's piece here and its neighbours (their round caps overlap).
      if (over) for (let m = j - 2; m <= j; m++) if (m >= 0 && m < over.length) z = Math.min(z, over[m] - 1e-3);
      depths.push(z);
      S.items.push({ z, kind: "path", pts: [prev, next], style });
      prev = next;
    }
    return depths;
  }

  function arrow(S, a, b, style, head, over) {
    const depths = segments(S, a, lerp(a, b, 0.999), style, 0, over);
    const tip = S.project(b), back = S.project(lerp(a, b, 0.9));
    const z = Math.min(tip[2], depths[depths.length - 1]) - 1e-3;
    S.items.push({ z, kind: "head", tip, back, size: head, colour: style.colour });
    return depths;
  }

  function addBody(S, q, o) {
    const body = D.body;
    const V = body.vertices.map((v) => add(o, rotate(q, v)));
    const light = unit(add(add(mul(S.B.right, -0.35), mul(S.B.up, 0.6)), mul(S.B.eye, 0.75)));
    let xmin = Infinity, xmax = -Infinity, ymin = Infinity, ymax = -Infinity;
    body.faces.forEach((f, k) => {
      const pts = f.map((j) => V[j]);
      const normal = cross(sub(pts[1], pts[0]), sub(pts[2], pts[0]));
      const len = norm(normal);
      if (len === 0 || dot(normal, S.B.eye) <= 0) return; // turned away: hidden
      const shade = 0.62 + 0.38 * Math.max(0, dot(normal, light) / len);
      const p2 = pts.map(S.project);
      p2.forEach((p) => {
        xmin = Math.min(xmin, p[0]); xmax = Math.max(xmax, p[0]);
        ymin = Math.min(ymin, p[1]); ymax = Math.max(ymax, p[1]);
      });
      const z = p2.reduce((acc, p) => acc + p[2], 0) / p2.length;
      S.items.push({ z, kind: "face", pts: p2, fill: rgb(TONES[body.tones[k]], shade) });
    });
    S.anchors.body = [xmin, ymin, xmax, ymax].map((x) => Math.round(x * 10) / 10);
    const c = add(o, rotate(q, body.centre));
    for (let a = 0; a < 3; a++) {
      const e = [0, 0, 0]; e[a] = body.axisLength;
      const tip = add(c, rotate(q, e));
      const key = `e${a + 1}`;
      segments(S, c, tip, { colour: COLOUR[key], width: 2.2 });
      const t2 = S.project(tip);
      S.labels.push({ text: key, at: t2, colour: COLOUR[key] });
      S.anchors[key] = [t2[0], t2[1]];
    }
    if (body.pivot) {
      const p = add(o, rotate(q, body.pivot));
      segments(S, p, c, { colour: "#333333", width: 1.4, dash: [4, 3] });
      const p2 = S.project(p);
      S.marks.push({ kind: "pivot", at: p2 });
      S.labels.push({ text: "pivot", at: [p2[0] + 10, p2[1] + 14], colour: "#000000", fixed: true });
      S.anchors.pivot = [p2[0], p2[1]];
    }
  }

  function addVectors(S, q, o, i) {
    // L first: ω, thinner, is painted over it where the two are within 15° of each other.
    const order = D.vectors.slice().sort((a, b) => (a.key === "L" ? -1 : b.key === "L" ? 1 : 0));
    let under = null;
    order.forEach((v) => {
      const value = v.values[Math.min(i, v.values.length - 1)];
      if (norm(value) < 1e-9) return;
      const dir = rotate(q, value), tip = add(o, mul(dir, v.length * G));
      const thick = v.key === "L";
      const over = !thick && under && dot(unit(dir), under.dir) > Math.cos(Math.PI / 12) ? under.depths : null;
      const depths = arrow(S, o, tip, { colour: COLOUR[v.key], width: thick ? 7 : 3.2 }, thick ? 14 : 11, over);
      if (thick) under = { dir: unit(dir), depths };
      const t2 = S.project(tip);
      S.labels.push({ text: v.key === "omega" ? "ω" : "L", at: t2, colour: COLOUR[v.key], bold: true });
      S.anchors[v.key] = [t2[0], t2[1]];
    });
  }

  // The rotor's plane ⊥ u (a translucent disk, its rim) and an arc of its angle α, from the
  // plane's direction nearest space x to its image under the rotation; none when α = 0.
  function addPlane(S, q, o) {
    const sHalf = Math.hypot(q[1], q[2], q[3]);
    if (sHalf < 1e-9) return;
    const u = [q[1] / sHalf, q[2] / sHalf, q[3] / sHalf];
    const alpha = 2 * Math.atan2(sHalf, q[0]);
    let a = sub([1, 0, 0], mul(u, u[0]));
    if (norm(a) < 0.3) a = sub([0, 1, 0], mul(u, u[1]));
    a = unit(a);
    const b = cross(u, a);
    const at = (r, angle) => add(o, add(mul(a, r * Math.cos(angle)), mul(b, r * Math.sin(angle))));
    // The translucent disk is laid under the drawing (a big polygon cutting through the body
    // cannot be depth-sorted against its faces without patches); its rim and arc are sorted.
    const sectors = 72;
    S.under.push({ fill: hexRgba(COLOUR.plane, 0.16),
      pts: Array.from({ length: sectors }, (_, k) => S.project(at(PLANE_RADIUS, (2 * Math.PI * k) / sectors))) });
    for (let k = 0; k < sectors; k += 2) {
      const s0 = (2 * Math.PI * k) / sectors, s1 = (2 * Math.PI * (k + 2)) / sectors;
      segments(S, at(PLANE_RADIUS, s0), at(PLANE_RADIUS, s1), { colour: COLOUR.plane, width: 1 }, 1);
    }
    const steps = Math.max(2, Math.ceil(alpha / 0.1));
    for (let k = 0; k < steps; k++) {
      segments(S, at(ARC_RADIUS, (alpha * k) / steps), at(ARC_RADIUS, (alpha * (k + 1)) / steps),
        { colour: COLOUR.plane, width: 3.2 }, 1);
    }
    const end = S.project(at(ARC_RADIUS, alpha)), before = S.project(at(ARC_RADIUS, alpha * 0.9));
    S.items.push({ z: end[2] - 1e-3, kind: "head", tip: end, back: before, size: 10, colour: COLOUR.plane });
    const middle = S.project(at(ARC_RADIUS, alpha / 2));
    const label = S.project(at(ARC_RADIUS + 0.2 * G, alpha / 2));
    S.labels.push({ text: `α = ${fmt((alpha * 180) / Math.PI, 1)}°`, at: label, colour: "#7a6200" });
    S.anchors.plane = [middle[0], middle[1]];
  }

  // A polyline through the points T (space, mapped by ``at``) in runs of ``run`` pieces,
  // each depth-sorted: up to ``upto`` (the past) in style(true), after it in style(false).
  function addRuns(S, T, upto, run, at, style) {
    for (let k = 1; k < T.length; k += run) {
      const last = Math.min(T.length - 1, k + run - 1);
      for (const past of [true, false]) {
        const lo = past ? k : Math.max(k, upto), hi = past ? Math.min(last, upto - 1) : last;
        if (hi < lo) continue;
        const pts = [];
        for (let j = lo - 1; j <= hi; j++) pts.push(S.project(at(T[j])));
        const z = pts.reduce((acc, x) => acc + x[2], 0) / pts.length;
        S.items.push({ z, kind: "path", pts, style: style(past) });
      }
    }
  }

  // The symmetry axis' trace on the unit sphere, in runs of pieces (the past darker).
  function addTrace(S, p, q, o, i) {
    const upto = p.traceUpTo[Math.min(i, p.traceUpTo.length - 1)];
    addRuns(S, p.trace, upto, 40, (x) => add(o, mul(x, G)),
      (past) => ({ colour: COLOUR.trace, width: past ? 1.8 : 1, alpha: past ? 1 : 0.35 }));
    const tip = S.project(add(o, mul(rotate(q, D.symmetry), G)));
    S.items.push({ z: tip[2] - 2e-3, kind: "dot", at: tip, r: 3.5, colour: COLOUR.trace });
    S.anchors.trace = [tip[0], tip[1]];
  }

  // The centre of mass' path through space: the part flown so far solid, the rest faint.
  function addTrail(S, p, i) {
    const T = p.trail, upto = p.trailUpTo[Math.min(i, p.trailUpTo.length - 1)];
    addRuns(S, T, upto, 20, (x) => x, (past) => ({ colour: COLOUR.trail,
      width: past ? 2.4 : 1.2, alpha: past ? 1 : 0.4, dash: past ? [] : [2, 3] }));
    const here = S.project(T[Math.max(0, Math.min(T.length - 1, upto - 1))]);
    S.items.push({ z: here[2] - 2e-3, kind: "dot", at: here, r: 4, colour: COLOUR.trail });
    S.anchors.trail = [here[0], here[1]];
  }

  function addLines(S, i) {
    D.lines.forEach((line) => {
      const p = line.point[i], d = line.direction[i];
      segments(S, sub(p, mul(d, 2 * VIEW_RADIUS)), add(p, mul(d, 2 * VIEW_RADIUS)),
        { colour: line.colour, width: 2, dash: [7, 4] });
      const p2 = S.project(p);
      S.anchors[line.key] = [p2[0], p2[1]];
    });
  }

  function paint(ctx, S) {
    for (const u of S.under) {
      ctx.beginPath();
      u.pts.forEach((p, k) => (k ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
      ctx.closePath();
      ctx.fillStyle = u.fill;
      ctx.fill();
    }
    S.items.sort((x, y) => y.z - x.z); // farthest first
    for (const it of S.items) {
      if (it.kind === "face") {
        ctx.beginPath();
        it.pts.forEach((p, k) => (k ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
        ctx.closePath();
        ctx.fillStyle = it.fill;
        ctx.fill();
        ctx.strokeStyle = it.fill; // closes the hairline seams between faces
        ctx.lineWidth = 0.6;
        ctx.stroke();
      } else if (it.kind === "path") {
        ctx.beginPath();
        it.pts.forEach((p, k) => (k ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1])));
        ctx.strokeStyle = it.style.colour;
        ctx.globalAlpha = it.style.alpha || 1;
        ctx.lineWidth = it.style.width;
        ctx.lineCap = "round";
        ctx.setLineDash(it.style.dash || []);
        ctx.stroke();
        ctx.globalAlpha = 1;
        ctx.setLineDash([]);
      } else if (it.kind === "head") {
        let dx = it.tip[0] - it.back[0], dy = it.tip[1] - it.back[1];
        const len = Math.hypot(dx, dy);
        ctx.fillStyle = it.colour;
        ctx.beginPath();
        if (len < 1) {
          ctx.arc(it.tip[0], it.tip[1], it.size / 2.5, 0, 2 * Math.PI); // seen end-on
        } else {
          dx /= len; dy /= len;
          const bx = it.tip[0] - dx * it.size, by = it.tip[1] - dy * it.size, w = it.size * 0.45;
          ctx.moveTo(it.tip[0], it.tip[1]);
          ctx.lineTo(bx - dy * w, by + dx * w);
          ctx.lineTo(bx + dy * w, by - dx * w);
          ctx.closePath();
        }
        ctx.fill();
      } else if (it.kind === "dot") {
        ctx.beginPath();
        ctx.arc(it.at[0], it.at[1], it.r, 0, 2 * Math.PI);
        ctx.fillStyle = it.colour;
        ctx.fill();
      }
    }
    for (const m of S.marks) { // the pivot: a ring always on top
      ctx.beginPath();
      ctx.arc(m.at[0], m.at[1], 5.5, 0, 2 * Math.PI);
      ctx.fillStyle = "#ffffff";
      ctx.fill();
      ctx.lineWidth = 3;
      ctx.strokeStyle = COLOUR.pivot;
      ctx.stroke();
    }
    // Labels beside their points, left or right of the centre; one that would cover a label
    // already placed moves down (then up) until it is clear.
    ctx.textBaseline = "middle";
    const placed = [];
    const clash = (b) => placed.some((o) => b[0] < o[2] && o[0] < b[2] && b[1] < o[3] && o[1] < b[3]);
    S.labels.sort((x, y) => (y.bold ? 1 : 0) - (x.bold ? 1 : 0));
    for (const l of S.labels) {
      ctx.font = (l.bold ? "bold 16px" : "13px") + " system-ui, sans-serif";
      const right = l.fixed || l.at[0] >= S.cx;
      const w = ctx.measureText(l.text).width, h = l.bold ? 16 : 13;
      const x = l.fixed ? l.at[0] : l.at[0] + (right ? 8 : -8);
      const left = right ? x : x - w;
      let y = l.at[1];
      for (let step = 1; step < 12 && clash([left, y - h / 2, left + w, y + h / 2]); step++) {
        y = l.at[1] + (step % 2 ? 1 : -1) * Math.ceil(step / 2) * (h + 1);
      }
      placed.push([left, y - h / 2, left + w, y + h / 2]);
      ctx.textAlign = right ? "left" : "right";
      ctx.lineWidth = 3.5;
      ctx.strokeStyle = "rgba(255,255,255,0.9)";
      ctx.strokeText(l.text, x, y);
      ctx.fillStyle = l.colour;
      ctx.fillText(l.text, x, y);
    }
  }

  function draw(panel, i) {
    const ctx = panel.ctx, p = panel.path;
    ctx.clearRect(0, 0, panel.width, panel.height);
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, panel.width, panel.height);
    const S = scene(panel);
    if (i >= p.frames) {
      ctx.fillStyle = "#b00000";
      ctx.font = "15px system-ui, sans-serif";
      ctx.textAlign = "center";
      ctx.fillText(`path ended at t = ${p.endedAt} s`, S.cx, S.cy);
      panel.canvas.dataset.elements = "{}";
      return [];
    }
    const q = p.q[i], o = p.position ? p.position[i] : [0, 0, 0];
    // a moving body's ω, L, plane, trace and space axes are drawn at its centre of mass
    const g = p.position && D.body ? add(o, rotate(q, D.body.centre)) : o;
    const centre = S.project(g);
    ctx.beginPath(); // the unit sphere's outline, behind everything
    ctx.arc(centre[0], centre[1], S.s * G, 0, 2 * Math.PI);
    ctx.strokeStyle = "#e4e4e4";
    ctx.lineWidth = 1;
    ctx.stroke();
    for (let a = 0; a < 3; a++) {
      const e = [0, 0, 0]; e[a] = 1.6 * G;
      segments(S, g, add(g, e), { colour: SPACE, width: 1 });
      S.labels.push({ text: "xyz"[a], at: S.project(add(g, e)), colour: "#777777" });
    }
    if (D.body) addBody(S, q, o);
    addVectors(S, q, g, i);
    addPlane(S, q, g);
    addTrace(S, p, q, g, i);
    if (p.trail) addTrail(S, p, i);
    addLines(S, i);
    paint(ctx, S);
    panel.canvas.dataset.elements = JSON.stringify(S.anchors);
    panel.canvas.dataset.camera = JSON.stringify({ right: S.B.right, up: S.B.up, eye: S.B.eye, scale: S.s, cx: S.cx, cy: S.cy });
    return Object.keys(S.anchors);
  }

  function readout(p, i) {
    const row = readouts.querySelector(`tr[data-path="${CSS.escape(p.name)}"]`);
    if (i >= p.frames) {
      // The path stopped early (its state stopped being finite): say where it ended.
      row.querySelector(".rotor").textContent = `path ended at t = ${p.endedAt} s`;
      row.querySelector(".q").dataset.q = "null";
      return;
    }
    const q = p.q[i];
    row.querySelector(".rotor").textContent = "R = " + rotorText(q);
    const cell = row.querySelector(".q");
    cell.textContent = `(${q.map((c) => fmt(c, 6)).join(", ")})`;
    cell.dataset.q = JSON.stringify(q);
    const eu = p.euler[i];
    row.querySelector(".euler").textContent = `(${eu.map((c) => fmt(c, 3) + "°").join(", ")})`;
    const g = row.querySelector(".gimbal");
    g.textContent = p.locked[i] ? "LOCKED (sin θ = 0)" : p.near[i] ? `near (sin θ = ${p.sinTheta[i].toExponential(1)})` : "no";
    g.className = "gimbal" + (p.locked[i] ? " locked" : p.near[i] ? " near" : "");
  }

  let current = 0;
  function show(index) {
    const i = Math.max(0, Math.min(n - 1, index | 0));
    current = i;
    const drawn = new Set();
    panels.forEach((panel) => {
      draw(panel, i).forEach((k) => drawn.add(k));
      readout(panel.path, i);
    });
    document.querySelectorAll("#legend li").forEach((li) => {
      li.dataset.drawn = String(drawn.has(li.dataset.element));
    });
    slider.value = String(i);
    timeLabel.textContent = `t = ${fmt(D.t[i], 4)} s  (${i + 1}/${n})`;
    readouts.dataset.index = String(i);
    readouts.dataset.time = String(D.t[i]);
    if (document.body.dataset.ready !== "true") {
      document.body.dataset.readyMs = String(Math.round(performance.now()));
      document.body.dataset.ready = "true";
    }
  }

  function startIndex() {
    const params = new URLSearchParams(window.location.search);
    if (params.has("frame")) return Number(params.get("frame")) || 0;
    if (params.has("t")) {
      const t = Number(params.get("t"));
      let best = 0;
      for (let k = 1; k < n; k++) if (Math.abs(D.t[k] - t) < Math.abs(D.t[best] - t)) best = k;
      return best;
    }
    return 0;
  }

  let timer = null;
  function play() {
    if (timer !== null) {
      clearInterval(timer); timer = null; playButton.textContent = "play"; return;
    }
    playButton.textContent = "pause";
    if (current >= n - 1) show(0);
    timer = setInterval(() => {
      if (current + 1 >= n) { play(); return; }
      show(current + 1);
    }, 50);
  }

  // Drag any picture to turn the camera (all pictures together); double-click resets it.
  let drag = null;
  panels.forEach((panel) => {
    const c = panel.canvas;
    c.addEventListener("pointerdown", (ev) => { drag = [ev.clientX, ev.clientY]; c.setPointerCapture(ev.pointerId); });
    c.addEventListener("pointermove", (ev) => {
      if (!drag) return;
      camera.azimuth -= (ev.clientX - drag[0]) * 0.5;
      camera.elevation = Math.max(-89, Math.min(89, camera.elevation + (ev.clientY - drag[1]) * 0.5));
      drag = [ev.clientX, ev.clientY];
      show(current);
    });
    c.addEventListener("pointerup", () => { drag = null; });
    c.addEventListener("dblclick", () => {
      camera.azimuth = D.camera.azimuth; camera.elevation = D.camera.elevation; show(current);
    });
  });

  slider.max = String(n - 1);
  slider.addEventListener("input", () => show(Number(slider.value)));
  playButton.addEventListener("click", play);
  window.addEventListener("resize", () => { panels.forEach(resize); show(current); });
  panels.forEach(resize);
  show(startIndex());
})();
