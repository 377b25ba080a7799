// The live page, part 2 of 4: the particle labs' view in 2D. The scene's fixed parts
// come from the scene as the knobs have changed it (S.doc): planes, obstacles, the
// centres of attractors and vortices, the boids' goal (points the mouse can move);
// springs and pins from the page's model of the scene (tools/wbview/data.py).
const MANY = 1000;  // above this, particles are stamped into pixels (tools/view does too)

function radii() {  // every particle's radius (m), as the scene declares them
  if (S.radii && S.radii.doc === S.docText) return S.radii.r;
  const r = [];
  (S.doc.particles || []).forEach(function (p) { r.push(+p.radius || 0); });
  (S.doc.emitters || []).forEach(function (e) {
    for (let k = 0; k < (e.count | 0); k++) r.push(+e.radius || 0);
  });
  S.radii = { doc: S.docText, r: r };
  return r;
}
// Points of the scene the mouse can move, each with its path in the scene's JSON.
function marks() {
  const out = [];
  (S.doc.forces || []).forEach(function (f, k) {
    if (!f || typeof f !== "object") return;
    if (f.type === "attractor") {
      out.push({ at: f.center || [0, 0], label: "attractor", path: ["forces", k, "center"] });
    } else if (f.type === "vortex") {
      out.push({ at: f.center || [0, 0], label: "vortex", radius: f.core,
        path: ["forces", k, "center"] });
    } else if (f.type === "boids" && f.goal_weight) {
      out.push({ at: f.goal || [0, 0], label: "goal", path: ["forces", k, "goal"] });
    } else if (f.type === "curl-noise") {
      (f.obstacles || []).forEach(function (o, j) {
        out.push({ at: o.center, label: "obstacle", disc: o.radius,
          path: ["forces", k, "obstacles", j, "center"] });
      });
    }
  });
  return out;
}

function fit2(pane) {
  const p0 = S.panes[0];
  let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  const grow = function (x, y, r) {
    if (!isFinite(x + y)) return;
    lo[0] = Math.min(lo[0], x - r); hi[0] = Math.max(hi[0], x + r);
    lo[1] = Math.min(lo[1], y - r); hi[1] = Math.max(hi[1], y + r);
  };
  const rr = radii();
  const n = p0.n();
  for (let i = 0; i < n; i++) { const q = p0.pos(i); grow(q[0], q[1], rr[i] || 0); }
  marks().forEach(function (m) { grow(m.at[0], m.at[1], m.disc || 0); });
  S.scene.model.anchored.forEach(function (a) { grow(a[1], a[2], 0); });
  S.scene.model.planes.forEach(function (p) { grow(p.point[0], p.point[1], 0); });
  if (!isFinite(lo[0])) { lo = [-1, -1]; hi = [1, 1]; }
  S.fitBox = { lo: lo, hi: hi, size: Math.max(hi[0] - lo[0], hi[1] - lo[1], 1e-6) };
  S.userView = false;
  view2(lo, hi);
}
function view2(lo, hi) {  // both panes show the box lo..hi (with a margin)
  const span = Math.max(hi[0] - lo[0], hi[1] - lo[1], 1e-6);
  const pad = 0.12 * span;
  S.panes.forEach(function (p) {
    const s = Math.min(p.W / (hi[0] - lo[0] + 2 * pad), p.H / (hi[1] - lo[1] + 2 * pad));
    p.view = { cx: (lo[0] + hi[0]) / 2, cy: (lo[1] + hi[1]) / 2, s: s };
    p.bg = null;
  });
}
// The view grows to keep every particle in it (a swinging rope, a spiral, a splash), up to
// ten times the scene's first box: beyond that (a run blowing up) arrows at the edge say
// where the particles went.
function extend2() {
  const p0 = S.panes[0], f = S.fitBox;
  if (!p0.view || !f) return;
  const v = p0.view;
  const lo = [v.cx - p0.W / 2 / v.s, v.cy - p0.H / 2 / v.s];
  const hi = [v.cx + p0.W / 2 / v.s, v.cy + p0.H / 2 / v.s];
  const lim = [[f.lo[0] - 10 * f.size, f.lo[1] - 10 * f.size], [f.hi[0] + 10 * f.size, f.hi[1] + 10 * f.size]];
  let grow = false;
  const nlo = lo.slice(), nhi = hi.slice();
  S.panes.forEach(function (p) {
    if (p.kind === "none" || (p.idx === 1 && S.compare === "none")) return;
    const n = p.n();
    for (let i = 0; i < n; i++) {
      const q = p.pos(i);
      for (let d = 0; d < 2; d++) {
        if (!(q[d] >= lim[0][d] && q[d] <= lim[1][d])) continue;
        if (q[d] < nlo[d]) { nlo[d] = q[d]; grow = true; }
        if (q[d] > nhi[d]) { nhi[d] = q[d]; grow = true; }
      }
    }
  });
  if (grow) view2(nlo, nhi);
}
function sx(p, x) { return p.W / 2 + (x - p.view.cx) * p.view.s; }
function sy(p, y) { return p.H / 2 - (y - p.view.cy) * p.view.s; }
function world2(p, X, Y) { return [p.view.cx + (X - p.W / 2) / p.view.s, p.view.cy - (Y - p.H / 2) / p.view.s]; }

