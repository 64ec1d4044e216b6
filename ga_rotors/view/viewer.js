// ga_rotors viewer: moves the body, ω, L and the rotor's plane to the slider's time.
// Data come from #view-data (written by ga_rotors.view.page); the figure's static parts and
// trace styles from #view-figure. Conventions: q = (w, x, y, z), v_space = q v_body q*,
// R = w − x e23 − y e31 − z e12 = cos(α/2) − I u sin(α/2).
(function () {
  "use strict";
  const D = JSON.parse(document.getElementById("view-data").textContent);
  const F = JSON.parse(document.getElementById("view-figure").textContent);
  const gd = document.getElementById("figure");
  const slider = document.getElementById("slider");
  const playButton = document.getElementById("play");
  const timeLabel = document.getElementById("time");
  const readouts = document.getElementById("readouts");
  const TRACES = 11; // per path, in the order ga_rotors.view.page.figure adds them
  const n = D.t.length;

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

  function norm(v) { return Math.hypot(v[0], v[1], v[2]); }

  function fmt(x, digits) {
    const s = x.toFixed(digits);
    return s === (-0).toFixed(digits) ? (0).toFixed(digits) : s;
  }

  function signed(x) { return (x < 0 ? "− " : "+ ") + fmt(Math.abs(x), 4); }

  function segment(v, scale) {
    return [[0, v[0] * scale], [0, v[1] * scale], [0, v[2] * scale]];
  }

  // The rotor's plane ⊥ u (a disk) and an arc of its angle α, or nothing when α ≈ 0.
  function plane(q) {
    const s = Math.hypot(q[1], q[2], q[3]);
    if (s < 1e-9) return null;
    const u = [q[1] / s, q[2] / s, q[3] / s];
    const alpha = 2 * Math.atan2(s, q[0]);
    const ref = Math.abs(u[2]) < 0.9 ? [0, 0, 1] : [1, 0, 0];
    let a = [u[1] * ref[2] - u[2] * ref[1], u[2] * ref[0] - u[0] * ref[2], u[0] * ref[1] - u[1] * ref[0]];
    const na = norm(a);
    a = [a[0] / na, a[1] / na, a[2] / na];
    const b = [u[1] * a[2] - u[2] * a[1], u[2] * a[0] - u[0] * a[2], u[0] * a[1] - u[1] * a[0]];
    const disk = [[0], [0], [0]], arc = [[], [], []];
    const r = 1.25, segments = 40;
    for (let i = 0; i <= segments; i++) {
      const s1 = (2 * Math.PI * i) / segments;
      for (let c = 0; c < 3; c++) disk[c].push(r * (a[c] * Math.cos(s1) + b[c] * Math.sin(s1)));
      const s2 = (alpha * i) / segments;
      for (let c = 0; c < 3; c++) arc[c].push(1.2 * (a[c] * Math.cos(s2) + b[c] * Math.sin(s2)));
    }
    const fan = [[], [], []];
    for (let i = 1; i <= segments; i++) { fan[0].push(0); fan[1].push(i); fan[2].push(i + 1 > segments ? 1 : i + 1); }
    return { disk, arc, fan };
  }

  function rotorText(q) {
    return `${fmt(q[0], 4)} ${signed(-q[1])} e23 ${signed(-q[2])} e31 ${signed(-q[3])} e12`;
  }

  const scaleW = D.wMax > 0 ? 1.4 / D.wMax : 0;
  const scaleL = D.LMax ? 1.4 / D.LMax : 0;

  function show(index) {
    const i = Math.max(0, Math.min(n - 1, index | 0));
    const x = [], y = [], z = [], traces = [], extra = { i: [], j: [], k: [] }, meshTraces = [];
    const put = (trace, xyz) => { traces.push(trace); x.push(xyz[0]); y.push(xyz[1]); z.push(xyz[2]); };
    D.paths.forEach((p, pi) => {
      const base = pi * TRACES;
      const row = readouts.querySelector(`tr[data-path="${p.name}"]`);
      if (i >= p.frames) {
        // The path stopped early (its state stopped being finite): show where it ended.
        row.querySelector(".rotor").textContent = `path ended at t = ${p.endedAt} s`;
        row.querySelector(".q").dataset.q = "null";
        return;
      }
      const q = p.q[i];
      const body = D.vertices.map((v) => rotate(q, v));
      put(base + 2, [body.map((v) => v[0]), body.map((v) => v[1]), body.map((v) => v[2])]);
      for (let a = 0; a < 3; a++) {
        const e = [0, 0, 0]; e[a] = 1.3;
        put(base + 3 + a, segment(rotate(q, e), 1));
      }
      put(base + 6, segment(rotate(q, D.w[i]), scaleW));
      put(base + 7, D.L ? segment(rotate(q, D.L[i]), scaleL) : [[], [], []]);
      const pl = plane(q);
      put(base + 8, pl ? pl.disk : [[], [], []]);
      meshTraces.push(base + 8);
      extra.i.push(pl ? pl.fan[0] : []); extra.j.push(pl ? pl.fan[1] : []); extra.k.push(pl ? pl.fan[2] : []);
      put(base + 9, pl ? pl.arc : [[], [], []]);
      const e = [0, 0, 0]; e[D.axis] = 1;
      const tip = rotate(q, e);
      put(base + 10, [[tip[0]], [tip[1]], [tip[2]]]);

      row.querySelector(".rotor").textContent = "R = " + rotorText(q);
      const cell = row.querySelector(".q");
      cell.textContent = `(${q.map((c) => fmt(c, 6)).join(", ")})`;
      cell.dataset.q = JSON.stringify(q);
      const eu = p.euler[i];
      row.querySelector(".euler").textContent = `(${eu.map((c) => fmt(c, 3) + "°").join(", ")})`;
      const g = row.querySelector(".gimbal");
      g.textContent = p.locked[i] ? "LOCKED (sin θ = 0)" : p.near[i] ? `near (sin θ = ${p.sinTheta[i].toExponential(1)})` : "no";
      g.className = "gimbal" + (p.locked[i] ? " locked" : p.near[i] ? " near" : "");
    });
    if (traces.length) Plotly.restyle(gd, { x, y, z }, traces);
    if (meshTraces.length) Plotly.restyle(gd, extra, meshTraces);
    slider.value = String(i);
    timeLabel.textContent = `t = ${fmt(D.t[i], 4)} s  (${i + 1}/${n})`;
    readouts.dataset.index = String(i);
    readouts.dataset.time = String(D.t[i]);
    document.body.dataset.ready = "true";
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
    if (Number(slider.value) >= n - 1) show(0);
    timer = setInterval(() => {
      const next = Number(slider.value) + 1;
      if (next >= n) { play(); return; }
      show(next);
    }, 50);
  }

  slider.max = String(n - 1);
  slider.addEventListener("input", () => show(Number(slider.value)));
  playButton.addEventListener("click", play);
  Plotly.newPlot(gd, F.data, F.layout, { responsive: true, displaylogo: false }).then(() =>
    show(startIndex()),
  );
})();
