// tools/view's page, part 3 of 6: the particle labs' view, in 2D.
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
      for (let a = 0; a < 2; a++) {
        lo[a] = Math.min(lo[a], d.center[a] - d.radius);
        hi[a] = Math.max(hi[a], d.center[a] + d.radius);
      }
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
  const span = Math.max(hi[0] - lo[0], hi[1] - lo[1], 4 * rmax,
    1e-9 * Math.max(1, Math.abs(lo[0]), Math.abs(lo[1])));
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
  for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) {
    // None under the unit at the right end.
    const label = gridLabel(x, step);
    if (sx(x) + 2 + ctx.measureText(label).width < W - 20) ctx.fillText(label, sx(x) + 2, H - 4);
  }
  for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) {
    ctx.fillText(gridLabel(y, step), 3, sy(y) - 2);
  }
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
    drawMark(ctx, x, y, m.radius * v.s, m.label, 6);
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
    const x = EXACT.pos[(k * N + i) * 2] + ORIGIN[0];
    const y = EXACT.pos[(k * N + i) * 2 + 1] + ORIGIN[1];
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
// A particle outside the view is marked by a small arrow at the edge, pointing to it (at
// most 40 arrows; the line above the view counts them all).
function drawOffView2(k) {
  let shown = 0, out = 0;
  ctx.fillStyle = COLORS.run;
  for (let i = 0; i < N; i++) {
    const X = sx(value(R1, k, i, 0)), Y = sy(value(R1, k, i, 1));
    if (!isFinite(X + Y) || (X >= 0 && X <= W && Y >= 0 && Y <= H)) continue;
    out++;
    if (shown >= 40) continue;
    shown++;
    edgeArrow(ctx, W, H, X, Y);
  }
  S.offView = out;
}
function drawOverlays2(k) {
  drawExact2(k);
  drawOffView2(k);
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
