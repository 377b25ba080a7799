// The live page, part 3 of 4: the rigid lab's view in 3D (flat-shaded faces, far to
// near, as tools/view draws them; the shapes' faces are geom.js's).
function up3() { return S.scene.model.up || [0, 0, 1]; }
function basis3() {  // two horizontal directions for the camera's yaw
  const U = up3();
  const a = Math.abs(U[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
  const e1 = norm3(sub3(a, mul3(U, dot3(a, U))));
  return [e1, cross3(U, e1)];
}
function shapeSize(i) {
  const s = S.scene.model.shapes[i];
  if (!s || s.shape === "unknown") return 0.2;
  if (s.shape === "box") return Math.max(s.size[0], s.size[1], s.size[2]);
  if (s.shape === "sphere") return 2 * s.radius;
  return Math.max(2 * s.radius, s.length);
}
function fit3() {
  const p0 = S.panes[0], n = p0.n();
  let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity], big = 0;
  for (let i = 0; i < n; i++) {
    const x = p0.pos(i);
    for (let d = 0; d < 3; d++) if (isFinite(x[d])) {
      lo[d] = Math.min(lo[d], x[d]); hi[d] = Math.max(hi[d], x[d]);
    }
    big = Math.max(big, shapeSize(i));
  }
  S.scene.model.hinges.forEach(function (h) {
    for (let d = 0; d < 3; d++) {
      lo[d] = Math.min(lo[d], h.anchor[d]); hi[d] = Math.max(hi[d], h.anchor[d]);
    }
  });
  if (!isFinite(lo[0])) { lo = [-1, -1, -1]; hi = [1, 1, 1]; }
  const radius = Math.max(Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2 + big, 0.5);
  const keep = S.cam || { yaw: -Math.PI / 2 + 0.6, pitch: 0.35 };
  const fov = 40 * Math.PI / 180;
  S.cam = { target: [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2],
    yaw: keep.yaw, pitch: keep.pitch, fov: fov, radius: radius, big: big,
    dist: radius / Math.sin(fov / 2 * 0.8) * 1.05 };
}
function camera(p) {
  const E = basis3(), cam = orbitCamera(S.cam, up3(), E[0], E[1], p.H);
  cam.W = p.W; cam.H = p.H;
  return cam;
}
function project(cam, q) {
  const d = sub3(q, cam.eye), z = dot3(d, cam.f);
  if (!(z > 1e-9)) return null;
  return [cam.W / 2 + cam.F * dot3(d, cam.r) / z, cam.H / 2 - cam.F * dot3(d, cam.u) / z, z];
}
function ray(cam, X, Y) {  // the direction through screen point (X, Y)
  return norm3(add3(cam.f, add3(mul3(cam.r, (X - cam.W / 2) / cam.F),
    mul3(cam.u, -(Y - cam.H / 2) / cam.F))));
}

function drawFloor3(p, cam) {
  const half = Math.max(S.cam.radius * 1.6, S.cam.big * 2);
  S.scene.model.planes.forEach(function (pl) {
    drawPlaneGrid(p.ctx, cam, pl, S.cam.target, half, project);
  });
}

function faces3(p, cam) {  // every front face of every body, far to near
  const items = [], n = p.n();
  for (let i = 0; i < n; i++) {
    const P = p.pose(i);
    if (!P) continue;
    const s = S.scene.model.shapes[i], col = BODY_COLORS[i % BODY_COLORS.length];
    if (s && s.shape === "sphere") {
      const c = project(cam, P.x);
      if (c) items.push({ z: c[2], i: i, sphere: true, c: c, r: cam.F * s.radius / c[2], col: col });
      continue;
    }
    shapeFaces(s, P).forEach(function (f) {
      const m = mul3(f.pts.reduce(add3, [0, 0, 0]), 1 / f.pts.length);
      if (dot3(f.n, sub3(cam.eye, m)) <= 0) return;
      const pp = f.pts.map(function (q) { return project(cam, q); });
      if (pp.some(function (q) { return !q; })) return;
      const z = pp.reduce(function (a, q) { return a + q[2]; }, 0) / pp.length;
      items.push({ z: z, i: i, pp: pp, f: f, seam: f.seam,
        col: shade(col, 0.5 + 0.6 * Math.max(0, dot3(f.n, cam.light))) });
    });
  }
  return items.sort(function (a, b) { return b.z - a.z; });
}
function path3(ctx, pts) {
  pts.forEach(function (q, j) { if (j === 0) ctx.moveTo(q[0], q[1]); else ctx.lineTo(q[0], q[1]); });
  ctx.closePath();
}

function draw3(p) {
  if (!S.cam) fit3();
  const ctx = p.ctx, cam = camera(p);
  ctx.setTransform(p.DPR, 0, 0, p.DPR, 0, 0);
  ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, p.W, p.H);
  drawFloor3(p, cam);
  if (p.kind === "none") return;
  faces3(p, cam).forEach(function (it) {
    ctx.fillStyle = it.col; ctx.lineWidth = 1;
    ctx.strokeStyle = it.seam ? it.col : "rgba(0,0,0,0.45)";
    ctx.beginPath();
    if (it.sphere) ctx.arc(it.c[0], it.c[1], it.r, 0, 2 * Math.PI); else path3(ctx, it.pp);
    ctx.fill(); ctx.stroke();
  });
  // The solution's recorded run over this one: its bodies' edges, dashed.
  const o = S.panes[1 - p.idx];
  if (p.idx === 0 && o && o.kind === "trace" && S.overlay) {
    ctx.strokeStyle = COLORS[1]; ctx.lineWidth = 1.5; ctx.setLineDash([5, 3]);
    for (let i = 0; i < o.n(); i++) {
      const P = o.pose(i);
      if (!P) continue;
      ctx.beginPath();
      shapeFaces(S.scene.model.shapes[i], P).forEach(function (f) {
        const pp = f.pts.map(function (q) { return project(cam, q); });
        if (!pp.some(function (q) { return !q; })) path3(ctx, pp);
      });
      ctx.stroke();
    }
    ctx.setLineDash([]);
  }
  S.scene.model.hinges.forEach(function (h) {
    const a = project(cam, h.anchor);
    if (h.axis) {
      drawHingeAxis(ctx, cam, project, h.anchor, h.axis,
                    Math.max(shapeSize(h.body), S.cam.radius * 0.3));
    }
    if (a) {
      ctx.fillStyle = "#000"; ctx.beginPath();
      path3(ctx, [[a[0], a[1] - 6], [a[0] + 6, a[1]], [a[0], a[1] + 6], [a[0] - 6, a[1]]]);
      ctx.fill();
    }
  });
  for (let i = 0; i < p.n(); i++) {  // centres and body axes on top
    const P = p.pose(i);
    if (!P) continue;
    const c = project(cam, P.x);
    if (!c) continue;
    drawBodyAxes(ctx, cam, project, P, c, 0.65 * shapeSize(i));
    ctx.fillStyle = "#111"; ctx.beginPath(); ctx.arc(c[0], c[1], 3.5, 0, 2 * Math.PI); ctx.fill();
  }
  if (S.trails && p.trail.length > 1) {
    ctx.strokeStyle = COLORS[p.idx]; ctx.lineWidth = 2; ctx.globalAlpha = 0.6;
    ctx.beginPath();
    p.trail[0].ids.forEach(function (id, j) {
      p.trail.forEach(function (fr, k) {
        const q = project(cam, fr.xy.slice(3 * j, 3 * j + 3));
        if (!q) return;
        if (k === 0) ctx.moveTo(q[0], q[1]); else ctx.lineTo(q[0], q[1]);
      });
    });
    ctx.stroke(); ctx.globalAlpha = 1;
  }
  if (S.grab && S.grab.pane === p.idx) {
    const P = p.pose(S.grab.item);
    if (P) {
      const a = project(cam, add3(P.x, apply(P.R, S.grab.at))), b = project(cam, S.grab.target);
      if (a && b) {
        ctx.strokeStyle = "#d62728"; ctx.lineWidth = 2;
        ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(b[0], b[1]); ctx.stroke();
        ctx.fillStyle = "#d62728"; ctx.beginPath(); ctx.arc(a[0], a[1], 4, 0, 2 * Math.PI); ctx.fill();
      }
    }
  }
}

