// tools/view's page, part 4 of 6: the rigid lab's view, in 3D (flat-shaded faces, far to
// near).
// ---------------------------------------------------------------- 3D view
function pathThrough(pts) {  // a closed path through screen points [x, y, ...]
  pts.forEach(function (p, j) {
    if (j === 0) ctx.moveTo(p[0], p[1]); else ctx.lineTo(p[0], p[1]);
  });
  ctx.closePath();
}
function fillDot(c, r) {  // a filled dot of radius r at screen point c
  ctx.beginPath(); ctx.arc(c[0], c[1], r, 0, 2 * Math.PI); ctx.fill();
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
    for (let d = 0; d < 3; d++) {
      lo[d] = Math.min(lo[d], h.anchor[d]); hi[d] = Math.max(hi[d], h.anchor[d]);
    }
  });
  const target = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2];
  const half = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2;
  const radius = Math.max(half + BIG * 0.75, 1e-6);
  const keep = S.cam || { yaw: -Math.PI / 2 + 0.6, pitch: 0.35 };
  const fov = 40 * Math.PI / 180;
  const aspect = Math.min(1, W / H);
  S.cam = { target: target, yaw: keep.yaw, pitch: keep.pitch, fov: fov,
    dist: radius / Math.sin(fov / 2 * aspect) * 1.05, radius: radius };
  S.dirty = true;
}
function camera() { return orbitCamera(S.cam, UP, E1, E2, H); }
function project(cam, p) {
  const d = sub3(p, cam.eye);
  const z = dot3(d, cam.f);
  if (!(z > 1e-6 * cam.F / 1000 + 1e-9)) return null;
  return [W / 2 + cam.F * dot3(d, cam.r) / z, H / 2 - cam.F * dot3(d, cam.u) / z, z];
}
function bodyFaces(i, P) {  // [{pts: world points, n: world normal}]
  return shapeFaces(SCENE ? SCENE.shapes[i] : null, P);
}
function contactPoints(i, P) {  // the rigid lab's candidates (framework/drivers/rigid)
  const s = SCENE.shapes[i], out = [];
  SCENE.planes.forEach(function (pl) {
    let cand = [];
    if (s.shape === "sphere") cand = [sub3(P.x, mul3(pl.normal, s.radius))];
    else if (s.shape === "box") {
      cand = boxCorners(s.size).map(function (p) { return add3(P.x, apply(P.R, p)); });
    }
    else if (s.shape === "cylinder") {
      for (let e = -1; e <= 1; e += 2) for (let k = 0; k < 16; k++) {
        const a = 2 * Math.PI * k / 16;
        const p = [s.radius * Math.cos(a), s.radius * Math.sin(a), 0.5 * e * s.length];
        cand.push(add3(P.x, apply(P.R, p)));
      }
    }
    cand.forEach(function (p) {
      if (dot3(sub3(p, pl.point), pl.normal) < SCENE.contact_slop) out.push(p);
    });
  });
  return out;
}

function drawFloor3(cam) {
  if (!SCENE) return;
  const half = Math.max(S.cam.radius * 1.6, BIG * 2);
  SCENE.planes.forEach(function (pl) { drawPlaneGrid(ctx, cam, pl, S.cam.target, half, project); });
}

function draw3() {
  if (!S.cam || S.follow) fit3(S.follow);
  const cam = camera();
  ctx.setTransform(DPR, 0, 0, DPR, 0, 0);
  ctx.fillStyle = "#ffffff"; ctx.fillRect(0, 0, W, H);
  drawFloor3(cam);
  const k = S.frame;
  const k2 = R2 && S.run2 ? frameAt(R2, R1.t[k]) : null;
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
      const lit = 0.5 + 0.6 * Math.max(0, dot3(f.n, cam.light));
      items.push({ z: z, pp: pp, seam: f.seam, col: shade(col, lit) });
    });
  }
  items.sort(function (a, b) { return b.z - a.z; });
  items.forEach(function (it) {
    if (it.sphere) { drawSphere(cam, it); return; }
    ctx.fillStyle = it.col; ctx.lineWidth = 1;
    ctx.strokeStyle = it.seam ? it.col : "rgba(0,0,0,0.45)";  // no seams inside a cylinder
    ctx.beginPath(); pathThrough(it.pp); ctx.fill(); ctx.stroke();
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
      if (c) {
        const r = cam.F * s.radius / c[2];
        ctx.moveTo(c[0] + r, c[1]); ctx.arc(c[0], c[1], r, 0, 2 * Math.PI);
      }
    } else bodyFaces(i, P).forEach(function (f) {
      const pp = f.pts.map(function (p) { return project(cam, p); });
      if (pp.some(function (p) { return !p; })) return;
      pathThrough(pp);
    });
    ctx.stroke(); ctx.setLineDash([]);
    const c = project(cam, P.x);
    if (c) { ctx.fillStyle = COLORS.run2; fillDot(c, 3); }
  }
  // Hinges: anchor, the body point pinned to it, a revolute hinge's axis.
  if (SCENE) SCENE.hinges.forEach(function (h) {
    const a = project(cam, h.anchor);
    const P0 = pose(R1, 0, h.body), P = poses[h.body];
    if (h.axis) {
      drawHingeAxis(ctx, cam, project, h.anchor, h.axis,
                    Math.max(shapeSize(h.body), S.cam.radius * 0.3));
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
      ctx.beginPath();
      pathThrough([[a[0], a[1] - 6], [a[0] + 6, a[1]], [a[0], a[1] + 6], [a[0] - 6, a[1]]]);
      ctx.fill();
    }
  });
  // Trails of the centres of mass, over the bodies (a body hides its own short path).
  if (S.trails) [[R1, k, COLORS.trail], [R2, k2, COLORS.trail2]].forEach(function (a) {
    if (!a[0] || a[1] === null) return;
    ctx.strokeStyle = a[2]; ctx.lineWidth = 2; ctx.globalAlpha = 0.8;
    ctx.beginPath();
    for (let i = 0; i < N; i++) {
      let started = false;
      for (let q = 0; q <= a[1]; q++) {
        const p = project(cam, [value(a[0], q, i, 0), value(a[0], q, i, 1), value(a[0], q, i, 2)]);
        if (!p || !isFinite(p[0] + p[1])) { started = false; continue; }
        if (!started) { ctx.moveTo(p[0], p[1]); started = true; } else ctx.lineTo(p[0], p[1]);
      }
    }
    ctx.stroke(); ctx.globalAlpha = 1;
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
        if (q) fillDot(q, 3.5);
      });
    }
    const c = project(cam, P.x);
    drawn.push(c);
    if (!c) continue;
    drawBodyAxes(ctx, cam, project, P, c, 0.5 * shapeSize(i) + 0.15 * shapeSize(i));
    ctx.fillStyle = COLORS.com;
    fillDot(c, 3.5);
    if (S.pick === i) {
      ctx.strokeStyle = COLORS.pick; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(c[0], c[1], 9, 0, 2 * Math.PI); ctx.stroke();
      ctx.fillStyle = COLORS.pick; ctx.font = "12px sans-serif";
      ctx.fillText("#" + i, c[0] + 11, c[1] - 9);
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