function drawFixed2(p) {  // grid, planes, obstacles, marks
  const ctx = p.ctx, v = p.view, W = p.W, H = p.H;
  ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, W, H);
  const step = niceStep(W / v.s, W / 110);
  ctx.lineWidth = 1; ctx.strokeStyle = "#eeeeee"; ctx.fillStyle = "#999";
  ctx.font = "11px sans-serif";
  ctx.beginPath();
  const x0 = world2(p, 0, H), x1 = world2(p, W, 0);
  for (let x = Math.ceil(x0[0] / step) * step; x <= x1[0]; x += step) {
    ctx.moveTo(Math.round(sx(p, x)) + 0.5, 0); ctx.lineTo(Math.round(sx(p, x)) + 0.5, H);
  }
  for (let y = Math.ceil(x0[1] / step) * step; y <= x1[1]; y += step) {
    ctx.moveTo(0, Math.round(sy(p, y)) + 0.5); ctx.lineTo(W, Math.round(sy(p, y)) + 0.5);
  }
  ctx.stroke();
  ctx.fillText(fmt(step, 3) + " m grid", 4, H - 4);
  const L = 4 * (W + H) / v.s;
  S.scene.model.planes.forEach(function (pl) {
    const n = pl.normal, t = [-n[1], n[0]], depth = pl.thickness || L;
    const a = [pl.point[0] - L * t[0], pl.point[1] - L * t[1]];
    const b = [pl.point[0] + L * t[0], pl.point[1] + L * t[1]];
    ctx.fillStyle = pl.thickness ? "rgba(127,106,60,0.45)" : "rgba(127,106,60,0.16)";
    ctx.beginPath();
    ctx.moveTo(sx(p, a[0]), sy(p, a[1])); ctx.lineTo(sx(p, b[0]), sy(p, b[1]));
    ctx.lineTo(sx(p, b[0] - depth * n[0]), sy(p, b[1] - depth * n[1]));
    ctx.lineTo(sx(p, a[0] - depth * n[0]), sy(p, a[1] - depth * n[1]));
    ctx.closePath(); ctx.fill();
    ctx.strokeStyle = "#7f6a3c"; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.moveTo(sx(p, a[0]), sy(p, a[1])); ctx.lineTo(sx(p, b[0]), sy(p, b[1]));
    ctx.stroke();
  });
  marks().forEach(function (m) {
    const x = sx(p, m.at[0]), y = sy(p, m.at[1]);
    if (m.disc) {
      ctx.fillStyle = "rgba(120,120,120,0.25)"; ctx.strokeStyle = "#888"; ctx.lineWidth = 1;
      ctx.beginPath(); ctx.arc(x, y, m.disc * v.s, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
    }
    drawMark(ctx, x, y, m.radius * v.s, m.label + " (drag)", 7);
  });
}

function radiusPx(p, r, n) { return Math.max(r * p.view.s, n > MANY ? 1.5 : n > 100 ? 2.5 : 4); }