// The body under the mouse and the point of it hit (world), or null.
function pick3(p, X, Y) {
  const cam = camera(p), items = faces3(p, cam), d = ray(cam, X, Y);
  for (let k = items.length - 1; k >= 0; k--) {  // nearest first
    const it = items[k];
    if (it.sphere) {
      if (Math.hypot(X - it.c[0], Y - it.c[1]) > it.r) continue;
      const P = p.pose(it.i), s = S.scene.model.shapes[it.i];
      const oc = sub3(cam.eye, P.x), b = dot3(oc, d);
      const disc = b * b - (dot3(oc, oc) - s.radius * s.radius);
      const t = -b - Math.sqrt(Math.max(0, disc));
      return { item: it.i, hit: add3(cam.eye, mul3(d, t)) };
    }
    if (!inside(it.pp, X, Y)) continue;
    const q0 = it.f.pts[0], t = dot3(sub3(q0, cam.eye), it.f.n) / dot3(d, it.f.n);
    return { item: it.i, hit: add3(cam.eye, mul3(d, t)) };
  }
  return null;
}
function inside(pts, X, Y) {  // is (X, Y) inside the polygon (even-odd rule)?
  let c = false;
  for (let a = 0, b = pts.length - 1; a < pts.length; b = a++) {
    if ((pts[a][1] > Y) !== (pts[b][1] > Y) &&
        X < (pts[b][0] - pts[a][0]) * (Y - pts[a][1]) / (pts[b][1] - pts[a][1]) + pts[a][0]) c = !c;
  }
  return c;
}
// Where the mouse ray meets the plane through `through`, facing the camera.
function target3(p, X, Y, through) {
  const cam = camera(p), d = ray(cam, X, Y);
  const t = dot3(sub3(through, cam.eye), cam.f) / dot3(d, cam.f);
  return add3(cam.eye, mul3(d, t));
}
