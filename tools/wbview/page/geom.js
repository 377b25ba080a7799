// tools/view's page, part 1 of 6, shared with the live pages (tools/wbview/live): pure
// helpers with no state: 3-vectors, rotations, shapes' faces, colours, pixel stamps, and
// the rule that draws a quantity constant to rounding flat (tools/wbplot/flat.py's).
function sub3(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
function add3(a, b) { return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]; }
function mul3(a, s) { return [a[0] * s, a[1] * s, a[2] * s]; }
function dot3(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function cross3(a, b) {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}
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
function shade(hex, k) {
  const v = parseInt(hex.slice(1), 16);
  const r = (v >> 16) & 255, g = (v >> 8) & 255, b = v & 255;
  const c = function (x) { return Math.min(255, Math.round(x * k)); };
  return "rgb(" + c(r) + "," + c(g) + "," + c(b) + ")";
}
function boxCorners(size) {
  const out = [];
  for (let k = 0; k < 8; k++) {  // bit 0: x, bit 1: y, bit 2: z (set: +), as the lab's
    out.push([(k & 1 ? 0.5 : -0.5) * size[0], (k & 2 ? 0.5 : -0.5) * size[1],
      (k & 4 ? 0.5 : -0.5) * size[2]]);
  }
  return out;
}
const BOX_FACES = [  // corners (counter-clockwise seen from outside) and the outward normal
  [[0, 2, 6, 4], [-1, 0, 0]], [[1, 5, 7, 3], [1, 0, 0]], [[0, 4, 5, 1], [0, -1, 0]],
  [[2, 3, 7, 6], [0, 1, 0]], [[0, 1, 3, 2], [0, 0, -1]], [[4, 6, 7, 5], [0, 0, 1]]];
const CYL_N = 24;
function shapeFaces(s, P) {  // [{pts: world points, n: world normal}] of shape s at pose P
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
      faces.push({ pts: [bot[k], bot[k1], top[k1], top[k]],
        n: apply(P.R, [Math.cos(a), Math.sin(a), 0]), seam: true });
    }
    faces.push({ pts: top.slice().reverse(), n: apply(P.R, [0, 0, 1]) });
    faces.push({ pts: bot, n: apply(P.R, [0, 0, -1]) });
  }
  return faces;
}
const STAMPS = {};
function stampOffsets(R, ring) {
  const key = R + (ring ? "r" : "d");
  if (STAMPS[key]) return STAMPS[key];
  const out = [];
  for (let dy = -R - 1; dy <= R + 1; dy++) for (let dx = -R - 1; dx <= R + 1; dx++) {
    const d2 = dx * dx + dy * dy;
    const inRing = d2 <= (R + 0.5) * (R + 0.5) && d2 >= (R - 1) * (R - 1);
    if (ring ? inRing : d2 <= R * R + 0.8 * R) out.push(dx, dy);
  }
  return (STAMPS[key] = new Int32Array(out));
}
function rgba32(hex) {  // ImageData's bytes R, G, B, A as one little-endian word
  const v = parseInt(hex.slice(1), 16);
  return ((255 << 24) | ((v & 255) << 16) | (v & 0xff00) | ((v >> 16) & 255)) >>> 0;
}
function niceStep(span, target) {  // a 1-2-5 step giving about `target` intervals
  const raw = span / Math.max(target, 1);
  const p = Math.pow(10, Math.floor(Math.log10(raw)));
  const m = raw / p;
  return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}
