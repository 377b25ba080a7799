// The viewer page of tools/view: draws one run (and optionally a second one) of the
// workbook, its curves, the exact motion and the frame budget. Plain Canvas 2D, no
// library, nothing fetched: the data is in this file (docs/view.md).
"use strict";
(function () {
  const T0 = performance.now();
  const META = JSON.parse(document.getElementById("wb-meta").textContent);
  const RIGID = META.kind === "rigid";
  const C = META.cols.length;            // values per particle or body and frame
  const N = META.n;
  const ORIGIN = META.origin;
  const COLORS = { run: "#1f77b4", run2: "#ff7f0e", exact: "#111111", trail: "#9ecae1",
    trail2: "#fdd0a2", pick: "#d62728", cursor: "#c51b7d", diverged: "#d62728",
    spring: "#9a9a9a", plane: "#7f6a3c", com: "#111111" };
  const BODY_COLORS = ["#4e79a7", "#59a14f", "#edc948", "#b07aa1", "#76b7b2", "#e15759",
    "#9c755f", "#bab0ac"];
  const AXIS_COLORS = ["#d62728", "#2ca02c", "#1f77b4"];

  // ---------------------------------------------------------------- data
  function blob(ref) {  // "#blob:K" -> Float32Array of the K-th binary block
    const el = document.getElementById("wb-blob-" + ref.slice(6));
    const text = el.textContent.trim();
    let bytes;
    if (Uint8Array.fromBase64) {
      bytes = Uint8Array.fromBase64(text);
    } else {
      const bin = atob(text);
      bytes = new Uint8Array(bin.length);
      for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    }
    return new Float32Array(bytes.buffer, bytes.byteOffset, bytes.byteLength / 4);
  }
  const RUNS = META.runs.map(function (r) {
    r.pos = blob(r.data);
    r.frames = r.t.length;
    return r;
  });
  const R1 = RUNS[0], R2 = RUNS[1] || null;
  const EXACT = META.exact ? { kind: META.exact.kind, pos: blob(META.exact.pos),
    paths: META.exact.paths, periodic: META.exact.periodic } : null;
  const SCENE = META.scene;

  function value(run, k, i, d) {  // value d of id i at kept frame k (positions absolute)
    const v = run.pos[(k * N + i) * C + d];
    return d < ORIGIN.length ? v + ORIGIN[d] : v;
  }
  function frameAt(run, t) {  // last kept frame with time <= t (0 if none)
    const ts = run.t;
    let lo = 0, hi = ts.length - 1;
    const tol = 1e-9 * Math.max(Math.abs(ts[ts.length - 1]), 1e-300);
    if (t < ts[0]) return 0;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (ts[mid] <= t + tol) lo = mid; else hi = mid - 1;
    }
    return lo;
  }

  // ---------------------------------------------------------------- state
  const S = { frame: 0, playing: false, playT: R1.t[0], speed: 1, everyFrame: false,
    trails: false, exact: true, run2: true, springs: true, contacts: true, follow: false,
    pick: null, lastTick: null, dirty: true, drawMs: [], draws: 0,
    view2: null, cam: null, ready: false, lastDrawn: null };

  // ---------------------------------------------------------------- formatting
  function fmt(x, digits) {
    if (x === null || x === undefined) return "—";
    if (!isFinite(x)) return String(x);
    digits = digits || 6;
    if (x !== 0 && (Math.abs(x) >= 1e6 || Math.abs(x) < 1e-4)) return x.toExponential(digits - 1);
    return String(+x.toPrecision(digits));
  }
  function fmtT(t) {
    const dt = R1.dt;
    if (dt && dt > 0) {
      const dec = Math.max(0, Math.min(9, Math.ceil(-Math.log10(dt) + 1e-9)));
      if (Math.abs(t) < 1e6) return t.toFixed(dec);
    }
    return fmt(t, 7);
  }
  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (c) {
      return { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c];
    });
  }

  // ---------------------------------------------------------------- page text
  const el = function (id) { return document.getElementById(id); };
  function header() {
    const name = META.name || (META.scene_path || R1.path).split("/").pop();
    el("title").textContent = name;
    document.title = name + " — tools/view";
    let sub = (RIGID ? N + (N === 1 ? " body" : " bodies") : N + (N === 1 ? " particle" : " particles"))
      + " · " + R1.label + " (" + R1.path + ")";
    if (R2) sub += " against " + R2.label + " (" + R2.path + ")";
    el("subtitle").textContent = sub;
    el("desc").textContent = META.description || (META.scene ? "" :
      "No --scene given: particles are drawn as dots (no radii, springs, planes); bodies as "
      + "their axes.");
    const notes = [];
    let bad = false;
    RUNS.forEach(function (r, ri) {
      const who = RUNS.length > 1 ? r.label + ": " : "";
      if (r.diverged) {
        bad = true;
        notes.push("<b>" + esc(who) + "diverged at step " + esc(r.diverged.step) + "</b> (t = "
          + esc(fmt(r.diverged.t, 7)) + " s): " + esc(r.diverged.why)
          + ' <button data-run="' + ri + '" class="godiv">go to that step</button>');
      }
      (r.summary.warnings || []).forEach(function (w) {
        notes.push(esc(who) + "warning: " + esc(w));
      });
      if (r.summary.unconverged) notes.push(esc(who) + r.summary.unconverged
        + " steps' implicit solve did not converge");
      if (r.kept_every > 1) notes.push(esc(who) + "showing every " + r.kept_every
        + "th written step (" + r.frames + " of " + r.frames_written
        + ") to keep this page small: docs/view.md");
      if (!r.stats) notes.push(esc(who) + "no stats file: no curves (--stats, or <run>-stats.csv beside the trace)");
      if (!Object.keys(r.summary).length) notes.push(esc(who)
        + "no summary: no frame budget and no divergence mark (--summary FILE: the run's "
        + "stdout saved, e.g. &gt; out/run-summary.json)");
    });
    if (META.difference && META.difference.identical) notes.push("The two runs coincide: every "
      + "written position is the same in both (their curves lie on top of each other).");
    if (SCENE && SCENE.springs_left_out) notes.push(SCENE.springs_left_out
      + " springs not drawn (more than the page draws)");
    const b = el("banner");
    if (notes.length) {
      b.innerHTML = notes.join("<br>");
      b.style.display = "block";
      if (!bad) b.className = "warn";
    }
    Array.prototype.forEach.call(b.querySelectorAll("button.godiv"), function (btn) {
      btn.addEventListener("click", function () {
        const r = RUNS[+btn.dataset.run];
        seekT(r.diverged.t === null ? r.t[r.frames - 1] : r.diverged.t);
      });
    });
    el("c-trails").checked = N <= 50;  // a few particles: their paths show by default
    if (!EXACT) el("l-exact").style.display = "none";
    if (!R2) el("l-run2").style.display = "none";
    if (!SCENE || RIGID || !(SCENE.springs.length || SCENE.anchored.length))
      el("l-springs").style.display = "none";
    if (!RIGID || !SCENE || !SCENE.planes.length) el("l-contacts").style.display = "none";
    el("help-cam").textContent = RIGID
      ? "drag to turn the camera, Shift+drag (or right-drag) to move it, wheel to zoom, F to fit"
      : "drag to move the camera, wheel to zoom, F to fit";
  }

  function legend() {
    const items = [];
    if (RIGID) {
      items.push('<span class="sw" style="color:' + BODY_COLORS[0] + '">■</span>' + esc(R1.label));
      if (R2) items.push('<span class="sw" style="color:' + COLORS.run2 + '">□</span>' + esc(R2.label) + " (edges)");
      items.push('<span class="sw" style="color:' + COLORS.com + '">●</span>centre of mass, axes '
        + '<span style="color:' + AXIS_COLORS[0] + '">x</span> <span style="color:' + AXIS_COLORS[1]
        + '">y</span> <span style="color:' + AXIS_COLORS[2] + '">z</span>');
      if (SCENE && SCENE.planes.length) items.push('<span class="sw" style="color:' + COLORS.pick
        + '">●</span>contact point (within 1 mm of a plane)');
      if (SCENE && SCENE.hinges.length) items.push('<span class="sw">◆</span>hinge anchor'
        + (SCENE.hinges.some(function (h) { return h.axis; }) ? ', <span style="color:#7b3294">—</span> hinge axis' : ""));
    } else {
      items.push('<span class="sw" style="color:' + COLORS.run + '">●</span>' + esc(R1.label));
      if (R2) items.push('<span class="sw" style="color:' + COLORS.run2 + '">○</span>' + esc(R2.label));
      if (EXACT) items.push('<span class="sw">◌</span>exact (' + esc(EXACT.kind) + ")");
      if (SCENE && SCENE.pinned.length) items.push('<span class="sw">▲</span>pinned');
    }
    el("legend").innerHTML = items.join("<br>");
  }

  // ---------------------------------------------------------------- canvas helpers
  const canvas = el("stage");
  const ctx = canvas.getContext("2d");
  let W = 0, H = 0, DPR = 1;
  function resize() {
    DPR = window.devicePixelRatio || 1;
    const r = canvas.getBoundingClientRect();
    W = Math.max(10, r.width); H = Math.max(10, r.height);
    canvas.width = Math.round(W * DPR); canvas.height = Math.round(H * DPR);
    charts.forEach(function (c) { c.resize(); });
    S.dirty = true;
  }
  function gridLabel(v, step) {  // a grid label: multiples of the step, without rounding noise
    const k = Math.round(v / step);
    return fmt(k * step, Math.max(1, Math.ceil(Math.log10(Math.abs(k) + 1)) + 2));
  }
  function niceStep(span, target) {  // a 1-2-5 step giving about `target` intervals
    const raw = span / Math.max(target, 1);
    const p = Math.pow(10, Math.floor(Math.log10(raw)));
    const m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
  }

  // ---------------------------------------------------------------- 2D view
  function fit2(frameOnly) {
    let lo, hi;
    if (frameOnly) {
      lo = [Infinity, Infinity]; hi = [-Infinity, -Infinity];
      for (let i = 0; i < N; i++) {
        const x = value(R1, S.frame, i, 0), y = value(R1, S.frame, i, 1);
        if (!isFinite(x) || !isFinite(y)) continue;
        lo[0] = Math.min(lo[0], x); hi[0] = Math.max(hi[0], x);
        lo[1] = Math.min(lo[1], y); hi[1] = Math.max(hi[1], y);
      }
      if (!isFinite(lo[0])) return;
    } else if (META.box) {
      lo = META.box.lo.slice(); hi = META.box.hi.slice();
    } else {
      lo = [-1, -1]; hi = [1, 1];
    }
    let rmax = 0;
    if (SCENE) for (let i = 0; i < SCENE.radii.length; i++) rmax = Math.max(rmax, SCENE.radii[i]);
    if (!frameOnly && SCENE) {
      SCENE.discs.forEach(function (d) {
        lo[0] = Math.min(lo[0], d.center[0] - d.radius); hi[0] = Math.max(hi[0], d.center[0] + d.radius);
        lo[1] = Math.min(lo[1], d.center[1] - d.radius); hi[1] = Math.max(hi[1], d.center[1] + d.radius);
      });
      SCENE.marks.concat(SCENE.anchored.map(function (a) { return { at: [a[1], a[2]] }; }))
        .concat(SCENE.planes.map(function (p) { return { at: p.point }; }))
        .forEach(function (m) {
          lo[0] = Math.min(lo[0], m.at[0]); hi[0] = Math.max(hi[0], m.at[0]);
          lo[1] = Math.min(lo[1], m.at[1]); hi[1] = Math.max(hi[1], m.at[1]);
        });
    }
    if (!frameOnly && EXACT && EXACT.periodic) EXACT.paths.forEach(function (p) {
      p.forEach(function (q) {
        lo[0] = Math.min(lo[0], q[0]); hi[0] = Math.max(hi[0], q[0]);
        lo[1] = Math.min(lo[1], q[1]); hi[1] = Math.max(hi[1], q[1]);
      });
    });
    const span = Math.max(hi[0] - lo[0], hi[1] - lo[1], 4 * rmax, 1e-9 * Math.max(1, Math.abs(lo[0]), Math.abs(lo[1])));
    const pad = 0.08 * span + rmax;
    const sx = W / Math.max(hi[0] - lo[0] + 2 * pad, span * 0.05);
    const sy = H / Math.max(hi[1] - lo[1] + 2 * pad, span * 0.05);
    S.view2 = { cx: (lo[0] + hi[0]) / 2, cy: (lo[1] + hi[1]) / 2, s: Math.min(sx, sy) };
    S.dirty = true;
  }
  function sx(x) { return W / 2 + (x - S.view2.cx) * S.view2.s; }
  function sy(y) { return H / 2 - (y - S.view2.cy) * S.view2.s; }

  function drawGrid2() {
    const v = S.view2;
    const step = niceStep(W / v.s, W / 110);
    const x0 = v.cx - W / 2 / v.s, x1 = v.cx + W / 2 / v.s;
    const y0 = v.cy - H / 2 / v.s, y1 = v.cy + H / 2 / v.s;
    ctx.lineWidth = 1;
    ctx.strokeStyle = "#eeeeee";
    ctx.fillStyle = "#999";
    ctx.font = "11px sans-serif";
    ctx.beginPath();
    for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) {
      ctx.moveTo(Math.round(sx(x)) + 0.5, 0); ctx.lineTo(Math.round(sx(x)) + 0.5, H);
    }
    for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) {
      ctx.moveTo(0, Math.round(sy(y)) + 0.5); ctx.lineTo(W, Math.round(sy(y)) + 0.5);
    }
    ctx.stroke();
    for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) ctx.fillText(gridLabel(x, step), sx(x) + 2, H - 4);
    for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) ctx.fillText(gridLabel(y, step), 3, sy(y) - 2);
    ctx.fillText("m", W - 14, H - 4);
  }

  function drawScene2() {
    if (!SCENE) return;
    const v = S.view2;
    const L = 4 * (W + H) / v.s;
    SCENE.planes.forEach(function (p) {
      const n = p.normal, t = [-n[1], n[0]];
      const depth = p.thickness ? p.thickness : L;
      const a = [p.point[0] - L * t[0], p.point[1] - L * t[1]];
      const b = [p.point[0] + L * t[0], p.point[1] + L * t[1]];
      ctx.fillStyle = p.thickness ? "rgba(127,106,60,0.45)" : "rgba(127,106,60,0.16)";
      ctx.beginPath();
      ctx.moveTo(sx(a[0]), sy(a[1])); ctx.lineTo(sx(b[0]), sy(b[1]));
      ctx.lineTo(sx(b[0] - depth * n[0]), sy(b[1] - depth * n[1]));
      ctx.lineTo(sx(a[0] - depth * n[0]), sy(a[1] - depth * n[1]));
      ctx.closePath(); ctx.fill();
      ctx.strokeStyle = COLORS.plane; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.moveTo(sx(a[0]), sy(a[1])); ctx.lineTo(sx(b[0]), sy(b[1])); ctx.stroke();
    });
    SCENE.discs.forEach(function (d) {
      ctx.fillStyle = "rgba(120,120,120,0.25)"; ctx.strokeStyle = "#888"; ctx.lineWidth = 1;
      ctx.beginPath(); ctx.arc(sx(d.center[0]), sy(d.center[1]), d.radius * v.s, 0, 2 * Math.PI);
      ctx.fill(); ctx.stroke();
    });
    ctx.font = "11px sans-serif";
    SCENE.marks.forEach(function (m) {
      const x = sx(m.at[0]), y = sy(m.at[1]);
      ctx.strokeStyle = "#555"; ctx.fillStyle = "#555"; ctx.lineWidth = 1.5;
      if (m.radius) {
        ctx.setLineDash([4, 4]);
        ctx.beginPath(); ctx.arc(x, y, m.radius * v.s, 0, 2 * Math.PI); ctx.stroke();
        ctx.setLineDash([]);
      }
      ctx.beginPath(); ctx.moveTo(x - 6, y); ctx.lineTo(x + 6, y); ctx.moveTo(x, y - 6); ctx.lineTo(x, y + 6);
      ctx.stroke();
      ctx.fillText(m.label, x + 7, y - 5);
    });
  }

  function radiusPx(i) {
    const r = SCENE ? SCENE.radii[i] * S.view2.s : 0;
    return Math.max(r, N > MANY ? 1.5 : N > 100 ? 2.5 : 4);
  }

  function drawSprings2(run, k, color) {
    if (!SCENE || !S.springs) return;
    ctx.strokeStyle = color; ctx.lineWidth = 1;
    ctx.beginPath();
    const sp = SCENE.springs;
    for (let s = 0; s < sp.length; s++) {
      const i = sp[s][0], j = sp[s][1];
      const xi = value(run, k, i, 0), yi = value(run, k, i, 1);
      const xj = value(run, k, j, 0), yj = value(run, k, j, 1);
      if (!isFinite(xi + yi + xj + yj)) continue;
      ctx.moveTo(sx(xi), sy(yi)); ctx.lineTo(sx(xj), sy(yj));
    }
    SCENE.anchored.forEach(function (a) {
      const x = value(run, k, a[0], 0), y = value(run, k, a[0], 1);
      if (!isFinite(x + y)) return;
      ctx.moveTo(sx(a[1]), sy(a[2])); ctx.lineTo(sx(x), sy(y));
    });
    ctx.stroke();
    ctx.fillStyle = "#555";
    SCENE.anchored.forEach(function (a) { ctx.fillRect(sx(a[1]) - 3, sy(a[2]) - 3, 6, 6); });
  }

  function trailIds() {
    const ids = [];
    const limit = 300;
    if (N <= limit) { for (let i = 0; i < N; i++) ids.push(i); }
    else { for (let q = 0; q < limit; q++) ids.push(Math.floor(q * N / limit)); }
    if (S.pick !== null && ids.indexOf(S.pick) < 0) ids.push(S.pick);
    return ids;
  }
  function drawTrails2(run, k, color) {
    const ids = trailIds();
    const first = N > 50 ? Math.max(0, k - 60) : 0;
    ctx.strokeStyle = color; ctx.lineWidth = 1.5;
    ctx.beginPath();
    ids.forEach(function (i) {
      let started = false;
      for (let q = first; q <= k; q++) {
        const x = value(run, q, i, 0), y = value(run, q, i, 1);
        if (!isFinite(x + y)) { started = false; continue; }
        if (!started) { ctx.moveTo(sx(x), sy(y)); started = true; } else ctx.lineTo(sx(x), sy(y));
      }
    });
    ctx.stroke();
  }

  function drawParticles2(run, k, fill, hollow) {  // N <= MANY: anti-aliased discs
    ctx.fillStyle = fill; ctx.strokeStyle = fill;
    ctx.lineWidth = 2;
    ctx.beginPath();
    for (let i = 0; i < N; i++) {
      const x = value(run, k, i, 0), y = value(run, k, i, 1);
      if (!isFinite(x) || !isFinite(y)) continue;
      const px = sx(x), py = sy(y), r = radiusPx(i);
      if (px < -r || px > W + r || py < -r || py > H + r) continue;
      ctx.moveTo(px + r, py);
      ctx.arc(px, py, r, 0, 2 * Math.PI);
    }
    if (hollow) ctx.stroke(); else ctx.fill();
    if (!hollow && N <= 400) {
      ctx.strokeStyle = "rgba(0,0,0,0.35)"; ctx.lineWidth = 1; ctx.stroke();
    }
  }

  // Many particles are stamped into a pixel buffer over a cached background: filling a
  // path of 10^4 arcs takes tens of milliseconds in a software canvas, stamping about one.
  const MANY = 1000;
  let BG = null, BUF = null;
  const STAMPS = {};
  function stampOffsets(R, ring) {
    const key = R + (ring ? "r" : "d");
    if (STAMPS[key]) return STAMPS[key];
    const out = [];
    for (let dy = -R - 1; dy <= R + 1; dy++) for (let dx = -R - 1; dx <= R + 1; dx++) {
      const d2 = dx * dx + dy * dy;
      if (ring ? d2 <= (R + 0.5) * (R + 0.5) && d2 >= (R - 1) * (R - 1) : d2 <= R * R + 0.8 * R) out.push(dx, dy);
    }
    return (STAMPS[key] = new Int32Array(out));
  }
  function rgba32(hex) {  // ImageData's bytes R, G, B, A as one little-endian word
    const v = parseInt(hex.slice(1), 16);
    return ((255 << 24) | ((v & 255) << 16) | (v & 0xff00) | ((v >> 16) & 255)) >>> 0;
  }
  function background2() {
    const v = S.view2;
    const key = [W, H, DPR, v.cx, v.cy, v.s].join();
    if (BG && BG.key === key) return;
    ctx.setTransform(DPR, 0, 0, DPR, 0, 0);
    ctx.fillStyle = "#ffffff"; ctx.fillRect(0, 0, W, H);
    drawGrid2();
    drawScene2();
    BUF = ctx.getImageData(0, 0, canvas.width, canvas.height);
    BG = { key: key, pixels: new Uint32Array(BUF.data.buffer.slice(0)) };
  }
  function stampParticles2(run, k, color, ring, big) {
    const u = new Uint32Array(BUF.data.buffer), cw = canvas.width, ch = canvas.height;
    const col = rgba32(color);
    for (let i = 0; i < N; i++) {
      const x = value(run, k, i, 0), y = value(run, k, i, 1);
      if (!isFinite(x) || !isFinite(y)) continue;
      const rp = radiusPx(i) * DPR;
      const R = Math.max(ring ? 2 : 1, Math.round(rp));
      const cx = Math.round(sx(x) * DPR), cy = Math.round(sy(y) * DPR);
      if (cx < -R - 1 || cy < -R - 1 || cx > cw + R || cy > ch + R) continue;
      if (R > 12) { big.push([i, ring]); continue; }
      const off = stampOffsets(R, ring);
      const inside = cx > R && cy > R && cx < cw - R - 1 && cy < ch - R - 1;
      for (let q = 0; q < off.length; q += 2) {
        const X = cx + off[q], Y = cy + off[q + 1];
        if (inside || (X >= 0 && Y >= 0 && X < cw && Y < ch)) u[Y * cw + X] = col;
      }
    }
  }

  function drawPinned2(k) {
    if (!SCENE || !SCENE.pinned.length) return;
    ctx.fillStyle = "#222";
    SCENE.pinned.forEach(function (i) {
      const x = sx(value(R1, k, i, 0)), y = sy(value(R1, k, i, 1));
      if (!isFinite(x + y)) return;
      ctx.beginPath(); ctx.moveTo(x, y - 9); ctx.lineTo(x - 6, y - 18); ctx.lineTo(x + 6, y - 18);
      ctx.closePath(); ctx.fill();
    });
  }

  function drawExact2(k) {
    if (!EXACT || !S.exact) return;
    ctx.strokeStyle = "rgba(17,17,17,0.55)"; ctx.lineWidth = 1.2;
    ctx.setLineDash([5, 4]);
    ctx.beginPath();
    EXACT.paths.forEach(function (p) {
      p.forEach(function (q, j) {
        if (j === 0) ctx.moveTo(sx(q[0]), sy(q[1])); else ctx.lineTo(sx(q[0]), sy(q[1]));
      });
    });
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.strokeStyle = COLORS.exact; ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (let i = 0; i < N; i++) {
      const x = EXACT.pos[(k * N + i) * 2] + ORIGIN[0], y = EXACT.pos[(k * N + i) * 2 + 1] + ORIGIN[1];
      const r = Math.max(radiusPx(i) + 3, 6);
      ctx.moveTo(sx(x) + r, sy(y)); ctx.arc(sx(x), sy(y), r, 0, 2 * Math.PI);
    }
    ctx.stroke();
  }

  function drawMany2(k, k2) {  // the pixel-buffer path (N > MANY): vectors drawn on top
    background2();
    new Uint32Array(BUF.data.buffer).set(BG.pixels);
    const big = [];
    stampParticles2(R1, k, COLORS.run, false, big);
    if (k2 !== null) stampParticles2(R2, k2, COLORS.run2, true, big);
    ctx.putImageData(BUF, 0, 0);
    ctx.setTransform(DPR, 0, 0, DPR, 0, 0);
    big.forEach(function (b) {  // discs larger than a stamp
      const run = b[1] ? R2 : R1, kk = b[1] ? k2 : k;
      const x = sx(value(run, kk, b[0], 0)), y = sy(value(run, kk, b[0], 1)), r = radiusPx(b[0]);
      ctx.fillStyle = COLORS.run; ctx.strokeStyle = COLORS.run2; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(x, y, r, 0, 2 * Math.PI);
      if (b[1]) ctx.stroke(); else ctx.fill();
    });
    if (k2 !== null) drawSprings2(R2, k2, "rgba(255,127,14,0.45)");
    drawSprings2(R1, k, COLORS.spring);
    if (S.trails) {
      if (k2 !== null) drawTrails2(R2, k2, COLORS.trail2);
      drawTrails2(R1, k, COLORS.trail);
    }
    drawPinned2(k);
  }

  function draw2() {
    if (!S.view2 || S.follow) fit2(S.follow);
    const k = S.frame;
    const k2 = R2 && S.run2 ? frameAt(R2, R1.t[k]) : null;
    if (N > MANY) {
      drawMany2(k, k2);
      drawOverlays2(k);
      S.lastDrawn = { frame: k, frame2: k2 };
      return;
    }
    ctx.setTransform(DPR, 0, 0, DPR, 0, 0);
    ctx.fillStyle = "#ffffff"; ctx.fillRect(0, 0, W, H);
    drawGrid2();
    drawScene2();
    if (k2 !== null) drawSprings2(R2, k2, "rgba(255,127,14,0.45)");
    drawSprings2(R1, k, COLORS.spring);
    if (S.trails) {
      if (k2 !== null) drawTrails2(R2, k2, COLORS.trail2);
      drawTrails2(R1, k, COLORS.trail);
    }
    drawParticles2(R1, k, COLORS.run, false);
    drawPinned2(k);
    if (k2 !== null) drawParticles2(R2, k2, COLORS.run2, true);
    drawOverlays2(k);
    S.lastDrawn = { frame: k, frame2: k2 };
  }
  function drawOverlays2(k) {
    drawExact2(k);
    if (S.pick !== null) {
      const x = value(R1, k, S.pick, 0), y = value(R1, k, S.pick, 1);
      if (isFinite(x + y)) {
        ctx.strokeStyle = COLORS.pick; ctx.lineWidth = 2;
        ctx.beginPath(); ctx.arc(sx(x), sy(y), radiusPx(S.pick) + 5, 0, 2 * Math.PI); ctx.stroke();
        ctx.fillStyle = COLORS.pick; ctx.font = "12px sans-serif";
        ctx.fillText("#" + S.pick, sx(x) + radiusPx(S.pick) + 7, sy(y) - 7);
      }
    }
  }

  // ---------------------------------------------------------------- 3D view
  function sub3(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function add3(a, b) { return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]; }
  function mul3(a, s) { return [a[0] * s, a[1] * s, a[2] * s]; }
  function dot3(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross3(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function norm3(a) { const n = Math.hypot(a[0], a[1], a[2]); return n > 0 ? mul3(a, 1 / n) : a; }
  function rot(q) {  // rotation matrix (rows) of a quaternion [w, x, y, z], normalised
    const n = Math.hypot(q[0], q[1], q[2], q[3]);
    if (!(n > 0) || !isFinite(n)) return null;
    const w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]];
  }
  function apply(R, p) {
    return [R[0][0] * p[0] + R[0][1] * p[1] + R[0][2] * p[2],
      R[1][0] * p[0] + R[1][1] * p[1] + R[1][2] * p[2],
      R[2][0] * p[0] + R[2][1] * p[1] + R[2][2] * p[2]];
  }
  function applyT(R, p) {
    return [R[0][0] * p[0] + R[1][0] * p[1] + R[2][0] * p[2],
      R[0][1] * p[0] + R[1][1] * p[1] + R[2][1] * p[2],
      R[0][2] * p[0] + R[1][2] * p[1] + R[2][2] * p[2]];
  }
  function pose(run, k, i) {
    const x = [value(run, k, i, 0), value(run, k, i, 1), value(run, k, i, 2)];
    const q = [value(run, k, i, 3), value(run, k, i, 4), value(run, k, i, 5), value(run, k, i, 6)];
    const R = rot(q);
    if (!R || !isFinite(x[0] + x[1] + x[2])) return null;
    return { x: x, R: R };
  }
  const UP = RIGID && SCENE ? SCENE.up : [0, 0, 1];
  const E1 = (function () {
    const a = Math.abs(UP[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    return norm3(sub3(a, mul3(UP, dot3(a, UP))));
  })();
  const E2 = cross3(UP, E1);

  function shapeSize(i) {
    const s = SCENE ? SCENE.shapes[i] : null;
    if (!s || s.shape === "unknown") return 0.2;
    if (s.shape === "box") return Math.max(s.size[0], s.size[1], s.size[2]);
    if (s.shape === "sphere") return 2 * s.radius;
    return Math.max(2 * s.radius, s.length);
  }
  let BIG = 0;
  function fit3(frameOnly) {
    let lo, hi;
    if (frameOnly || !META.box) {
      lo = [Infinity, Infinity, Infinity]; hi = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < N; i++) for (let d = 0; d < 3; d++) {
        const v = value(R1, S.frame, i, d);
        if (isFinite(v)) { lo[d] = Math.min(lo[d], v); hi[d] = Math.max(hi[d], v); }
      }
      if (!isFinite(lo[0])) { lo = [-1, -1, -1]; hi = [1, 1, 1]; }
    } else { lo = META.box.lo.slice(); hi = META.box.hi.slice(); }
    BIG = 0;
    for (let i = 0; i < N; i++) BIG = Math.max(BIG, shapeSize(i));
    if (SCENE) SCENE.hinges.forEach(function (h) {
      for (let d = 0; d < 3; d++) { lo[d] = Math.min(lo[d], h.anchor[d]); hi[d] = Math.max(hi[d], h.anchor[d]); }
    });
    const target = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2];
    const radius = Math.max(Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2 + BIG * 0.75, 1e-6);
    const keep = S.cam || { yaw: -Math.PI / 2 + 0.6, pitch: 0.35 };
    const fov = 40 * Math.PI / 180;
    const aspect = Math.min(1, W / H);
    S.cam = { target: target, yaw: keep.yaw, pitch: keep.pitch, fov: fov,
      dist: radius / Math.sin(fov / 2 * aspect) * 1.05, radius: radius };
    S.dirty = true;
  }
  function camera() {
    const c = S.cam;
    const dir = add3(mul3(add3(mul3(E1, Math.cos(c.yaw)), mul3(E2, Math.sin(c.yaw))), Math.cos(c.pitch)),
      mul3(UP, Math.sin(c.pitch)));
    const eye = add3(c.target, mul3(dir, c.dist));
    const f = norm3(sub3(c.target, eye));
    let r = cross3(f, UP);
    r = Math.hypot(r[0], r[1], r[2]) > 1e-9 ? norm3(r) : E1;
    const u = cross3(r, f);
    return { eye: eye, f: f, r: r, u: u, F: (H / 2) / Math.tan(c.fov / 2),
      light: norm3(add3(add3(UP, mul3(f, -1.0)), mul3(r, 0.4))) };
  }
  function project(cam, p) {
    const d = sub3(p, cam.eye);
    const z = dot3(d, cam.f);
    if (!(z > 1e-6 * cam.F / 1000 + 1e-9)) return null;
    return [W / 2 + cam.F * dot3(d, cam.r) / z, H / 2 - cam.F * dot3(d, cam.u) / z, z];
  }
  function shade(hex, k) {
    const v = parseInt(hex.slice(1), 16);
    const r = (v >> 16) & 255, g = (v >> 8) & 255, b = v & 255;
    const c = function (x) { return Math.min(255, Math.round(x * k)); };
    return "rgb(" + c(r) + "," + c(g) + "," + c(b) + ")";
  }
  function boxCorners(size) {
    const out = [];
    for (let k = 0; k < 8; k++) out.push([(k & 1 ? 0.5 : -0.5) * size[0], (k & 2 ? 0.5 : -0.5) * size[1],
      (k & 4 ? 0.5 : -0.5) * size[2]]);
    return out;
  }
  const BOX_FACES = [[[0, 2, 6, 4], [-1, 0, 0]], [[1, 5, 7, 3], [1, 0, 0]], [[0, 4, 5, 1], [0, -1, 0]],
    [[2, 3, 7, 6], [0, 1, 0]], [[0, 1, 3, 2], [0, 0, -1]], [[4, 6, 7, 5], [0, 0, 1]]];
  const CYL_N = 24;
  function bodyFaces(i, P) {  // [{pts: world points, n: world normal}]
    const s = SCENE ? SCENE.shapes[i] : null;
    const faces = [];
    const W_ = function (p) { return add3(P.x, apply(P.R, p)); };
    if (s && s.shape === "box") {
      const c = boxCorners(s.size).map(W_);
      BOX_FACES.forEach(function (f) {
        faces.push({ pts: f[0].map(function (j) { return c[j]; }), n: apply(P.R, f[1]) });
      });
    } else if (s && s.shape === "cylinder") {
      const h = s.length / 2, r = s.radius;
      const top = [], bot = [];
      for (let k = 0; k < CYL_N; k++) {
        const a = 2 * Math.PI * k / CYL_N;
        top.push(W_([r * Math.cos(a), r * Math.sin(a), h]));
        bot.push(W_([r * Math.cos(a), r * Math.sin(a), -h]));
      }
      for (let k = 0; k < CYL_N; k++) {
        const k1 = (k + 1) % CYL_N, a = 2 * Math.PI * (k + 0.5) / CYL_N;
        faces.push({ pts: [bot[k], bot[k1], top[k1], top[k]], n: apply(P.R, [Math.cos(a), Math.sin(a), 0]), seam: true });
      }
      faces.push({ pts: top.slice().reverse(), n: apply(P.R, [0, 0, 1]) });
      faces.push({ pts: bot, n: apply(P.R, [0, 0, -1]) });
    }
    return faces;
  }
  function contactPoints(i, P) {  // the rigid lab's candidates (framework/drivers/rigid)
    const s = SCENE.shapes[i], out = [];
    SCENE.planes.forEach(function (pl) {
      let cand = [];
      if (s.shape === "sphere") cand = [sub3(P.x, mul3(pl.normal, s.radius))];
      else if (s.shape === "box") cand = boxCorners(s.size).map(function (p) { return add3(P.x, apply(P.R, p)); });
      else if (s.shape === "cylinder") {
        for (let e = -1; e <= 1; e += 2) for (let k = 0; k < 16; k++) {
          const a = 2 * Math.PI * k / 16;
          cand.push(add3(P.x, apply(P.R, [s.radius * Math.cos(a), s.radius * Math.sin(a), 0.5 * e * s.length])));
        }
      }
      cand.forEach(function (p) { if (dot3(sub3(p, pl.point), pl.normal) < SCENE.contact_slop) out.push(p); });
    });
    return out;
  }

  function drawFloor3(cam) {
    if (!SCENE) return;
    const c = S.cam;
    SCENE.planes.forEach(function (pl) {
      const n = pl.normal;
      const a = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
      const u = norm3(sub3(a, mul3(n, dot3(a, n)))), w = cross3(n, u);
      const centre = sub3(c.target, mul3(n, dot3(sub3(c.target, pl.point), n)));
      const half = Math.max(c.radius * 1.6, BIG * 2);
      const step = niceStep(2 * half, 10);
      const corners = [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(function (q) {
        return project(cam, add3(centre, add3(mul3(u, q[0] * half), mul3(w, q[1] * half))));
      });
      const above = dot3(sub3(cam.eye, pl.point), n) > 0;
      if (corners.every(function (q) { return q; })) {
        ctx.fillStyle = above ? "rgba(200,184,138,0.35)" : "rgba(200,184,138,0.12)";
        ctx.beginPath();
        corners.forEach(function (q, j) { if (j === 0) ctx.moveTo(q[0], q[1]); else ctx.lineTo(q[0], q[1]); });
        ctx.closePath(); ctx.fill();
      }
      ctx.strokeStyle = "rgba(127,106,60,0.35)"; ctx.lineWidth = 1;
      ctx.beginPath();
      const m = Math.floor(half / step);
      for (let j = -m; j <= m; j++) {
        [[u, w], [w, u]].forEach(function (ax) {
          const p0 = project(cam, add3(centre, add3(mul3(ax[0], j * step), mul3(ax[1], -half))));
          const p1 = project(cam, add3(centre, add3(mul3(ax[0], j * step), mul3(ax[1], half))));
          if (p0 && p1) { ctx.moveTo(p0[0], p0[1]); ctx.lineTo(p1[0], p1[1]); }
        });
      }
      ctx.stroke();
    });
  }

  function draw3() {
    if (!S.cam || S.follow) fit3(S.follow);
    const cam = camera();
    ctx.setTransform(DPR, 0, 0, DPR, 0, 0);
    ctx.fillStyle = "#ffffff"; ctx.fillRect(0, 0, W, H);
    drawFloor3(cam);
    const k = S.frame;
    const k2 = R2 && S.run2 ? frameAt(R2, R1.t[k]) : null;
    if (S.trails) [[R1, k, COLORS.trail], [R2, k2, COLORS.trail2]].forEach(function (a) {
      if (!a[0] || a[1] === null) return;
      ctx.strokeStyle = a[2]; ctx.lineWidth = 2;
      ctx.beginPath();
      for (let i = 0; i < N; i++) {
        let started = false;
        for (let q = 0; q <= a[1]; q++) {
          const p = project(cam, [value(a[0], q, i, 0), value(a[0], q, i, 1), value(a[0], q, i, 2)]);
          if (!p || !isFinite(p[0] + p[1])) { started = false; continue; }
          if (!started) { ctx.moveTo(p[0], p[1]); started = true; } else ctx.lineTo(p[0], p[1]);
        }
      }
      ctx.stroke();
    });
    // Bodies: every face of every body, far to near (painter's order), back faces culled.
    const items = [];
    const poses = [];
    for (let i = 0; i < N; i++) {
      const P = pose(R1, k, i);
      poses.push(P);
      if (!P) continue;
      const s = SCENE ? SCENE.shapes[i] : null;
      const col = BODY_COLORS[i % BODY_COLORS.length];
      if (s && s.shape === "sphere") {
        const c = project(cam, P.x);
        if (c) items.push({ z: c[2], sphere: true, c: c, P: P, r: s.radius, col: col });
        continue;
      }
      bodyFaces(i, P).forEach(function (f) {
        let cx = 0, cy = 0, cz = 0;
        f.pts.forEach(function (p) { cx += p[0]; cy += p[1]; cz += p[2]; });
        const m = [cx / f.pts.length, cy / f.pts.length, cz / f.pts.length];
        if (dot3(f.n, sub3(cam.eye, m)) <= 0) return;
        const pp = f.pts.map(function (p) { return project(cam, p); });
        if (pp.some(function (p) { return !p; })) return;
        const z = pp.reduce(function (a, p) { return a + p[2]; }, 0) / pp.length;
        items.push({ z: z, pp: pp, seam: f.seam, col: shade(col, 0.5 + 0.6 * Math.max(0, dot3(f.n, cam.light))) });
      });
    }
    items.sort(function (a, b) { return b.z - a.z; });
    items.forEach(function (it) {
      if (it.sphere) { drawSphere(cam, it); return; }
      ctx.fillStyle = it.col; ctx.strokeStyle = it.seam ? it.col : "rgba(0,0,0,0.45)"; ctx.lineWidth = 1;
      ctx.beginPath();
      it.pp.forEach(function (p, j) { if (j === 0) ctx.moveTo(p[0], p[1]); else ctx.lineTo(p[0], p[1]); });
      ctx.closePath(); ctx.fill(); ctx.stroke();
    });
    // The second run: edges only.
    if (k2 !== null) for (let i = 0; i < N; i++) {
      const P = pose(R2, k2, i);
      if (!P) continue;
      ctx.strokeStyle = COLORS.run2; ctx.lineWidth = 1.5; ctx.setLineDash([5, 3]);
      const s = SCENE ? SCENE.shapes[i] : null;
      ctx.beginPath();
      if (s && s.shape === "sphere") {
        const c = project(cam, P.x);
        if (c) { ctx.moveTo(c[0] + cam.F * s.radius / c[2], c[1]); ctx.arc(c[0], c[1], cam.F * s.radius / c[2], 0, 2 * Math.PI); }
      } else bodyFaces(i, P).forEach(function (f) {
        const pp = f.pts.map(function (p) { return project(cam, p); });
        if (pp.some(function (p) { return !p; })) return;
        pp.forEach(function (p, j) { if (j === 0) ctx.moveTo(p[0], p[1]); else ctx.lineTo(p[0], p[1]); });
        ctx.closePath();
      });
      ctx.stroke(); ctx.setLineDash([]);
      const c = project(cam, P.x);
      if (c) { ctx.fillStyle = COLORS.run2; ctx.beginPath(); ctx.arc(c[0], c[1], 3, 0, 2 * Math.PI); ctx.fill(); }
    }
    // Hinges: anchor, the body point pinned to it, a revolute hinge's axis.
    if (SCENE) SCENE.hinges.forEach(function (h) {
      const a = project(cam, h.anchor);
      const P0 = pose(R1, 0, h.body), P = poses[h.body];
      if (h.axis) {
        const L = Math.max(shapeSize(h.body), S.cam.radius * 0.3);
        const p0 = project(cam, sub3(h.anchor, mul3(h.axis, L))), p1 = project(cam, add3(h.anchor, mul3(h.axis, L)));
        if (p0 && p1) {
          ctx.strokeStyle = "#7b3294"; ctx.lineWidth = 2.5;
          ctx.beginPath(); ctx.moveTo(p0[0], p0[1]); ctx.lineTo(p1[0], p1[1]); ctx.stroke();
        }
      }
      if (P0 && P) {
        const rb = applyT(P0.R, sub3(h.anchor, P0.x));
        const pin = project(cam, add3(P.x, apply(P.R, rb)));
        if (a && pin) {
          ctx.strokeStyle = "#000"; ctx.lineWidth = 1;
          ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(pin[0], pin[1]); ctx.stroke();
        }
      }
      if (a) {
        ctx.fillStyle = "#000";
        ctx.beginPath(); ctx.moveTo(a[0], a[1] - 6); ctx.lineTo(a[0] + 6, a[1]); ctx.lineTo(a[0], a[1] + 6);
        ctx.lineTo(a[0] - 6, a[1]); ctx.closePath(); ctx.fill();
      }
    });
    // Contacts, axes, centres of mass: on top.
    const drawn = [];
    for (let i = 0; i < N; i++) {
      const P = poses[i];
      if (!P) { drawn.push(null); continue; }
      if (SCENE && S.contacts && SCENE.planes.length && SCENE.shapes[i].shape !== "unknown") {
        ctx.fillStyle = COLORS.pick;
        contactPoints(i, P).forEach(function (p) {
          const q = project(cam, p);
          if (q) { ctx.beginPath(); ctx.arc(q[0], q[1], 3.5, 0, 2 * Math.PI); ctx.fill(); }
        });
      }
      const c = project(cam, P.x);
      drawn.push(c);
      if (!c) continue;
      const L = 0.5 * shapeSize(i) + 0.15 * shapeSize(i);
      for (let d = 0; d < 3; d++) {
        const e = [0, 0, 0]; e[d] = L;
        const q = project(cam, add3(P.x, apply(P.R, e)));
        if (!q) continue;
        ctx.strokeStyle = AXIS_COLORS[d]; ctx.lineWidth = 2;
        ctx.beginPath(); ctx.moveTo(c[0], c[1]); ctx.lineTo(q[0], q[1]); ctx.stroke();
      }
      ctx.fillStyle = COLORS.com;
      ctx.beginPath(); ctx.arc(c[0], c[1], 3.5, 0, 2 * Math.PI); ctx.fill();
      if (S.pick === i) {
        ctx.strokeStyle = COLORS.pick; ctx.lineWidth = 2;
        ctx.beginPath(); ctx.arc(c[0], c[1], 9, 0, 2 * Math.PI); ctx.stroke();
        ctx.fillStyle = COLORS.pick; ctx.font = "12px sans-serif"; ctx.fillText("#" + i, c[0] + 11, c[1] - 9);
      }
    }
    S.lastDrawn = { frame: k, frame2: k2, screen: drawn };
  }
  function drawSphere(cam, it) {
    const r = cam.F * it.r / it.c[2];
    const lp = [it.c[0] - 0.35 * r, it.c[1] - 0.35 * r];
    const g = ctx.createRadialGradient(lp[0], lp[1], r * 0.1, it.c[0], it.c[1], r);
    g.addColorStop(0, it.col); g.addColorStop(1, shade(it.col, 0.45));
    ctx.fillStyle = g;
    ctx.beginPath(); ctx.arc(it.c[0], it.c[1], r, 0, 2 * Math.PI); ctx.fill();
    ctx.strokeStyle = "rgba(0,0,0,0.45)"; ctx.lineWidth = 1; ctx.stroke();
    // Three great circles of the body frame, front halves only: the spin shows.
    for (let d = 0; d < 3; d++) {
      ctx.strokeStyle = AXIS_COLORS[d]; ctx.globalAlpha = 0.7; ctx.lineWidth = 1.2;
      ctx.beginPath();
      let started = false;
      for (let k = 0; k <= 48; k++) {
        const a = 2 * Math.PI * k / 48;
        const p = [0, 0, 0];
        p[(d + 1) % 3] = it.r * Math.cos(a); p[(d + 2) % 3] = it.r * Math.sin(a);
        const w = add3(it.P.x, apply(it.P.R, p));
        const front = dot3(sub3(w, it.P.x), sub3(cam.eye, it.P.x)) > 0;
        const q = project(cam, w);
        if (!front || !q) { started = false; continue; }
        if (!started) { ctx.moveTo(q[0], q[1]); started = true; } else ctx.lineTo(q[0], q[1]);
      }
      ctx.stroke(); ctx.globalAlpha = 1;
    }
  }

  // ---------------------------------------------------------------- charts
  const charts = [];
  function Chart(title, series, opts) {
    const box = document.createElement("div");
    box.className = "chart";
    box.innerHTML = '<div class="head"><b></b><label title="a log scale of |value|: a blow-up and '
      + 'tiny errors both show"><input type="checkbox"> log |y|</label></div>'
      + '<div class="vals"></div><canvas></canvas>';
    el("charts").appendChild(box);
    this.box = box; this.title = title; this.series = series; this.opts = opts || {};
    this.canvas = box.querySelector("canvas"); this.ctx = this.canvas.getContext("2d");
    box.querySelector("b").textContent = title;
    this.log = !!this.opts.log;
    const box_ = box.querySelector("input");
    const self = this;
    box_.checked = this.log;
    box_.addEventListener("change", function () { self.log = box_.checked; self.paint(); });
    this.canvas.addEventListener("click", function (ev) {
      const r = self.canvas.getBoundingClientRect();
      seekT(self.tOf(ev.clientX - r.left));
    });
    this.canvas.addEventListener("mousemove", function (ev) {
      const r = self.canvas.getBoundingClientRect();
      self.hoverT = self.tOf(ev.clientX - r.left); self.draw();
    });
    this.canvas.addEventListener("mouseleave", function () { self.hoverT = null; self.shownAt = null; self.draw(); });
    charts.push(this);
  }
  Chart.prototype.resize = function () {
    const r = this.canvas.getBoundingClientRect();
    this.w = Math.max(50, r.width); this.h = Math.max(40, r.height);
    this.canvas.width = Math.round(this.w * DPR); this.canvas.height = Math.round(this.h * DPR);
    this.painted = false;
  };
  Chart.prototype.margins = { l: 58, r: 8, t: 6, b: 20 };
  Chart.prototype.tRange = function () { return TRANGE; };
  Chart.prototype.px = function (t) {
    const m = this.margins, tr = TRANGE;
    return m.l + (t - tr[0]) / (tr[1] - tr[0] || 1) * (this.w - m.l - m.r);
  };
  Chart.prototype.tOf = function (px) {
    const m = this.margins, tr = TRANGE;
    return tr[0] + (px - m.l) / (this.w - m.l - m.r) * (tr[1] - tr[0]);
  };
  Chart.prototype.tr = function (v) { return this.log ? (v === null || v === 0 ? null : Math.log10(Math.abs(v))) : v; };
  // The curves, axes and divergence marks are painted once (again on resize or a change of
  // scale); the playhead and the mouse are lines over the canvas, moved at every frame, so
  // that playing repaints no chart.
  Chart.prototype.paint = function () {
    if (!this.w) this.resize();
    this.painted = true;
    const c = this.ctx, m = this.margins, w = this.w, h = this.h, self = this;
    c.setTransform(DPR, 0, 0, DPR, 0, 0);
    c.fillStyle = "#fff"; c.fillRect(0, 0, w, h);
    let lo = Infinity, hi = -Infinity;
    this.series.forEach(function (s) {
      s.v.forEach(function (v) {
        const y = self.tr(v);
        if (y !== null && isFinite(y)) { lo = Math.min(lo, y); hi = Math.max(hi, y); }
      });
    });
    const drawable = isFinite(lo);
    if (!drawable) { lo = 0; hi = 1; }
    if (hi - lo < 1e-12 * Math.max(Math.abs(hi), 1e-300)) {
      const d = Math.max(Math.abs(hi) * 1e-6, 1e-12); lo -= d; hi += d;
    }
    const pad = 0.06 * (hi - lo); lo -= pad; hi += pad;
    this.yr = [lo, hi];
    const Y = function (y) { return m.t + (hi - y) / (hi - lo) * (h - m.t - m.b); };
    c.strokeStyle = "#e6e6e6"; c.fillStyle = "#666"; c.font = "10px sans-serif"; c.lineWidth = 1;
    // Log scale: whole decades when the curve spans one or more, else plain values.
    const decades = this.log && hi - lo >= 1;
    const ys = decades ? Math.max(1, Math.round(niceStep(hi - lo, 4))) : niceStep(hi - lo, 4);
    c.beginPath();
    for (let y = Math.ceil(lo / ys) * ys; y <= hi; y += ys) {
      c.moveTo(m.l, Math.round(Y(y)) + 0.5); c.lineTo(w - m.r, Math.round(Y(y)) + 0.5);
      c.fillText(decades ? "1e" + Math.round(y) : this.log ? fmt(Math.pow(10, y), 3) : gridLabel(y, ys), 2, Y(y) + 3);
    }
    const tr = TRANGE, ts = niceStep(tr[1] - tr[0], 5);
    for (let t = Math.ceil(tr[0] / ts) * ts; t <= tr[1] + 1e-12; t += ts) {
      c.moveTo(Math.round(this.px(t)) + 0.5, m.t); c.lineTo(Math.round(this.px(t)) + 0.5, h - m.b);
      if (this.px(t) < w - m.r - 40) c.fillText(gridLabel(t, ts), this.px(t) - 6, h - 5);
    }
    c.stroke();
    c.fillText("t (s)", w - m.r - 24, h - 5);
    if (!drawable) {
      c.fillStyle = "#444"; c.font = "12px sans-serif";
      c.fillText(this.opts.empty || "no finite value to draw", m.l + 10, m.t + 40);
    }
    c.strokeStyle = "#bbb"; c.strokeRect(m.l + 0.5, m.t + 0.5, w - m.l - m.r - 1, h - m.t - m.b - 1);
    c.save(); c.beginPath(); c.rect(m.l, m.t, w - m.l - m.r, h - m.t - m.b); c.clip();
    // Totals (E) last, on top: a total equal to one of its parts stays visible.
    this.series.filter(function (s) { return !s.top; }).concat(this.series.filter(function (s) { return s.top; })).forEach(function (s) {
      c.strokeStyle = s.color; c.lineWidth = s.width || 1.4; c.setLineDash(s.dash || []);
      c.beginPath();
      let started = false;
      for (let j = 0; j < s.t.length; j++) {
        const y = self.tr(s.v[j]);
        if (y === null || !isFinite(y)) { started = false; continue; }
        const X = self.px(s.t[j]), YY = Y(y);
        if (!started) { c.moveTo(X, YY); started = true; } else c.lineTo(X, YY);
      }
      c.stroke(); c.setLineDash([]);
    });
    // The divergence of each run that diverged, where its summary says.
    this.marks = [];
    RUNS.forEach(function (r) {
      if (!r.diverged || r.diverged.t === null) return;
      const X = Math.round(self.px(r.diverged.t)) + 0.5;
      c.strokeStyle = COLORS.diverged; c.lineWidth = 1.5; c.setLineDash([4, 3]);
      c.beginPath(); c.moveTo(X, m.t); c.lineTo(X, h - m.b); c.stroke(); c.setLineDash([]);
      c.fillStyle = COLORS.diverged; c.font = "10px sans-serif";
      c.fillText("diverged, step " + r.diverged.step, Math.max(m.l + 2, X - 100), m.t + 10);
      self.marks.push({ t: r.diverged.t, step: r.diverged.step, px: X - 0.5 });
    });
    c.restore();
  };
  Chart.prototype.line = function (cls, color) {
    const d = document.createElement("div");
    d.className = cls;
    d.style.background = color;
    this.box.appendChild(d);
    return d;
  };
  Chart.prototype.place = function (div, t) {
    if (t === null || t === undefined) { div.style.display = "none"; return null; }
    const m = this.margins, X = Math.round(this.px(t));
    div.style.display = "block";
    div.style.left = (this.canvas.offsetLeft + X) + "px";
    div.style.top = (this.canvas.offsetTop + m.t) + "px";
    div.style.height = (this.h - m.t - m.b) + "px";
    return X;
  };
  Chart.prototype.draw = function () {
    if (!this.painted) this.paint();
    if (!this.cursorDiv) {
      this.cursorDiv = this.line("cursor", COLORS.cursor);
      this.hoverDiv = this.line("hover", "rgba(0,0,0,0.3)");
    }
    const tc = R1.t[S.frame];
    this.cursor = { t: tc, px: this.place(this.cursorDiv, tc) };
    this.place(this.hoverDiv, this.hoverT);
    // Values at the playhead (or under the mouse).
    const at = this.hoverT !== null && this.hoverT !== undefined ? this.hoverT : tc;
    if (at === this.shownAt) return;
    this.shownAt = at;
    const vals = this.series.filter(function (s) { return !s.quiet; }).map(function (s) {
      const j = nearestBefore(s.t, at);
      return '<span style="color:' + s.color + '">' + esc(s.name) + " " + esc(j < 0 ? "—" : fmt(s.v[j], 6)) + "</span>";
    });
    this.box.querySelector(".vals").innerHTML = vals.join(" ");
  };
  function nearestBefore(ts, t) {
    let lo = 0, hi = ts.length - 1;
    if (!ts.length || t < ts[0] - 1e-12 * Math.abs(ts[0] || 1)) return -1;
    const tol = 1e-9 * Math.max(Math.abs(ts[hi]), 1e-300);
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (ts[mid] <= t + tol) lo = mid; else hi = mid - 1; }
    return lo;
  }

  let TRANGE = [R1.t[0], R1.t[R1.frames - 1]];
  function makeCharts() {
    RUNS.forEach(function (r) {
      TRANGE[0] = Math.min(TRANGE[0], r.t[0]); TRANGE[1] = Math.max(TRANGE[1], r.t[r.frames - 1]);
    });
    if (TRANGE[1] <= TRANGE[0]) TRANGE[1] = TRANGE[0] + 1;
    // A little room after the last step: a run that diverged ends there, and its mark must
    // not fall on the frame's edge.
    TRANGE[1] += 0.02 * (TRANGE[1] - TRANGE[0]);
    const anyDiv = RUNS.some(function (r) { return r.diverged; });
    const dash = [6, 3];
    const E = [], P = [], L = [];
    RUNS.forEach(function (r, ri) {
      const s = r.stats;
      if (!s) return;
      const suffix = ri ? " (" + r.label + ")" : "";
      const d = ri ? dash : null;
      E.push({ name: "E" + suffix, color: ri ? COLORS.run2 : "#111", t: s.t, v: s.energy, dash: d, width: 1.8, top: true });
      if (!ri) {
        E.push({ name: "K", color: "#d62728", t: s.t, v: s.kinetic });
        E.push({ name: "U", color: "#1f77b4", t: s.t, v: s.potential });
      }
      const pc = RIGID ? [["px", "#d62728"], ["py", "#2ca02c"], ["pz", "#1f77b4"]] : [["px", "#d62728"], ["py", "#2ca02c"]];
      pc.forEach(function (p) { P.push({ name: p[0] + suffix, color: ri ? shadeAlt(p[1]) : p[1], t: s.t, v: s[p[0]], dash: d }); });
      if (RIGID) [["Lx", "#d62728"], ["Ly", "#2ca02c"], ["Lz", "#1f77b4"]].forEach(function (p) {
        L.push({ name: p[0] + suffix, color: ri ? shadeAlt(p[1]) : p[1], t: s.t, v: s[p[0]], dash: d });
      });
    });
    if (E.length) new Chart("Energy (J)", E, { log: anyDiv, id: "energy" });
    if (P.length) new Chart("Momentum (kg m/s)", P, { log: anyDiv, id: "momentum" });
    if (L.length) new Chart("Angular momentum about the origin (kg m²/s)", L, { log: anyDiv, id: "angular" });
    if (META.exact) new Chart("Distance from the exact motion (m), largest over particles",
      [{ name: "|x − exact|", color: "#111", t: META.exact.distance.t, v: META.exact.distance.v }],
      { log: true, id: "exact" });
    if (META.difference) {
      const D = [{ name: "|x₁ − x₂|", color: COLORS.run2, t: META.difference.t, v: META.difference.v }];
      if (META.difference.angle) D.push({ name: "angle (rad)", color: "#7b3294", t: META.difference.t, v: META.difference.angle });
      new Chart("Difference between the runs, largest over " + (RIGID ? "bodies" : "particles"), D,
        { log: true, id: "difference", empty: META.difference.identical
          ? "0 at every written step: the two runs coincide" : "no written time in common" });
    }
    if (!charts.length) el("charts").innerHTML = '<p class="muted">No curves: give the run\'s --stats file.</p>';
  }
  function shadeAlt(hex) { return hex === "#d62728" ? "#ff9896" : hex === "#2ca02c" ? "#98df8a" : "#aec7e8"; }

  // ---------------------------------------------------------------- budget and inspector
  function budget() {
    const b = META.budget, box = el("budget");
    if (!b.available) { box.innerHTML = '<p class="muted">Not available: ' + esc(b.why) + ".</p>"; return; }
    const pct = 100 * b.share;
    box.innerHTML = "<p>The step loop took <b>" + esc(fmt(b.ms_per_frame, 3)) + " ms</b> of CPU per "
      + "simulated 1/60 s (" + esc(fmt(b.steps_per_frame, 3)) + " steps of dt), "
      + "<b>" + esc(fmt(pct, 3)) + " %</b> of a 16.7 ms frame at 60 Hz.</p>"
      + '<div class="bar"><div class="' + (b.share > 1 ? "over" : "") + '" style="width:'
      + Math.min(100, pct).toFixed(2) + '%"></div></div>'
      + "<p>At this cost one frame holds about <b>" + esc(b.fit === null ? "—" : b.fit.toLocaleString("en"))
      + "</b> " + esc(b.what) + " (this run: " + esc(b.n) + "; cost taken to grow as " + esc(b.scaling) + ").</p>"
      + '<p class="muted">From the summary: cpu_s = ' + esc(fmt(b.cpu_s, 4)) + " s over t = " + esc(fmt(b.t, 6))
      + " s (" + esc(b.steps) + " steps). cpu_s includes writing the trace: a run without --out (or with a "
      + "larger --every) times the step loop alone.</p>"
      + (R2 && Object.keys(R2.summary).length ? '<p class="muted">' + esc(R2.label) + ": "
        + esc(fmt(R2.summary.cpu_s * 1000 / (R2.summary.t * 60), 3)) + " ms per simulated 1/60 s.</p>" : "");
  }
  function inspect() {
    const box = el("inspect");
    if (S.pick === null) return;
    const k = S.frame, i = S.pick;
    const rows = [];
    const k2 = R2 ? frameAt(R2, R1.t[k]) : null;
    if (RIGID) {
      const names = ["x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz"];
      for (let g = 0; g < 13; g += g < 3 ? 3 : g < 7 ? 4 : 3) {
        const n = g < 3 ? 3 : g < 7 ? 4 : 3;
        const vals = [];
        for (let d = g; d < g + n; d++) vals.push(fmt(value(R1, k, i, d), 7));
        let extra = "";
        if (k2 !== null) { const v2 = []; for (let d = g; d < g + n; d++) v2.push(fmt(value(R2, k2, i, d), 7)); extra = "<td>" + v2.join(", ") + "</td>"; }
        rows.push("<tr><td>" + names.slice(g, g + n).join(",") + "</td><td>" + vals.join(", ") + "</td>" + extra + "</tr>");
      }
    } else {
      const x = value(R1, k, i, 0), y = value(R1, k, i, 1);
      rows.push("<tr><td>x, y</td><td>" + fmt(x, 7) + ", " + fmt(y, 7) + "</td></tr>");
      if (SCENE) rows.push("<tr><td>radius</td><td>" + fmt(SCENE.radii[i], 6) + "</td></tr>");
      if (k2 !== null) {
        const x2 = value(R2, k2, i, 0), y2 = value(R2, k2, i, 1);
        rows.push("<tr><td>" + esc(R2.label) + "</td><td>" + fmt(x2, 7) + ", " + fmt(y2, 7) + " (t = " + fmtT(R2.t[k2]) + ")</td></tr>");
        rows.push("<tr><td>distance</td><td>" + fmt(Math.hypot(x - x2, y - y2), 4) + " m</td></tr>");
      }
      if (EXACT) {
        const ex = EXACT.pos[(k * N + i) * 2] + ORIGIN[0], ey = EXACT.pos[(k * N + i) * 2 + 1] + ORIGIN[1];
        rows.push("<tr><td>exact</td><td>" + fmt(ex, 7) + ", " + fmt(ey, 7) + "</td></tr>");
        rows.push("<tr><td>error</td><td>" + fmt(Math.hypot(x - ex, y - ey), 4) + " m</td></tr>");
      }
    }
    box.innerHTML = "<p><b>" + (RIGID ? "Body " : "Particle ") + i + "</b> at t = " + fmtT(R1.t[k])
      + ' <button id="b-unpick">drop</button></p><table>' + rows.join("") + "</table>"
      + '<p class="muted">Values stored as 32-bit floats (7 digits); the CSV has all 17.</p>';
    el("b-unpick").addEventListener("click", function () { S.pick = null; S.dirty = true; el("inspect").innerHTML = ""; });
  }

  // ---------------------------------------------------------------- playhead
  const scrub = el("scrub");
  function stepOf(run, k) { return run.steps ? run.steps[k] : null; }
  function hud() {
    const k = S.frame;
    let s = "t = " + fmtT(R1.t[k]) + " s";
    const st = stepOf(R1, k);
    if (st !== null) {
      const last = R1.summary.steps !== undefined ? R1.summary.steps : stepOf(R1, R1.frames - 1);
      s += "   step " + st + " of " + last;
    }
    s += "   frame " + (k + 1) + "/" + R1.frames;
    if (R1.diverged && k === R1.frames - 1) s += "   DIVERGED here";
    if (R2 && S.run2) {
      const k2 = frameAt(R2, R1.t[k]);
      s += "   │ " + R2.label + ": t = " + fmtT(R2.t[k2]) + (R2.steps ? ", step " + R2.steps[k2] : "");
      if (R2.diverged && k2 === R2.frames - 1 && R1.t[k] >= R2.t[k2]) s += " (ended: diverged)";
    }
    s += S.playing ? "   ▶ " + (S.everyFrame ? "every written step" : "×" + fmt(S.speed, 3)) : "";
    el("hud").textContent = s;
  }
  function setFrame(k) {
    k = Math.max(0, Math.min(R1.frames - 1, k | 0));
    if (k !== S.frame) S.dirty = true;
    S.frame = k; S.playT = R1.t[k];
    scrub.value = k;
  }
  function seekT(t) { setFrame(frameAt(R1, t)); S.dirty = true; }
  function gotoStep(step) {
    if (!R1.steps) return;
    let best = 0;
    for (let k = 0; k < R1.frames; k++) if (Math.abs(R1.steps[k] - step) < Math.abs(R1.steps[best] - step)) best = k;
    setFrame(best);
  }
  function drawTicks() {
    const c = el("ticks"), g = c.getContext("2d");
    const r = c.getBoundingClientRect();
    c.width = Math.round(r.width * DPR); c.height = Math.round(r.height * DPR);
    g.setTransform(DPR, 0, 0, DPR, 0, 0); g.clearRect(0, 0, r.width, r.height);
    RUNS.forEach(function (run) {
      if (!run.diverged || run.diverged.t === null) return;
      const x = 8 + (run.diverged.t - R1.t[0]) / (R1.t[R1.frames - 1] - R1.t[0] || 1) * (r.width - 16);
      g.fillStyle = COLORS.diverged; g.fillRect(Math.min(r.width - 3, x - 1.5), 0, 3, r.height);
    });
  }

  // ---------------------------------------------------------------- speed
  const SPEEDS = [0.01, 0.03, 0.1, 0.25, 0.5, 1, 2, 4, 10, 30, 100, 300, 1000];
  function defaultSpeed() {  // real time when the run lasts 2 to 30 s, else about 10 s of playback
    const span = R1.t[R1.frames - 1] - R1.t[0];
    if (span >= 2 && span <= 30) return 1;
    return span > 0 ? span / 10 : 1;
  }
  function speedMenu() {
    const sel = el("speed");
    const auto = defaultSpeed();
    const opts = SPEEDS.slice();
    if (opts.indexOf(auto) < 0) opts.push(auto);
    opts.sort(function (a, b) { return a - b; });
    sel.innerHTML = opts.map(function (v) {
      return '<option value="' + v + '"' + (v === auto ? " selected" : "") + ">×" + fmt(v, 3)
        + (v === auto && v !== 1 ? " (whole run in 10 s)" : v === 1 ? " (real time)" : "") + "</option>";
    }).join("") + '<option value="frame">every written step</option>';
    S.speed = auto;
    sel.addEventListener("change", function () {
      S.everyFrame = sel.value === "frame";
      if (!S.everyFrame) S.speed = +sel.value;
      S.lastTick = null;
    });
  }
  function bumpSpeed(dir) {
    const sel = el("speed");
    sel.selectedIndex = Math.max(0, Math.min(sel.options.length - 1, sel.selectedIndex + dir));
    sel.dispatchEvent(new Event("change"));
  }

  // ---------------------------------------------------------------- loop
  const ICON_PLAY = '<svg width="14" height="14" viewBox="0 0 14 14" aria-hidden="true">'
    + '<path d="M3 2v10l9-5z" fill="currentColor"/></svg>';
  const ICON_PAUSE = '<svg width="14" height="14" viewBox="0 0 14 14" aria-hidden="true">'
    + '<path d="M3 2h3v10H3zM8 2h3v10H8z" fill="currentColor"/></svg>';
  function play(on) {
    S.playing = on === undefined ? !S.playing : on;
    if (S.playing && S.frame === R1.frames - 1) setFrame(0);
    S.lastTick = null;
    el("b-play").innerHTML = S.playing ? ICON_PAUSE : ICON_PLAY;
    S.dirty = true;
  }
  function tick(now) {
    if (S.playing) {
      if (S.everyFrame) {
        if (S.frame >= R1.frames - 1) play(false); else setFrame(S.frame + 1);
      } else if (S.lastTick !== null) {
        S.playT += (now - S.lastTick) / 1000 * S.speed;
        const k = frameAt(R1, S.playT);
        if (k !== S.frame) { S.frame = k; scrub.value = k; S.dirty = true; }
        if (S.playT >= R1.t[R1.frames - 1]) play(false);
      }
      S.lastTick = now;
    }
    if (S.dirty) render();
    requestAnimationFrame(tick);
  }
  function render() {
    const t0 = performance.now();
    if (RIGID) draw3(); else draw2();
    charts.forEach(function (c) { c.draw(); });
    hud();
    if (S.pick !== null) inspect();
    S.dirty = false;
    const ms = performance.now() - t0;
    S.drawMs.push(ms); if (S.drawMs.length > 600) S.drawMs.shift();
    if (S.flush) ctx.getImageData(0, 0, 1, 1);  // benchmark: raster every frame now
    S.draws++;
    if (!S.ready) { S.ready = true; S.loadMs = performance.now(); }
  }

  // ---------------------------------------------------------------- input
  function wire() {
    el("b-play").addEventListener("click", function () { play(); });
    el("b-start").addEventListener("click", function () { setFrame(0); });
    el("b-end").addEventListener("click", function () { setFrame(R1.frames - 1); });
    el("b-back").addEventListener("click", function () { play(false); setFrame(S.frame - 1); });
    el("b-fwd").addEventListener("click", function () { play(false); setFrame(S.frame + 1); });
    el("b-fit").addEventListener("click", function () { if (RIGID) fit3(false); else fit2(false); });
    scrub.max = R1.frames - 1;
    scrub.addEventListener("input", function () { setFrame(+scrub.value); });
    [["c-trails", "trails"], ["c-exact", "exact"], ["c-run2", "run2"], ["c-springs", "springs"],
      ["c-contacts", "contacts"], ["c-follow", "follow"]].forEach(function (p) {
      const box = el(p[0]);
      S[p[1]] = box.checked;
      box.addEventListener("change", function () {
        S[p[1]] = box.checked; S.dirty = true;
        if (p[1] === "follow" && !box.checked) { if (RIGID) fit3(false); else fit2(false); }
      });
    });
    el("gostep").addEventListener("change", function () { gotoStep(+el("gostep").value); });
    window.addEventListener("keydown", function (ev) {
      if (ev.target.tagName === "INPUT" && ev.target.type !== "range" && ev.target.type !== "checkbox") return;
      const k = ev.key;
      if (k === " ") { play(); ev.preventDefault(); }
      else if (k === "ArrowRight") { play(false); setFrame(S.frame + (ev.shiftKey ? 10 : 1)); ev.preventDefault(); }
      else if (k === "ArrowLeft") { play(false); setFrame(S.frame - (ev.shiftKey ? 10 : 1)); ev.preventDefault(); }
      else if (k === "Home") setFrame(0);
      else if (k === "End") setFrame(R1.frames - 1);
      else if (k === "[") bumpSpeed(-1);
      else if (k === "]") bumpSpeed(1);
      else if (k === "f" || k === "F") { if (RIGID) fit3(false); else fit2(false); }
    });
    // Camera: drag, wheel; a click without a drag picks.
    let drag = null;
    canvas.addEventListener("contextmenu", function (ev) { ev.preventDefault(); });
    canvas.addEventListener("pointerdown", function (ev) {
      drag = { x: ev.clientX, y: ev.clientY, moved: false, pan: ev.shiftKey || ev.button === 2 };
      canvas.setPointerCapture(ev.pointerId);
    });
    canvas.addEventListener("pointermove", function (ev) {
      if (!drag) return;
      const dx = ev.clientX - drag.x, dy = ev.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 2) drag.moved = true;
      drag.x = ev.clientX; drag.y = ev.clientY;
      if (!drag.moved) return;
      if (RIGID) {
        if (drag.pan) {
          const cam = camera(), s = S.cam.dist / cam.F;
          S.cam.target = add3(S.cam.target, add3(mul3(cam.r, -dx * s), mul3(cam.u, dy * s)));
        } else {
          S.cam.yaw -= dx * 0.01;
          S.cam.pitch = Math.max(-1.5, Math.min(1.5, S.cam.pitch + dy * 0.01));
        }
      } else {
        S.view2.cx -= dx / S.view2.s; S.view2.cy += dy / S.view2.s;
      }
      S.follow = false; el("c-follow").checked = false;
      S.dirty = true;
    });
    canvas.addEventListener("pointerup", function (ev) {
      if (drag && !drag.moved) pickAt(ev);
      drag = null;
    });
    canvas.addEventListener("wheel", function (ev) {
      ev.preventDefault();
      const f = Math.exp(-ev.deltaY * 0.0015);
      if (RIGID) { S.cam.dist /= f; }
      else {
        const r = canvas.getBoundingClientRect();
        const mx = ev.clientX - r.left, my = ev.clientY - r.top;
        const wx = S.view2.cx + (mx - W / 2) / S.view2.s, wy = S.view2.cy - (my - H / 2) / S.view2.s;
        S.view2.s *= f;
        S.view2.cx = wx - (mx - W / 2) / S.view2.s; S.view2.cy = wy + (my - H / 2) / S.view2.s;
      }
      S.dirty = true;
    }, { passive: false });
    window.addEventListener("resize", function () { resize(); drawTicks(); });
  }
  function pickAt(ev) {
    const r = canvas.getBoundingClientRect();
    const mx = ev.clientX - r.left, my = ev.clientY - r.top;
    let best = null, bd = RIGID ? 30 : 12;
    for (let i = 0; i < N; i++) {
      let p;
      if (RIGID) p = S.lastDrawn && S.lastDrawn.screen ? S.lastDrawn.screen[i] : null;
      else { const x = value(R1, S.frame, i, 0), y = value(R1, S.frame, i, 1); p = isFinite(x + y) ? [sx(x), sy(y)] : null; }
      if (!p) continue;
      const d = Math.hypot(p[0] - mx, p[1] - my) - (RIGID ? 0 : radiusPx(i));
      if (d < bd) { bd = d; best = i; }
    }
    S.pick = best; S.dirty = true;
    if (best === null) el("inspect").innerHTML = '<p class="muted">Click a particle or body to follow its numbers.</p>';
  }

  // ---------------------------------------------------------------- test hooks
  // What the browser test (tools/view-check) reads back: what was drawn, and where.
  window.wbView = {
    get ready() { return S.ready; },
    loadMs: function () { return S.loadMs; },
    seek: function (k) { play(false); setFrame(k); render(); return S.frame; },
    state: function () {
      return { frame: S.frame, frames: R1.frames, t: R1.t[S.frame], step: stepOf(R1, S.frame),
        playing: S.playing, draws: S.draws, n: N, kind: META.kind };
    },
    // Positions drawn at the current frame: world coordinates (as stored) and CSS pixels.
    drawn: function (ids) {
      const k = S.lastDrawn.frame;
      const cam = RIGID ? camera() : null;
      const r = canvas.getBoundingClientRect();
      return ids.map(function (i) {
        const p = RIGID ? [value(R1, k, i, 0), value(R1, k, i, 1), value(R1, k, i, 2)]
          : [value(R1, k, i, 0), value(R1, k, i, 1)];
        const s = RIGID ? (S.lastDrawn.screen[i] ? S.lastDrawn.screen[i].slice(0, 2) : null) : [sx(p[0]), sy(p[1])];
        const q = RIGID ? [value(R1, k, i, 3), value(R1, k, i, 4), value(R1, k, i, 5), value(R1, k, i, 6)] : null;
        return { id: i, world: p, q: q, screen: s ? [s[0] + r.left, s[1] + r.top] : null,
          radius_px: RIGID ? 3.5 : radiusPx(i) };
      });
    },
    // Switches (exact, run2, trails, springs, contacts, pick, legend) for the pixel checks:
    // with the overlays off, a particle's centre pixel is its run's colour.
    set: function (o) {
      ["exact", "run2", "trails", "springs", "contacts"].forEach(function (k) {
        if (k in o) { S[k] = !!o[k]; const b = el("c-" + k); if (b) b.checked = S[k]; }
      });
      if ("pick" in o) S.pick = o.pick;
      if ("legend" in o) el("legend").style.display = o.legend ? "" : "none";
      S.dirty = true; render();
    },
    // The mapping from world to page pixels of the last drawing.
    view: function () {
      const r = canvas.getBoundingClientRect();
      if (!RIGID) return { kind: "2d", cx: S.view2.cx, cy: S.view2.cy, s: S.view2.s, left: r.left, top: r.top, W: W, H: H };
      const c = camera();
      return { kind: "3d", eye: c.eye, r: c.r, u: c.u, f: c.f, F: c.F, left: r.left, top: r.top, W: W, H: H };
    },
    colors: function () { return { run: COLORS.run, com: COLORS.com, cursor: COLORS.cursor, diverged: COLORS.diverged }; },
    charts: function () {
      return charts.map(function (c) {
        const r = c.canvas.getBoundingClientRect();
        return { id: c.opts.id, title: c.title, cursor: c.cursor ? { t: c.cursor.t, px: c.cursor.px + r.left } : null,
          marks: (c.marks || []).map(function (m) { return { t: m.t, step: m.step, px: m.px + r.left }; }),
          top: r.top + c.margins.t, bottom: r.bottom - c.margins.b,
          t_of_px: [c.tOf(c.margins.l), c.tOf(c.w - c.margins.r)], px_range: [c.margins.l + r.left, c.w - c.margins.r + r.left] };
      });
    },
    diverged: function () { return RUNS.map(function (r) { return r.diverged; }); },
    // Plays every written step for `seconds` and measures the frame rate and the draw time.
    benchmark: function (seconds) {
      return new Promise(function (resolve) {
        const sel = el("speed"); sel.value = "frame"; sel.dispatchEvent(new Event("change"));
        setFrame(0); play(true);
        const d0 = S.draws, t0 = performance.now();
        S.drawMs = []; S.flush = true;
        setTimeout(function () {
          const dt = (performance.now() - t0) / 1000, n = S.draws - d0;
          play(false); S.flush = false;
          const ms = S.drawMs.slice().sort(function (a, b) { return a - b; });
          resolve({ fps: n / dt, frames: n, seconds: dt,
            draw_ms_mean: ms.reduce(function (a, b) { return a + b; }, 0) / Math.max(ms.length, 1),
            draw_ms_p95: ms.length ? ms[Math.floor(ms.length * 0.95)] : null });
        }, seconds * 1000);
      });
    },
  };

  // ---------------------------------------------------------------- start
  el("b-play").innerHTML = ICON_PLAY;
  header();
  legend();
  speedMenu();
  makeCharts();
  budget();
  wire();
  resize();
  drawTicks();
  setFrame(0);
  render();
  requestAnimationFrame(tick);
  S.setupMs = performance.now() - T0;
})();
