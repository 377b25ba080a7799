// tools/view's page, part 5 of 6: the curves against time, with the playhead's cursor.
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
  this.canvas.addEventListener("mouseleave", function () {
    self.hoverT = null; self.shownAt = null; self.draw();
  });
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
Chart.prototype.tr = function (v) {  // the value as drawn: log10 |v| on a log scale
  if (!this.log) return v;
  return v === null || v === 0 ? null : Math.log10(Math.abs(v));
};
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
  // Every curve constant to rounding (a stub's energy of 1e-29 J, a momentum of 0): drawn
  // flat at its value, as tools/plot draws it (tools/wbplot/flat.py), with the value said.
  this.flat = null;
  if (drawable && !this.log) {
    const all = [];
    this.series.forEach(function (s) { all.push.apply(all, s.v); });
    const f = flatValue(all, this.opts.scale || 0);
    if (f !== null) {
      this.flat = f;
      const half = f === 0 ? 1 : 0.1 * Math.abs(f);
      lo = f - half; hi = f + half;
    }
  }
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
    const label = decades ? "1e" + Math.round(y)
      : this.log ? fmt(Math.pow(10, y), 3) : gridLabel(y, ys);
    c.fillText(label, 2, Y(y) + 3);
  }
  const tr = TRANGE, ts = niceStep(tr[1] - tr[0], 5);
  for (let t = Math.ceil(tr[0] / ts) * ts; t <= tr[1] + 1e-12; t += ts) {
    c.moveTo(Math.round(this.px(t)) + 0.5, m.t); c.lineTo(Math.round(this.px(t)) + 0.5, h - m.b);
    if (this.px(t) < w - m.r - 40) c.fillText(gridLabel(t, ts), this.px(t) - 6, h - 5);
  }
  c.stroke();
  c.fillText("t (s)", w - m.r - 24, h - 5);
  if (this.flat !== null) {
    c.fillStyle = "#444"; c.font = "11px sans-serif";
    c.fillText(this.flat === 0 ? "= 0 (to rounding)" : "= " + fmt(this.flat, 6) +
      " (constant to rounding)", m.l + 8, m.t + 12);
  }
  if (!drawable) {
    c.fillStyle = "#444"; c.font = "12px sans-serif";
    c.fillText(this.opts.empty || "no finite value to draw", m.l + 10, m.t + 40);
  }
  c.strokeStyle = "#bbb"; c.strokeRect(m.l + 0.5, m.t + 0.5, w - m.l - m.r - 1, h - m.t - m.b - 1);
  c.save(); c.beginPath(); c.rect(m.l, m.t, w - m.l - m.r, h - m.t - m.b); c.clip();
  // Totals (E) last, on top: a total equal to one of its parts stays visible.
  const parts = this.series.filter(function (s) { return !s.top; });
  parts.concat(this.series.filter(function (s) { return s.top; })).forEach(function (s) {
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
    return '<span style="color:' + s.color + '">' + esc(s.name) + " "
      + esc(j < 0 ? "—" : fmt(s.v[j], 6)) + "</span>";
  });
  this.box.querySelector(".vals").innerHTML = vals.join(" ");
};
function nearestBefore(ts, t) {
  let lo = 0, hi = ts.length - 1;
  if (!ts.length || t < ts[0] - 1e-12 * Math.abs(ts[0] || 1)) return -1;
  const tol = 1e-9 * Math.max(Math.abs(ts[hi]), 1e-300);
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (ts[mid] <= t + tol) lo = mid; else hi = mid - 1;
  }
  return lo;
}

// The time axis is the playhead's, the first run's: a second run that lasts longer is cut
// at its end (a first run that diverged early keeps its blow-up readable).
const TRANGE = [R1.t[0], R1.t[R1.frames - 1]];
function makeCharts() {
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
    E.push({ name: "E" + suffix, color: ri ? COLORS.run2 : "#111", t: s.t, v: s.energy, dash: d,
      width: 1.8, top: true });
    if (!ri) {
      E.push({ name: "K", color: "#d62728", t: s.t, v: s.kinetic });
      E.push({ name: "U", color: "#1f77b4", t: s.t, v: s.potential });
    }
    const xyz = [["x", "#d62728"], ["y", "#2ca02c"], ["z", "#1f77b4"]].slice(0, RIGID ? 3 : 2);
    const curve = function (name, color) {
      return { name: name + suffix, color: ri ? shadeAlt(color) : color, t: s.t, v: s[name],
        dash: d };
    };
    xyz.forEach(function (a) { P.push(curve("p" + a[0], a[1])); });
    if (RIGID) xyz.forEach(function (a) { L.push(curve("L" + a[0], a[1])); });
  });
  const e0 = RUNS[0].summary || {};
  const escale = Math.max(Math.abs(e0.energy0 || 0), Math.abs(e0.energy || 0));
  if (E.length) new Chart("Energy (J)", E, { log: anyDiv, id: "energy", scale: escale });
  if (P.length) new Chart("Momentum (kg m/s)", P, { log: anyDiv, id: "momentum" });
  if (L.length) {
    new Chart("Angular momentum about the origin (kg m²/s)", L, { log: anyDiv, id: "angular" });
  }
  if (META.exact) new Chart("Distance from the exact motion (m), largest over particles",
    [{ name: "|x − exact|", color: "#111", t: META.exact.distance.t, v: META.exact.distance.v }],
    { log: true, id: "exact" });
  if (META.difference) {
    const dif = META.difference;
    const D = [{ name: "|x₁ − x₂|", color: COLORS.run2, t: dif.t, v: dif.v }];
    if (dif.angle) D.push({ name: "angle (rad)", color: "#7b3294", t: dif.t, v: dif.angle });
    new Chart("Difference between the runs, largest over " + (RIGID ? "bodies" : "particles"), D,
      { log: true, id: "difference", empty: META.difference.identical
        ? "0 at every written step: the two runs coincide" : "no written time in common" });
  }
  if (!charts.length) {
    el("charts").innerHTML = '<p class="muted">No curves: give the run\'s --stats file.</p>';
  }
}
function shadeAlt(hex) {  // the second run's lighter shade of a first run's colour
  return hex === "#d62728" ? "#ff9896" : hex === "#2ca02c" ? "#98df8a" : "#aec7e8";
}