function drawParticles2(p, color, hollow) {
  const ctx = p.ctx, n = p.n(), rr = radii();
  ctx.fillStyle = color; ctx.strokeStyle = color; ctx.lineWidth = 2;
  ctx.beginPath();
  for (let i = 0; i < n; i++) {
    const q = p.pos(i), X = sx(p, q[0]), Y = sy(p, q[1]), r = radiusPx(p, rr[i] || 0, n);
    if (!isFinite(X + Y) || X < -r || X > p.W + r || Y < -r || Y > p.H + r) continue;
    ctx.moveTo(X + r, Y); ctx.arc(X, Y, r, 0, 2 * Math.PI);
  }
  if (hollow) ctx.stroke(); else ctx.fill();
}
// Many particles: stamped into the pixels of a cached picture of the scene's fixed parts
// (a path of 10^4 discs takes tens of milliseconds to fill in a browser without a GPU, and
// reading the canvas back as many; stamping takes about one), as tools/view does.
function background2(p) {
  const key = [p.W, p.H, p.DPR, p.view.cx, p.view.cy, p.view.s, S.docText].join();
  if (p.bg && p.bg.key === key) return;
  p.ctx.setTransform(p.DPR, 0, 0, p.DPR, 0, 0);
  drawFixed2(p);
  const img = p.ctx.getImageData(0, 0, p.canvas.width, p.canvas.height);
  p.bg = { key: key, img: img, pixels: new Uint32Array(img.data.buffer.slice(0)) };
}
function stamp2(p, u, q, color, ring) {  // q's particles into pixels u (p's canvas)
  const cw = p.canvas.width, ch = p.canvas.height, n = q.n(), rr = radii();
  const col = rgba32(color);
  for (let i = 0; i < n; i++) {
    const x = q.pos(i);
    const X = Math.round(sx(p, x[0]) * p.DPR), Y = Math.round(sy(p, x[1]) * p.DPR);
    const Rr = Math.max(ring ? 2 : 1, Math.min(12, Math.round(radiusPx(p, rr[i] || 0, n) * p.DPR)));
    if (!isFinite(X + Y) || X < -Rr - 1 || Y < -Rr - 1 || X > cw + Rr || Y > ch + Rr) continue;
    const off = stampOffsets(Rr, ring);
    const inside = X > Rr + 1 && Y > Rr + 1 && X < cw - Rr - 2 && Y < ch - Rr - 2;
    for (let k = 0; k < off.length; k += 2) {
      const a = X + off[k], b = Y + off[k + 1];
      if (inside || (a >= 0 && b >= 0 && a < cw && b < ch)) u[b * cw + a] = col;
    }
  }
}
function drawMany2(p, o) {  // the fixed parts and p's particles (o's as rings), as pixels
  background2(p);
  const u = new Uint32Array(p.bg.img.data.buffer);
  u.set(p.bg.pixels);
  stamp2(p, u, p, COLORS[p.idx], false);
  if (o) stamp2(p, u, o, COLORS[1], true);
  p.ctx.putImageData(p.bg.img, 0, 0);
  p.ctx.setTransform(p.DPR, 0, 0, p.DPR, 0, 0);
}

function drawSprings2(p) {
  const ctx = p.ctx, m = S.scene.model, n = p.n();
  if (!m.springs.length && !m.anchored.length) return;
  ctx.strokeStyle = "#9a9a9a"; ctx.lineWidth = 1;
  ctx.beginPath();
  m.springs.forEach(function (s) {
    if (s[0] >= n || s[1] >= n) return;
    const a = p.pos(s[0]), b = p.pos(s[1]);
    if (!isFinite(a[0] + a[1] + b[0] + b[1])) return;
    ctx.moveTo(sx(p, a[0]), sy(p, a[1])); ctx.lineTo(sx(p, b[0]), sy(p, b[1]));
  });
  anchored().forEach(function (a) {
    if (a[0] >= n) return;
    const q = p.pos(a[0]);
    if (!isFinite(q[0] + q[1])) return;
    ctx.moveTo(sx(p, a[1]), sy(p, a[2])); ctx.lineTo(sx(p, q[0]), sy(p, q[1]));
  });
  ctx.stroke();
  ctx.fillStyle = "#555";
  anchored().forEach(function (a) { ctx.fillRect(sx(p, a[1]) - 3, sy(p, a[2]) - 3, 6, 6); });
}
function anchored() {  // springs to fixed points, from the scene as changed: [i, x, y]
  const out = [];
  (S.doc.forces || []).forEach(function (f) {
    if (f && f.type === "spring" && f.anchor && f.j === undefined) out.push([f.i, f.anchor[0], f.anchor[1]]);
  });
  return out;
}