// tools/wbplot/flat.py's rule: values that differ by no more than rounding of their scale
// (1e-9 of it, plus 1e-12 in SI units) are one constant. Returns the value to draw them at
// (0 when it is 0 to rounding of `scale`), or null when they are not constant.
const ROUNDING_REL = 1e-9, ROUNDING_ABS = 1e-12;
function flatValue(values, scale) {
  let lo = Infinity, hi = -Infinity, big = isFinite(scale) ? Math.abs(scale || 0) : 0;
  for (let i = 0; i < values.length; i++) {
    const v = values[i];
    if (v === null || v === undefined || !isFinite(v)) continue;
    lo = Math.min(lo, v); hi = Math.max(hi, v); big = Math.max(big, Math.abs(v));
  }
  if (!isFinite(lo) || hi - lo > ROUNDING_REL * big + ROUNDING_ABS) return null;
  const mid = (lo + hi) / 2;
  return Math.abs(mid) <= ROUNDING_REL * (isFinite(scale) ? Math.abs(scale || 0) : 0) +
    ROUNDING_ABS ? 0 : mid;
}
// An orbit camera {target, yaw, pitch, dist, fov} around the up direction `up` (e1, e2:
// horizontal axes) for a canvas of height H: the eye, its frame (f forward, r right, u up),
// the focal length in pixels and a light direction.
function orbitCamera(c, up, e1, e2, H) {
  const flat = add3(mul3(e1, Math.cos(c.yaw)), mul3(e2, Math.sin(c.yaw)));
  const dir = add3(mul3(flat, Math.cos(c.pitch)), mul3(up, Math.sin(c.pitch)));
  const eye = add3(c.target, mul3(dir, c.dist));
  const f = norm3(sub3(c.target, eye));
  let r = cross3(f, up);
  r = Math.hypot(r[0], r[1], r[2]) > 1e-9 ? norm3(r) : e1;
  const u = cross3(r, f);
  return { eye: eye, f: f, r: r, u: u, F: (H / 2) / Math.tan(c.fov / 2),
    light: norm3(add3(add3(up, mul3(f, -1.0)), mul3(r, 0.4))) };
}
// A plane drawn as a grid (and, seen from above, a tint) of half-size `half` around the
// camera's target; `project` maps a world point to the screen (null behind the eye).
function drawPlaneGrid(ctx, cam, pl, target, half, project) {
  const n = pl.normal;
  const a = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
  const u = norm3(sub3(a, mul3(n, dot3(a, n)))), w = cross3(n, u);
  const centre = sub3(target, mul3(n, dot3(sub3(target, pl.point), n)));
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
}
// A small arrow at the edge of a W x H view, pointing to the screen point (X, Y) outside
// it (a particle that left the view).
function edgeArrow(ctx, W, H, X, Y) {
  const dx = X - W / 2, dy = Y - H / 2;
  const s = Math.min((W / 2 - 8) / Math.abs(dx || 1e-9), (H / 2 - 8) / Math.abs(dy || 1e-9));
  const ex = W / 2 + dx * s, ey = H / 2 + dy * s, a = Math.atan2(dy, dx);
  ctx.beginPath();
  ctx.moveTo(ex + 7 * Math.cos(a), ey + 7 * Math.sin(a));
  ctx.lineTo(ex + 5 * Math.cos(a + 2.4), ey + 5 * Math.sin(a + 2.4));
  ctx.lineTo(ex + 5 * Math.cos(a - 2.4), ey + 5 * Math.sin(a - 2.4));
  ctx.closePath(); ctx.fill();
}
// A mark of a 2D scene (an attractor, a vortex's centre) at the screen point (x, y): the
// dashed circle of its reach (rPx pixels; none when 0), a cross of arm `arm` pixels and
// its label beside it. Both pages draw marks with it.
function drawMark(ctx, x, y, rPx, label, arm) {
  ctx.strokeStyle = "#555"; ctx.fillStyle = "#555"; ctx.lineWidth = 1.5;
  if (rPx) {
    ctx.setLineDash([4, 4]);
    ctx.beginPath(); ctx.arc(x, y, rPx, 0, 2 * Math.PI); ctx.stroke();
    ctx.setLineDash([]);
  }
  ctx.beginPath();
  ctx.moveTo(x - arm, y); ctx.lineTo(x + arm, y); ctx.moveTo(x, y - arm); ctx.lineTo(x, y + arm);
  ctx.stroke();
  ctx.fillText(label, x + arm + 1, y - arm + 1);
}
const AXIS_COLORS = ["#d62728", "#2ca02c", "#1f77b4"];  // a body's x, y, z axes
// A body's axes at pose P (its centre drawn at the screen point c), L metres long.
function drawBodyAxes(ctx, cam, project, P, c, L) {
  for (let d = 0; d < 3; d++) {
    const e = [0, 0, 0]; e[d] = L;
    const q = project(cam, add3(P.x, apply(P.R, e)));
    if (!q) continue;
    ctx.strokeStyle = AXIS_COLORS[d]; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.moveTo(c[0], c[1]); ctx.lineTo(q[0], q[1]); ctx.stroke();
  }
}
// A revolute hinge's axis through its anchor, L metres each way, projected by the page's
// project(cam, point) (null behind the camera: then nothing is drawn).
function drawHingeAxis(ctx, cam, project, anchor, axis, L) {
  const p0 = project(cam, sub3(anchor, mul3(axis, L)));
  const p1 = project(cam, add3(anchor, mul3(axis, L)));
  if (p0 && p1) {
    ctx.strokeStyle = "#7b3294"; ctx.lineWidth = 2.5;
    ctx.beginPath(); ctx.moveTo(p0[0], p0[1]); ctx.lineTo(p1[0], p1[1]); ctx.stroke();
  }
}
