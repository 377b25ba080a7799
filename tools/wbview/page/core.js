// tools/view's page, part 2 of 6 (page.py joins them in one function, in this order):
// the data, the state, formatting, the page's text and the canvas helpers.
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
  const what = RIGID ? (N === 1 ? " body" : " bodies") : (N === 1 ? " particle" : " particles");
  let sub = N + what
    + " · " + R1.label + " (" + R1.path + ")";
  if (R1.dt) sub += " · run at h = " + fmt(R1.dt, 6) + " s";
  if (R2) sub += " against " + R2.label + " (" + R2.path + ")";
  el("subtitle").textContent = sub;
  // The scene's words are for its own dt: a run at another h is said to be one.
  const other = R1.dt && META.scene_dt && Math.abs(R1.dt - META.scene_dt) > 1e-9 * META.scene_dt;
  el("desc").textContent = (other ? "This run used h = " + fmt(R1.dt, 6) + " s, not the scene's "
    + "dt = " + fmt(META.scene_dt, 6) + " s; the scene's description, for its own dt: " : "")
    + (META.description || "") || (META.scene ? "" :
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
    if (!r.stats) notes.push(esc(who) + "no stats file: no curves (--stats, or RUN-stats.csv "
      + "beside the trace RUN.csv)");
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
    if (R2) {
      items.push('<span class="sw" style="color:' + COLORS.run2 + '">□</span>' + esc(R2.label)
        + " (edges)");
    }
    items.push('<span class="sw" style="color:' + COLORS.com + '">●</span>centre of mass, axes '
      + '<span style="color:' + AXIS_COLORS[0] + '">x</span> <span style="color:' + AXIS_COLORS[1]
      + '">y</span> <span style="color:' + AXIS_COLORS[2] + '">z</span>');
    if (SCENE && SCENE.planes.length) items.push('<span class="sw" style="color:' + COLORS.pick
      + '">●</span>contact point (within 1 mm of a plane)');
    if (SCENE && SCENE.hinges.length) items.push('<span class="sw">◆</span>hinge anchor'
      + (SCENE.hinges.some(function (h) { return h.axis; })
        ? ', <span style="color:#7b3294">—</span> hinge axis' : ""));
  } else {
    items.push('<span class="sw" style="color:' + COLORS.run + '">●</span>' + esc(R1.label));
    if (R2) {
      items.push('<span class="sw" style="color:' + COLORS.run2 + '">○</span>' + esc(R2.label));
    }
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
