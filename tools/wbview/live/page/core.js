// The live page, part 1 of 4 (tools/wbview/live/page.py joins them after tools/wbview's
// geom.js): the page's data, the WebAssembly modules and the simulations they hold, the
// runs (panes) and formatting. Nothing physical is computed here: a Sim is the lab's
// own C++ (framework/live/, docs/live.md).
const META = JSON.parse(document.getElementById("wb-live").textContent);
const RIGID = META.kind === "rigid";
const COLORS = ["#1f77b4", "#ff7f0e"];        // the first run, the one beside it
const BODY_COLORS = ["#4e79a7", "#59a14f", "#edc948", "#b07aa1", "#76b7b2", "#e15759"];
const FRAME_MS = 1000 / 60;                   // one displayed frame at 60 Hz
const R = { T: 0, STEPS: 1, K: 2, V: 3, E: 4, PX: 5, PY: 6, PZ: 7, LX: 8, LY: 9, LZ: 10,
  EVALS: 11, UNCONVERGED: 12, EXACT: 13 };   // framework/live/live.h, enum Readout
const el = function (id) { return document.getElementById(id); };

// ---------------------------------------------------------------- formatting
function fmt(x, digits) {
  if (x === null || x === undefined || Number.isNaN(x)) return "—";
  if (!isFinite(x)) return String(x);
  digits = digits || 5;
  if (x !== 0 && (Math.abs(x) >= 1e6 || Math.abs(x) < 1e-4)) return x.toExponential(digits - 1);
  return String(+x.toPrecision(digits));
}
function esc(s) {
  return String(s).replace(/[&<>"]/g, function (c) {
    return { "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" }[c];
  });
}

// ---------------------------------------------------------------- a simulation
// One scene stepped by a module's C++ (framework/live/exports.cpp).
function Sim(M, side) {
  this.M = M;
  this.side = side;
  const w = function (name, ret, args) { return M.cwrap(name, ret, args); };
  this.f = {
    load: w("wb_live_load", "number", ["number", "string", "string"]),
    update: w("wb_live_update", "number", ["number", "string"]),
    reset: w("wb_live_reset", "number", ["number"]),
    integrator: w("wb_live_integrator", "number", ["number", "string"]),
    step: M._wb_live_step, state: M._wb_live_state, size: M._wb_live_state_size,
    readouts: M._wb_live_readouts, exact: M._wb_live_exact, exactSize: M._wb_live_exact_size,
    grab: M._wb_live_grab, release: M._wb_live_release,
    status: w("wb_live_status", "string", ["number"]),
    error: w("wb_live_error", "string", [])
  };
  this.id = M._wb_live_new();
  if (this.id < 0) throw new Error("wb_live_new: " + this.f.error());
}
Sim.prototype.call = function (rc) {  // 0 ok, else the C++ message
  return rc === 0 ? null : this.f.error() || "failed";
};
Sim.prototype.load = function (file, text) { return this.call(this.f.load(this.id, file, text)); };
Sim.prototype.update = function (text) { return this.call(this.f.update(this.id, text)); };
Sim.prototype.reset = function () { return this.call(this.f.reset(this.id)); };
Sim.prototype.setIntegrator = function (name) {
  return this.call(this.f.integrator(this.id, name));
};
Sim.prototype.step = function (h, n) { return this.f.step(this.id, h, n); };
Sim.prototype.doubles = function (ptr, n) {  // a copy: the heap may move at the next call
  return n > 0 ? new Float64Array(this.M.HEAPF64.buffer, ptr, n).slice() : new Float64Array(0);
};
Sim.prototype.state = function () {
  return this.doubles(this.f.state(this.id), this.f.size(this.id));
};
Sim.prototype.readouts = function () {
  return this.doubles(this.f.readouts(this.id), this.M._wb_live_readout_count());
};
Sim.prototype.exact = function () {
  return this.doubles(this.f.exact(this.id), this.f.exactSize(this.id));
};
Sim.prototype.status = function () { return JSON.parse(this.f.status(this.id) || "{}"); };
Sim.prototype.grab = function (i, target, at) {
  this.f.grab(this.id, i, target[0], target[1], target[2] || 0, at[0], at[1], at[2]);
};
Sim.prototype.release = function () { this.f.release(this.id); };
Sim.prototype.free = function () { this.M._wb_live_delete(this.id); };