function drawTrails2(p, color) {
  if (!S.trails || p.trail.length < 2) return;
  const ctx = p.ctx;
  ctx.strokeStyle = color; ctx.globalAlpha = 0.45; ctx.lineWidth = 1.5;
  ctx.beginPath();
  const ids = p.trail[0].ids;
  ids.forEach(function (id, j) {
    let started = false;
    p.trail.forEach(function (fr) {
      const X = sx(p, fr.xy[2 * j]), Y = sy(p, fr.xy[2 * j + 1]);
      if (!isFinite(X + Y)) { started = false; return; }
      if (!started) { ctx.moveTo(X, Y); started = true; } else ctx.lineTo(X, Y);
    });
  });
  ctx.stroke(); ctx.globalAlpha = 1;
}

// A particle outside the view is marked by a small arrow at the edge, pointing to it.
function drawOffView2(p, color) {
  const ctx = p.ctx, n = p.n();
  let shown = 0, out = 0;
  ctx.fillStyle = color;
  for (let i = 0; i < n; i++) {
    const q = p.pos(i), X = sx(p, q[0]), Y = sy(p, q[1]);
    if (X >= 0 && X <= p.W && Y >= 0 && Y <= p.H) continue;
    out++;
    if (shown >= 40 || !isFinite(X + Y)) continue;
    shown++;
    edgeArrow(ctx, p.W, p.H, X, Y);
  }
  p.offView = out;
}

function draw2(p) {
  if (!p.view) fit2(p);
  const ctx = p.ctx, color = COLORS[p.idx];
  // The solution's recorded run over the first run, as rings.
  const o = S.panes[1 - p.idx];
  const over = p.idx === 0 && o && o.kind === "trace" && S.overlay ? o : null;
  if (p.kind !== "none" && p.n() > MANY) drawMany2(p, over);
  else {
    ctx.setTransform(p.DPR, 0, 0, p.DPR, 0, 0);
    drawFixed2(p);
  }
  if (p.kind === "none") return;
  drawSprings2(p);
  drawTrails2(p, color);
  if (p.n() <= MANY) {
    drawParticles2(p, color, false);
    if (over) drawParticles2(over, COLORS[1], true);
  }
  ctx.fillStyle = "#222";
  S.scene.model.pinned.forEach(function (i) {
    if (i >= p.n()) return;
    const q = p.pos(i), X = sx(p, q[0]), Y = sy(p, q[1]);
    ctx.beginPath(); ctx.moveTo(X, Y - 9); ctx.lineTo(X - 6, Y - 18); ctx.lineTo(X + 6, Y - 18);
    ctx.closePath(); ctx.fill();
  });
  if (p.exact && p.exact.length) {
    ctx.strokeStyle = "#111"; ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (let i = 0; 2 * i < p.exact.length; i++) {
      const X = sx(p, p.exact[2 * i]), Y = sy(p, p.exact[2 * i + 1]);
      ctx.moveTo(X + 7, Y); ctx.arc(X, Y, 7, 0, 2 * Math.PI);
    }
    ctx.stroke();
  }
  if (S.grab && S.grab.pane === p.idx) {
    const q = p.pos(S.grab.item), X = sx(p, q[0]), Y = sy(p, q[1]);
    const T = [sx(p, S.grab.target[0]), sy(p, S.grab.target[1])];
    ctx.strokeStyle = "#d62728"; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.moveTo(X, Y); ctx.lineTo(T[0], T[1]); ctx.stroke();
    ctx.beginPath(); ctx.arc(X, Y, radiusPx(p, radii()[S.grab.item] || 0, p.n()) + 4, 0, 2 * Math.PI);
    ctx.stroke();
  }
  drawOffView2(p, color);
}

// What the mouse is over: a movable point of the scene first, then the nearest particle.
function pick2(p, X, Y) {
  const ms = marks();
  for (let k = 0; k < ms.length; k++) {
    if (Math.hypot(sx(p, ms[k].at[0]) - X, sy(p, ms[k].at[1]) - Y) < 10) return { mark: ms[k] };
  }
  let best = -1, bd = 14;
  const n = p.n(), rr = radii();
  for (let i = 0; i < n; i++) {
    const q = p.pos(i);
    const d = Math.hypot(sx(p, q[0]) - X, sy(p, q[1]) - Y) - radiusPx(p, rr[i] || 0, n);
    if (d < bd) { bd = d; best = i; }
  }
  return best >= 0 ? { item: best } : null;
}