// ---------------------------------------------------------------- the page's state
const S = {
  modules: {},        // side -> the instantiated module
  info: {},           // side -> the lab's info (JSON from the module)
  scene: null,        // META.scenes[k] shown
  doc: null,          // its JSON, as the knobs have changed it
  h: 0,               // the step size (s)
  playing: true, speed: 1, trails: false,
  panes: [],          // the runs: panes[0] always, panes[1] when something is beside it
  compare: "none",
  debt: 0,            // simulated seconds owed to real time
  last: null,         // time of the last animation frame (ms)
  cost: { ms: 0, steps: 0, window: [] },  // the step's cost, measured here
  realtime: { behind: false, ratio: 1 },
  ready: false, frames: 0, errors: [],
  grab: null,         // {pane, item, at (body frame), target}
  dragMark: null      // a scene point being moved: {path, index}
};

// A run: a Sim of one module, or the solution's recorded run of the scene (a trace).
function Pane(idx) {
  this.idx = idx;
  this.canvas = el("stage-" + idx);
  this.ctx = this.canvas.getContext("2d");
  this.kind = "none";     // "live" or "trace"
  this.sim = null;
  this.side = null;
  this.integrator = null;
  this.label = "";
  this.state = null;      // the last state read (Float64Array)
  this.exact = null;
  this.ro = null;         // the last readouts
  this.status = {};
  this.history = [];      // [t, E, K, V, |p|, L, exact distance] samples for the charts
  this.segment = null;    // {step, E, h}: where the current step size began
  this.trail = [];        // recent positions of a few items
  this.W = 10; this.H = 10; this.DPR = 1;
}
Pane.prototype.resize = function () {
  this.DPR = window.devicePixelRatio || 1;
  const r = this.canvas.getBoundingClientRect();
  this.W = Math.max(10, r.width); this.H = Math.max(10, r.height);
  this.canvas.width = Math.round(this.W * this.DPR);
  this.canvas.height = Math.round(this.H * this.DPR);
  this.bg = null;
};
Pane.prototype.n = function () {
  if (this.kind === "trace") return S.scene.reference.n;
  return this.state ? this.state.length / (RIGID ? 13 : 4) : 0;
};
Pane.prototype.pos = function (i) {  // the item's position now ([x, y] or [x, y, z])
  const s = this.state;
  if (this.kind === "trace") return traceValue(this, i);
  return RIGID ? [s[13 * i], s[13 * i + 1], s[13 * i + 2]] : [s[4 * i], s[4 * i + 1]];
};
Pane.prototype.pose = function (i) {  // a body's {x, R}
  const p = this.kind === "trace" ? traceValue(this, i) : null;
  const s = this.state, b = 13 * i;
  const x = p ? p.slice(0, 3) : [s[b], s[b + 1], s[b + 2]];
  const q = p ? p.slice(3, 7) : [s[b + 3], s[b + 4], s[b + 5], s[b + 6]];
  const Rm = rot(q);
  return Rm && isFinite(x[0] + x[1] + x[2]) ? { x: x, R: Rm } : null;
};

// ---------------------------------------------------------------- the recorded run
function decode(b64) {
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return new Float32Array(bytes.buffer);
}
// The recorded frame at the first run's time (the last written one not after it).
function traceFrame(pane) {
  const ref = S.scene.reference, t = S.panes[0].ro ? S.panes[0].ro[R.T] : 0;
  let lo = 0, hi = ref.t.length - 1;
  if (t >= ref.t[hi]) return hi;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (ref.t[mid] <= t + 1e-12) lo = mid; else hi = mid - 1;
  }
  return lo;
}
function traceValue(pane, i) {
  const ref = S.scene.reference;
  if (!ref.values) ref.values = decode(ref.pos);
  const k = pane.frame, c = ref.cols;
  const base = (k * ref.n + i) * c;
  const out = [];
  for (let d = 0; d < c; d++) out.push(ref.values[base + d] + (d < ref.origin.length ? ref.origin[d] : 0));
  return out;
}
