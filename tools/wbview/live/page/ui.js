// The live page, part 4 of 4: starting the modules, the scene and its knobs, the runs
// side by side, the loop that steps them in real time, the readouts, the charts, the
// frame budget, the mouse, and window.wbLive (what tools/live-check reads).

// ---------------------------------------------------------------- the banner
function say(notes) {  // [{text, bad}] -> the banner
  const b = el("banner");
  if (!notes.length) { b.style.display = "none"; b.innerHTML = ""; return; }
  b.innerHTML = notes.map(function (n) {
    return "<p" + (n.bad ? ' class="bad"' : "") + ">" + n.html + "</p>";
  }).join("");
  b.className = notes.some(function (n) { return n.bad; }) ? "" : "warn";
  b.style.display = "block";
}
function fail(msg) {  // a problem of the page itself: on the page and in the console
  S.fatal = msg;
  console.error("live page: " + msg);
  say([{ html: esc(msg), bad: true }]);
}

// ---------------------------------------------------------------- panes
function recordedIntegrator() {  // the scene's, or the lab's default (its first)
  return S.scene.reference.integrator || integratorsOf(S.main)[0];
}
function paneLabel(p) {
  if (p.kind === "trace") {
    const r = S.scene.reference;
    return "the solution's recorded run (" + recordedIntegrator() + ", h = " + fmt(r.dt) + " s)";
  }
  const who = p.side === "student" ? "your code" : "the solution";
  return who + " (" + p.integrator + ")";
}
function makeLive(p, side, integrator) {
  if (!p.sim || p.sim.side !== side) p.sim = new Sim(S.modules[side], side);
  p.kind = "live"; p.side = side;
  const err = p.sim.load(S.scene.file, S.docText) ||
    (integrator ? p.sim.setIntegrator(integrator) : null);
  if (err) { p.error = err; return; }
  p.error = null;
  p.integrator = p.sim.status().integrator;
  refresh(p);
}
function integratorsOf(side) { return S.info[side].integrators.map(function (i) { return i.name; }); }
function fillSelect(sel, names, value) {
  sel.innerHTML = names.map(function (n) {
    return "<option" + (n === value ? " selected" : "") + ">" + esc(n) + "</option>";
  }).join("");
}
function compareChoices() {
  const out = [["none", "nothing"], ["same", "this code, another integrator"]];
  if (S.modules.solution && S.main !== "solution") out.push(["solution", "the solution, live"]);
  if (S.scene.reference) out.push(["trace", "the solution's recorded run"]);
  return out;
}
function setCompare(kind) {
  const p = S.panes[1];
  S.compare = kind;
  S.overlay = kind === "trace";
  el("pane-1").style.display = kind === "none" ? "none" : "flex";
  el("l-integ-1").style.display = kind === "same" || kind === "solution" ? "" : "none";
  p.kind = "none"; p.history = []; p.trail = [];
  if (kind === "same" || kind === "solution") {
    const side = kind === "same" ? S.main : "solution";
    const names = integratorsOf(side);
    let name = S.panes[0].integrator;
    if (kind === "same") name = names.find(function (n) { return n !== name; }) || name;
    fillSelect(el("integ-1"), names, name);
    makeLive(p, side, name);
    p.sim.reset();
  } else if (kind === "trace") {
    p.kind = "trace"; p.frame = 0;
  }
  syncRuns();
  S.panes.forEach(function (q) { q.resize(); });
  if (RIGID) fit3(); else fit2();
  if (S.scene.model) legend();
}
// Both runs from their initial state, together.
function syncRuns() {
  S.cost.window = [];
  S.panes.forEach(function (p) {
    if (p.kind === "live" && p.error) {  // the lab's code threw mid-step: a new world
      const err = p.sim.load(S.scene.file, S.docText) || p.sim.setIntegrator(p.integrator);
      p.error = err;
    }
    if (p.kind === "live") { p.sim.reset(); refresh(p); }
    p.history = []; p.trail = []; p.segment = null;
  });
  S.debt = 0;
  refreshTrace();
}

// ---------------------------------------------------------------- reading the runs
function refresh(p) {
  if (p.kind !== "live") return;
  p.state = p.sim.state();
  p.ro = p.sim.readouts();
  p.exact = p.sim.exact();
  p.status = p.sim.status();
  p.integrator = p.status.integrator || p.integrator;
  const steps = p.ro[R.STEPS], E = p.ro[R.E];
  if (!p.segment || p.segment.h !== S.h || p.segment.integrator !== p.integrator ||
      steps < p.segment.step) {
    p.segment = { step: steps, E: E, h: S.h, integrator: p.integrator };
  }
}
function refreshTrace() {
  const p = S.panes[1];
  if (p.kind !== "trace") return;
  const ref = S.scene.reference;
  p.frame = traceFrame(p);
  const E = ref.energy[p.frame];
  p.ro = [ref.t[p.frame], ref.steps[p.frame], NaN, NaN, E, NaN, NaN, NaN, NaN, NaN, NaN, NaN, NaN, NaN];
  p.integrator = recordedIntegrator();
}
// Energy growth per step since the step size (or integrator) last changed: (E/E0)^(1/k).
function growth(p) {
  if (!p.segment || !p.ro) return null;
  const k = p.ro[R.STEPS] - p.segment.step;
  if (k < 1 || !(p.segment.E !== 0) || !isFinite(p.segment.E)) return null;
  const q = p.ro[R.E] / p.segment.E;
  return q > 0 ? { factor: Math.pow(q, 1 / k), steps: k } : null;
}
function sample(p) {
  if (!p.ro) return;
  const r = p.ro;
  const L = RIGID ? Math.hypot(r[R.LX], r[R.LY], r[R.LZ]) : r[R.LZ];
  const row = [r[R.T], r[R.E], r[R.K], r[R.V], Math.hypot(r[R.PX], r[R.PY], r[R.PZ]), L,
    r[R.EXACT]];
  if (RIGID) {  // body 0's angular velocity seen from the body: R^T omega (the flip shows)
    const P = p.pose(0), s = p.state;
    const w = P && p.kind === "live" ? applyT(P.R, [s[10], s[11], s[12]]) : [NaN, NaN, NaN];
    row.push(w[0], w[1], w[2]);
  }
  p.history.push(row);
  if (p.history.length > 3000) p.history = p.history.filter(function (_, i) { return i % 2 === 0; });
  if (S.trails && p.kind === "live") {
    const n = p.n(), ids = [];
    for (let q = 0; q < Math.min(n, 200); q++) ids.push(Math.floor(q * n / Math.min(n, 200)));
    const xy = [];
    ids.forEach(function (i) { const q = p.pos(i); xy.push.apply(xy, q); });
    p.trail.push({ ids: ids, xy: xy });
    if (p.trail.length > 240) p.trail.shift();
  }
}

// ---------------------------------------------------------------- stepping in real time
// Of a 16.7 ms frame, what the steps may take: what drawing leaves, at least 4 ms (so that
// a heavy scene still steps, at 30 frames a second or more).
const BUDGET_MS = 14, MIN_BUDGET_MS = 4;
function stepBudget() { return Math.max(MIN_BUDGET_MS, BUDGET_MS - (S.drawMs || 0)); }
function stepRuns(n) {  // n steps of every live run; the most any took
  let most = 0;
  S.panes.forEach(function (p) {
    if (p.kind !== "live" || p.error) return;
    const k = p.sim.step(S.h, n);
    if (k < 0) {
      p.error = p.sim.f.error();
      S.playing = false;
      return;
    }
    most = Math.max(most, k);
  });
  return most;
}
function advance(wallS) {
  S.debt += Math.min(wallS, 0.1) * S.speed;
  const want = Math.floor(S.debt / S.h + 1e-9);
  if (want <= 0) return;
  const t0 = performance.now(), budget = stepBudget();
  let done = 0, chunk = Math.max(1, Math.min(want, S.chunk || 1)), per = stepCostMs() || 0;
  // Chunks of about 2 ms, so that the budget is checked often but the calls are few; the
  // next chunk only when it fits what is left (always one step a frame, at least).
  while (done < want && (done === 0 || performance.now() - t0 + chunk * per <= budget)) {
    const k = Math.min(chunk, want - done);
    const c0 = performance.now();
    const took = stepRuns(k);
    const ms = performance.now() - c0;
    if (took === 0) { done = want; break; }  // every run diverged or stopped
    done += k;
    S.cost.window.push([ms, k]);
    per = ms / k;
    chunk = Math.max(1, Math.round(k * 2 / Math.max(ms, 0.05)));
  }
  S.chunk = chunk;
  if (S.cost.window.length > 120) S.cost.window.splice(0, S.cost.window.length - 120);
  S.realtime = { behind: done < want, ratio: want > 0 ? done / want : 1 };
  S.debt = done < want ? 0 : S.debt - done * S.h;  // behind: no debt piles up
}
// ms of one step of every live run. The browser's clock resolves 0.1 ms, so the recent
// chunks tell only when they add up to some milliseconds; cheaper steps are timed on a
// copy of each run (the same scene, integrator and h, from the scene's start), stepped
// until the clock can tell.
function stepCostMs() {
  let ms = 0, k = 0;
  // Not the first chunks after a change: the browser compiles a function of the module
  // the first time it runs, and those chunks would count the compiling.
  S.cost.window.slice(10).forEach(function (c) { ms += c[0]; k += c[1]; });
  if (ms >= 5 && k > 0) { S.costFrom = "the run"; return ms / k; }
  let sum = 0, any = false;
  S.panes.forEach(function (p) {
    if (p.kind !== "live") return;
    const c = calibrate(p);
    if (c !== null) { sum += c; any = true; }
  });
  S.costFrom = "a copy of the run";
  return any ? sum : (k > 0 ? ms / k : null);
}
function calibrate(p) {
  const key = [p.side, S.docText, p.integrator, S.h].join("|");
  S.calib = S.calib || {};
  if (key in S.calib) return S.calib[key];
  S.calibSims = S.calibSims || {};
  const sim = S.calibSims[p.side] || (S.calibSims[p.side] = new Sim(S.modules[p.side], p.side));
  let out = null;
  if (!sim.load(S.scene.file, S.docText) && !sim.setIntegrator(p.integrator)) {
    // The clock is the wall's: on a busy machine the page can be held up for milliseconds
    // inside one run, so a run long enough to tell is timed three times, the fastest kept.
    const time = function (n) {
      sim.reset();
      const t0 = performance.now(), k = sim.step(S.h, n);
      return k < n ? null : performance.now() - t0;
    };
    for (let n = 16; n <= 65536; n *= 4) {
      let ms = time(n);
      if (ms === null) break;  // it diverged: no figure
      if (ms >= 3 || n === 65536) {
        for (let r = 0; r < 2 && ms !== null; r++) { const t = time(n); ms = t === null ? null : Math.min(ms, t); }
        if (ms === null) break;
        if (ms >= 3 || n === 65536) { out = ms / n; break; }
      }
    }
  }
  S.calib[key] = out;
  return out;
}

// ---------------------------------------------------------------- the loop
function frame(now) {
  requestAnimationFrame(frame);
  if (S.fatal) return;
  const wall = S.last === null ? 0 : (now - S.last) / 1000;
  S.last = now;
  if (wall > 0) S.fps = S.fps ? 0.9 * S.fps + 0.1 / wall : 1 / wall;
  S.frameTimes.push(now);
  if (S.frameTimes.length > 240) S.frameTimes.shift();
  if (S.pendingUpdate) applyUpdate();
  if (S.playing) advance(wall);
  S.panes.forEach(refresh);
  refreshTrace();
  S.panes.forEach(sample);
  if (!RIGID && !S.grab && !S.dragging && !S.userView) extend2();
  // A banner that comes or goes (diverged, a warning, "Not real time") changes the panes'
  // height: the canvas follows its box, else the drawing is stretched and the mouse lands
  // off what it is drawn over.
  S.panes.forEach(function (p) {
    const r = p.canvas.getBoundingClientRect();
    if (r.width > 0 && (Math.abs(r.width - p.W) > 0.5 || Math.abs(r.height - p.H) > 0.5)) p.resize();
  });
  const d0 = performance.now();
  S.panes.forEach(function (p) {
    if (p.idx === 1 && S.compare === "none") return;
    if (RIGID) draw3(p); else draw2(p);
  });
  const dms = performance.now() - d0;
  S.drawMs = S.drawMs === undefined ? dms : 0.9 * S.drawMs + 0.1 * dms;
  S.frames++;
  if (S.frames % 3 === 0) { readouts(); charts(); budget(); banner(); }
}

// ---------------------------------------------------------------- readouts
function readouts() {
  const rows = [];
  S.panes.forEach(function (p) {
    if (p.kind === "none" || !p.ro) return;
    const r = p.ro, g = growth(p), c = COLORS[p.idx];
    rows.push('<tr><td colspan="2" style="color:' + c + '"><b>' + esc(paneLabel(p)) + "</b></td></tr>");
    rows.push("<tr><td>t, step</td><td class=v>" + fmt(r[R.T], 6) + " s, " + r[R.STEPS] + "</td></tr>");
    rows.push("<tr><td>energy E = K + V</td><td class=v>" + fmt(r[R.E], 6) + " J = " +
      fmt(r[R.K]) + " + " + fmt(r[R.V]) + "</td></tr>");
    if (p.kind === "live") {
      if (g) rows.push("<tr><td>E per step (last " + g.steps + ")</td><td class=v>×" +
        g.factor.toFixed(8) + "</td></tr>");
      rows.push("<tr><td>momentum p</td><td class=v>[" + [r[R.PX], r[R.PY]].concat(RIGID ? [r[R.PZ]] : [])
        .map(function (x) { return fmt(x); }).join(", ") + "] kg m/s</td></tr>");
      if (RIGID) rows.push("<tr><td>angular momentum L</td><td class=v>[" +
        [r[R.LX], r[R.LY], r[R.LZ]].map(function (x) { return fmt(x); }).join(", ") +
        "] kg m²/s</td></tr>");
      if (isFinite(r[R.EXACT])) rows.push("<tr><td>from the exact motion</td><td class=v>" +
        fmt(r[R.EXACT]) + " m</td></tr>");
      if (r[R.UNCONVERGED] > 0) rows.push("<tr><td>unconverged solves</td><td class=v>" +
        r[R.UNCONVERGED] + "</td></tr>");
    }
  });
  rows.push("<tr><td>h</td><td class=v>" + fmt(S.h, 6) + " s" + theory() + "</td></tr>");
  el("readouts").innerHTML = "<table>" + rows.join("") + "</table>";
  S.panes.forEach(function (p) {
    const hud = el("hud-" + p.idx);
    if (p.kind === "none") return;
    const r = p.ro || [0, 0];
    hud.textContent = paneLabel(p) + " · t = " + fmt(r[R.T], 6) + " s · step " + r[R.STEPS] +
      (p.idx === 0 ? " · " + Math.round(S.fps || 0) + " fps" : "") +
      (p.offView ? " · " + p.offView + " out of view (arrows at the edge)" : "");
  });
}
// For a scene with a spring's closed form: explicit Euler's energy factor per step.
function theory() {
  if (!S.omega) return "";
  const hw = S.h * S.omega;
  return " (h ω = " + fmt(hw, 4) + "; explicit Euler's 1 + h²ω² = " + (1 + hw * hw).toFixed(8) + ")";
}

// ---------------------------------------------------------------- charts
function chartSeries() {
  const list = [
    { title: "energy (J)", cols: [[1, "E"], [2, "K"], [3, "V"]] },
    RIGID ? { title: "|L| (kg m²/s, solid) and |p| (kg m/s, dashed)", cols: [[5, "|L|"], [4, "|p|"]] }
      : { title: "|p| (kg m/s, solid) and L (kg m²/s, dashed)", cols: [[4, "|p|"], [5, "L"]] }];
  if (RIGID) list.push({ title: "body 0: ω in its own frame (rad/s): x, y, z",
    cols: [[7, "ωx"], [8, "ωy"], [9, "ωz"]], all: true });
  if (S.panes[0].history.some(function (h) { return isFinite(h[6]); })) {
    list.push({ title: "distance from the exact motion (m)", cols: [[6, "d"]] });
  }
  return list;
}
function charts() {
  const box = el("charts"), list = chartSeries();
  if (box.children.length !== list.length) {
    box.innerHTML = list.map(function (c, k) {
      return '<div class="chart"><div class="head"><b>' + esc(c.title) +
        '</b><label><input type="checkbox" class="logy" data-k="' + k + '"> log |y|</label></div>' +
        '<canvas id="chart-' + k + '"></canvas></div>';
    }).join("");
  }
  list.forEach(function (c, k) {
    const cv = el("chart-" + k), ctx = cv.getContext("2d"), dpr = window.devicePixelRatio || 1;
    const r = cv.getBoundingClientRect(), W = r.width, H = r.height;
    if (cv.width !== Math.round(W * dpr)) { cv.width = Math.round(W * dpr); cv.height = Math.round(H * dpr); }
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = "#fff"; ctx.fillRect(0, 0, W, H);
    const log = box.querySelector('.logy[data-k="' + k + '"]').checked;
    const tr = (function (v) { return log ? Math.log10(Math.abs(v)) : v; });
    let t0 = Infinity, t1 = -Infinity, lo = Infinity, hi = -Infinity;
    const lines = [];
    S.panes.forEach(function (p) {
      if (!p.history.length) return;
      c.cols.forEach(function (col, j) {
        if (p.idx === 1 && j > 0 && !c.all) return;  // the second run: its first curve only
        const pts = [];
        p.history.forEach(function (h) {
          const y = tr(h[col[0]]);
          if (!isFinite(y) || !isFinite(h[0])) return;
          pts.push([h[0], y]);
          t0 = Math.min(t0, h[0]); t1 = Math.max(t1, h[0]);
          lo = Math.min(lo, y); hi = Math.max(hi, y);
        });
        lines.push({ pts: pts, color: c.all ? AXIS_COLORS[j] : COLORS[p.idx],
          width: j === 0 || c.all ? 2 : 1, dash: c.all ? p.idx === 1 : j > 0, name: col[1] });
      });
    });
    if (!isFinite(lo)) return;
    // A quantity constant to rounding is drawn flat at its value, by tools/plot's rule
    // (tools/wbplot/flat.py: a spread of 1e-9 of its size, or 1e-12 in SI units: a stub's
    // 1e-29 J is 0, not an axis from 0 to 1e-29).
    const big = Math.max(Math.abs(hi), Math.abs(lo));
    const flat = hi - lo <= (log ? 1e-9 * Math.max(big, 1e-300) : 1e-9 * big + 1e-12);
    if (flat && !log && Math.abs((hi + lo) / 2) <= 1e-9 * big + 1e-12) { hi = 0; lo = 0; }
    if (flat) { const m = (hi + lo) / 2, d = Math.max(Math.abs(m) * 1e-3, 1e-12); lo = m - d; hi = m + d; }
    if (t1 <= t0) t1 = t0 + 1e-9;
    const L = 58, B = 14, X = function (t) { return L + (t - t0) / (t1 - t0) * (W - L - 6); };
    const Y = function (y) { return 4 + (hi - y) / (hi - lo) * (H - B - 8); };
    ctx.fillStyle = "#666"; ctx.font = "10px sans-serif";
    ctx.fillText((log ? "1e" : "") + fmt(hi, 4), 2, 12);
    ctx.fillText((log ? "1e" : "") + fmt(lo, 4), 2, H - B);
    ctx.fillText("t = " + fmt(t0, 4) + " s", L, H - 2);
    const right = fmt(t1, 4) + " s";
    ctx.fillText(right, W - 6 - ctx.measureText(right).width, H - 2);
    if (flat) ctx.fillText("constant to rounding: " + fmt((hi + lo) / 2, 8), L + 60, 12);
    lines.forEach(function (ln) {
      ctx.strokeStyle = ln.color; ctx.lineWidth = ln.width; ctx.setLineDash(ln.dash ? [3, 3] : []);
      ctx.beginPath();
      ln.pts.forEach(function (q, j) { if (j === 0) ctx.moveTo(X(q[0]), Y(q[1])); else ctx.lineTo(X(q[0]), Y(q[1])); });
      ctx.stroke();
    });
    ctx.setLineDash([]);
  });
}

// ---------------------------------------------------------------- frame budget
function budget() {
  const ms = stepCostMs();
  const per60 = ms === null ? null : ms * (1 / 60) / S.h;
  const lines = [];
  if (per60 === null) {
    lines.push("<p class=muted>Step the scene (play, or step) to measure its cost.</p>");
  } else {
    const share = per60 / FRAME_MS;
    lines.push('<div class="bar"><div class="' + (share > 1 ? "over" : "") + '" style="width:' +
      Math.min(100, 100 * share).toFixed(1) + '%"></div></div>');
    lines.push("<p>one step (every run beside the other) costs " + fmt(ms, 3) + " ms here (timed on " +
      S.costFrom + "); " +
      "1/60 s of simulated time is " + fmt(1 / 60 / S.h, 4) + " steps of h: " + fmt(per60, 3) +
      " ms, " + Math.round(100 * share) + " % of a 16.7 ms frame. Drawing takes " +
      fmt(S.drawMs, 2) + " ms a frame.</p>");
  }
  if (S.realtime.behind && S.playing) {
    lines.push('<p class="bad">Not real time: ×' + S.realtime.ratio.toFixed(2) +
      " (the page steps for at most " + fmt(stepBudget(), 2) + " ms a frame, what drawing leaves of " +
      BUDGET_MS + " ms; at h = " + fmt(S.h) +
      " s real time needs " + fmt(1 / S.h, 4) + " steps a second" +
      (ms !== null ? ", " + fmt(ms / S.h, 4) + " ms of stepping a second" : "") + ").</p>");
  }
  el("budget").innerHTML = lines.join("");
}

function banner() {
  const notes = [];
  S.panes.forEach(function (p) {
    if (p.kind !== "live") return;
    const who = esc(paneLabel(p)) + ": ";
    if (p.error) notes.push({ html: who + "stopped: " + esc(p.error), bad: true });
    const st = p.status;
    if (st.diverged) notes.push({ html: who + "<b>diverged at step " + st.diverged_at + "</b> (t = " +
      fmt(st.t, 6) + " s): " + esc(st.diverged) + " — reset, or a smaller h", bad: true });
    if (st.error) notes.push({ html: who + esc(st.error), bad: true });
    (st.warnings || []).forEach(function (w) { notes.push({ html: who + "warning: " + esc(w) }); });
    (st.notes || []).forEach(function (w) { notes.push({ html: who + esc(w) }); });
  });
  if (S.knobError) notes.push({ html: "that change was refused: " + esc(S.knobError), bad: true });
  if (S.realtime.behind && S.playing) notes.push({ html: "Not real time (×" +
    S.realtime.ratio.toFixed(2) + "): the steps of a frame take longer than the page allows " +
    "(frame budget, right)." });
  if (S.compare === "trace" && (Math.abs(S.h - S.scene.reference.dt) > 1e-9 * S.h ||
      S.panes[0].integrator !== recordedIntegrator())) {
    notes.push({ html: "The recorded run used " + esc(recordedIntegrator()) + " at h = " +
      fmt(S.scene.reference.dt) + " s: compare at those for the same motion." });
  }
  const key = JSON.stringify(notes);
  if (key !== S.bannerKey) { S.bannerKey = key; say(notes); }
}

// ---------------------------------------------------------------- the scene and its knobs
function loadScene(name) {
  S.scene = META.scenes.find(function (s) { return s.name === name; }) || META.scenes[0];
  S.doc = JSON.parse(S.scene.text);
  S.docText = S.goodText = S.scene.text;
  S.radii = null; S.cam = null; S.knobError = null;
  el("scene").value = S.scene.name;
  el("desc").textContent = S.scene.description || "";
  S.h = S.scene.dt || 0.01;
  S.hRange = [S.h / 16, S.h * 32];
  setH(S.h);
  S.omega = S.scene.omega || null;
  const p = S.panes[0];
  makeLive(p, S.main, S.scene.integrator || null);
  fillSelect(el("integ-0"), integratorsOf(S.main), p.integrator);
  const choices = compareChoices();
  if (!choices.some(function (c) { return c[0] === S.compare; })) S.compare = "none";
  el("compare").innerHTML = choices.map(function (c) {
    return '<option value="' + c[0] + '"' + (c[0] === S.compare ? " selected" : "") + ">" +
      esc(c[1]) + "</option>";
  }).join("");
  setCompare(S.compare);
  S.trails = p.n() <= 5;  // a few particles or bodies: their paths show by default
  el("c-trails").checked = S.trails;
  legend();
  knobs();
}
function legend() {
  S.panes.forEach(function (p) {
    const items = ['<span class="sw" style="color:' + COLORS[p.idx] + '">●</span>' +
      (p.idx === 0 ? "this run" : "the run beside it")];
    if (p.idx === 0 && S.compare === "trace") items.push('<span class="sw" style="color:' +
      COLORS[1] + '">○</span>the solution\'s recorded run, at the same t');
    if (!RIGID && S.scene.model.pinned.length) items.push('<span class="sw">▲</span>pinned');
    if (p.idx === 0 && S.panes[0].exact && S.panes[0].exact.length) {
      items.push('<span class="sw">◯</span>the exact motion');
    }
    if (RIGID && S.scene.model.hinges.length) items.push('<span class="sw">◆</span>hinge');
    el("legend-" + p.idx).innerHTML = items.join("<br>");
  });
}
function setH(h) {
  S.h = h;
  const r = S.hRange, v = 1000 * Math.log(h / r[0]) / Math.log(r[1] / r[0]);
  el("h").value = String(Math.round(Math.max(0, Math.min(1000, v))));
  el("h-num").value = String(+h.toPrecision(6));
}

function getAt(obj, path) { return path.reduce(function (o, k) { return o[k]; }, obj); }
function setAt(obj, path, v) { getAt(obj, path.slice(0, -1))[path[path.length - 1]] = v; }
const SKIP = { type: 1, i: 1, j: 1, seed: 1, body: 1, pin: 1, name: 1, description: 1 };
const RESETS = { count: 1, beads: 1, rows: 1, cols: 1, omega: 1, v: 1, x: 1, q: 1 };
// The scene's numbers a student turns: every number of its forces, contact settings and
// generators, its particles' and bodies' masses, a body's spin, its hinges' stiffness.
function knobList() {
  const out = [];
  const walk = function (v, path, label, resets) {
    const key = path[path.length - 1];
    if (typeof key === "string" && SKIP[key]) return;
    if (typeof v === "number") {
      out.push({ path: path, label: label, value: v, resets: resets || !!RESETS[key], key: key });
    } else if (Array.isArray(v)) {
      if (v.length <= 3 && v.every(function (x) { return typeof x === "number"; }) &&
          /^(center|goal|anchor|point|x|start|end|normal|size)$/.test(String(key))) return;
      v.forEach(function (x, k) { walk(x, path.concat([k]), label + "[" + k + "]", resets || !!RESETS[key]); });
    } else if (v && typeof v === "object") {
      Object.keys(v).forEach(function (k) {
        const sep = !label || label.endsWith(":") ? " " : ".";
        walk(v[k], path.concat([k]), label + sep + k, resets || !!RESETS[k]);
      });
    }
  };
  (S.doc.forces || []).forEach(function (f, k) { walk(f, ["forces", k], (f.type || "force") + " " + k + ":"); });
  ["contact", "rope", "cloth"].forEach(function (k) { if (S.doc[k]) walk(S.doc[k], [k], k + ":"); });
  (S.doc.emitters || []).forEach(function (e, k) {
    ["count", "m", "speed"].forEach(function (q) {
      if (typeof e[q] === "number") out.push({ path: ["emitters", k, q], label: "emitter " + k + ": " + q,
        value: e[q], resets: true, key: q });
    });
  });
  (S.doc.particles || []).slice(0, 4).forEach(function (pt, k) {
    if (typeof pt.m === "number") out.push({ path: ["particles", k, "m"], label: "particle " + k + ": m",
      value: pt.m, resets: false, key: "m" });
  });
  (S.doc.bodies || []).slice(0, 6).forEach(function (b, k) {
    if (typeof b.m === "number") out.push({ path: ["bodies", k, "m"], label: "body " + k + ": m",
      value: b.m, resets: false, key: "m" });
    if (Array.isArray(b.omega)) b.omega.forEach(function (w, d) {
      out.push({ path: ["bodies", k, "omega", d], label: "body " + k + ": omega[" + d + "]",
        value: w, resets: true, key: "omega" });
    });
  });
  (S.doc.hinges || []).forEach(function (hg, k) {
    if (typeof hg.beta === "number") out.push({ path: ["hinges", k, "beta"], label: "hinge " + k + ": beta",
      value: hg.beta, resets: false, key: "beta" });
  });
  return out;
}
function knobRange(k) {  // [min, max, log?, whole?] around the scene's value
  const v = k.value, whole = Number.isInteger(v) && /count|iterations|beads|rows|cols/.test(k.key);
  if (whole) return [1, Math.max(10, 4 * v), false, true];
  if (/restitution|beta/.test(k.key)) return [0, 1, false, false];
  if (/friction/.test(k.key)) return [0, 2, false, false];
  if (v > 0) return [v / 100, v * 100, true, false];
  if (v < 0) return [4 * v, -4 * v, false, false];
  return [-1, 1, false, false];
}
function knobs() {
  const list = knobList(), box = el("knobs");
  S.knobs = list;
  let group = null;
  const html = [];
  list.forEach(function (k, j) {
    const g = k.label.split(":")[0];
    if (g !== group) { group = g; html.push('<div class="group">' + esc(g) + "</div>"); }
    html.push('<label title="' + esc(k.path.join(".")) + (k.resets ? " (restarts the run)" : "") +
      '"><span>' + esc(k.label.split(":").slice(1).join(":").trim() || k.label) +
      (k.resets ? " ↺" : "") + '</span><input type="range" min="0" max="1000" data-j="' + j +
      '"><input type="number" step="any" data-j="' + j + '" value="' + k.value + '"></label>');
  });
  if (!list.length) html.push('<p class="note">This scene has no numbers to turn here.</p>');
  else html.push('<p class="note">↺: an initial value or a count: the run restarts from the ' +
    "scene's start. The others change the run as it goes.</p>");
  box.innerHTML = html.join("");
  list.forEach(function (k, j) { setKnobSlider(j, k.value); });
}
function setKnobSlider(j, v) {
  const k = S.knobs[j], r = knobRange(k);
  const s = document.querySelector('#knobs input[type=range][data-j="' + j + '"]');
  const f = r[2] ? Math.log(v / r[0]) / Math.log(r[1] / r[0]) : (v - r[0]) / (r[1] - r[0]);
  s.value = String(Math.round(1000 * Math.max(0, Math.min(1, f))));
}
function knobValue(j, slider) {
  const k = S.knobs[j], r = knobRange(k), f = slider / 1000;
  let v = r[2] ? r[0] * Math.pow(r[1] / r[0], f) : r[0] + f * (r[1] - r[0]);
  if (r[3]) v = Math.round(v); else v = +v.toPrecision(4);
  return v;
}
function setKnob(j, v) {
  const k = S.knobs[j];
  setAt(S.doc, k.path, v);
  k.value = v;
  S.pendingUpdate = k.resets || S.pendingUpdate === "reset" ? "reset" : "keep";
}
// The changed scene to every live run, once per frame: a new world, the same state (or
// the scene's start, for an initial value or a count). Refused: back to the last good one.
function applyUpdate() {
  const how = S.pendingUpdate;
  S.pendingUpdate = null;
  const text = JSON.stringify(S.doc);
  let err = null;
  S.panes.forEach(function (p) {
    if (p.kind === "live" && !err) err = p.sim.update(text);
  });
  if (err) {
    S.knobError = err;
    S.doc = JSON.parse(S.goodText);
    S.panes.forEach(function (p) { if (p.kind === "live") p.sim.update(S.goodText); });
    knobs();
    return;
  }
  S.knobError = null;
  S.cost.window = [];
  S.docText = S.goodText = text;
  S.radii = null;
  S.panes.forEach(function (p) { p.bg = null; });
  if (how === "reset") syncRuns();
  S.panes.forEach(function (p) { p.segment = null; });
}

// ---------------------------------------------------------------- the mouse
function mouse(p) {
  const cv = p.canvas;
  let drag = null;
  const at = function (e) { const r = cv.getBoundingClientRect(); return [e.clientX - r.left, e.clientY - r.top]; };
  cv.addEventListener("mousedown", function (e) {
    const m = at(e);
    e.preventDefault();
    if (p.kind === "live" && !e.shiftKey) {
      if (RIGID) {
        const hit = pick3(p, m[0], m[1]);
        if (hit) {
          const P = p.pose(hit.item);
          S.grab = { pane: p.idx, item: hit.item, at: applyT(P.R, sub3(hit.hit, P.x)), target: hit.hit };
          p.sim.grab(hit.item, S.grab.target, S.grab.at);
          drag = { kind: "grab" };
          return;
        }
      } else {
        const hit = pick2(p, m[0], m[1]);
        if (hit && hit.mark) { drag = { kind: "mark", path: hit.mark.path }; S.dragging = true; return; }
        if (hit) {
          S.grab = { pane: p.idx, item: hit.item, at: [0, 0, 0], target: world2(p, m[0], m[1]) };
          p.sim.grab(hit.item, S.grab.target, S.grab.at);
          drag = { kind: "grab" };
          return;
        }
      }
    }
    drag = { kind: RIGID && !e.shiftKey && e.button === 0 ? "turn" : "pan", from: m };
  });
  window.addEventListener("mousemove", function (e) {
    if (!drag) return;
    const m = at(e);
    if (drag.kind === "grab") {
      S.grab.target = RIGID ? target3(p, m[0], m[1], S.grab.target) : world2(p, m[0], m[1]);
      p.sim.grab(S.grab.item, S.grab.target, S.grab.at);
    } else if (drag.kind === "mark") {
      const w = world2(p, m[0], m[1]);
      setAt(S.doc, drag.path, [+w[0].toPrecision(6), +w[1].toPrecision(6)]);
      S.pendingUpdate = S.pendingUpdate || "keep";
    } else if (drag.kind === "turn") {
      S.cam.yaw -= (m[0] - drag.from[0]) * 0.008;
      S.cam.pitch = Math.max(-1.5, Math.min(1.5, S.cam.pitch + (m[1] - drag.from[1]) * 0.008));
      drag.from = m;
    } else {
      const dx = m[0] - drag.from[0], dy = m[1] - drag.from[1];
      if (RIGID) {
        const cam = camera(p), k = S.cam.dist / cam.F;
        S.cam.target = add3(S.cam.target, add3(mul3(cam.r, -dx * k), mul3(cam.u, dy * k)));
      } else S.panes.forEach(function (q) {
        if (q.view) { q.view.cx -= dx / q.view.s; q.view.cy += dy / q.view.s; q.bg = null; }
        S.userView = true;  // the camera is the user's now, until fit
      });
      drag.from = m;
    }
  });
  window.addEventListener("mouseup", function () {
    if (drag && drag.kind === "grab" && S.grab) {
      S.panes[S.grab.pane].sim.release();
      S.grab = null;
    }
    drag = null;
    S.dragging = false;
  });
  cv.addEventListener("wheel", function (e) {
    e.preventDefault();
    const k = Math.exp(-e.deltaY * 0.0015);
    if (RIGID) S.cam.dist /= k;
    else S.panes.forEach(function (q) { if (q.view) { q.view.s *= k; q.bg = null; } });
    S.userView = true;
  }, { passive: false });
}

// ---------------------------------------------------------------- controls
function controls() {
  el("b-play").addEventListener("click", function () { S.playing = !S.playing; S.debt = 0; playLabel(); });
  el("b-step").addEventListener("click", function () {
    S.playing = false; playLabel();
    stepRuns(1);
  });
  el("b-reset").addEventListener("click", function () { syncRuns(); });
  el("b-fit").addEventListener("click", function () { if (RIGID) fit3(); else fit2(); });
  el("h").addEventListener("input", function () {
    const r = S.hRange;
    setH(+(r[0] * Math.pow(r[1] / r[0], +el("h").value / 1000)).toPrecision(4));
  });
  el("h-num").addEventListener("change", function () {
    const v = +el("h-num").value;
    if (v > 0 && isFinite(v)) {
      S.hRange = [Math.min(S.hRange[0], v), Math.max(S.hRange[1], v)];
      setH(v);
    } else setH(S.h);
  });
  const integ = function (idx) {
    return function () {
      const p = S.panes[idx], sel = el("integ-" + idx);
      const err = p.sim.setIntegrator(sel.value);
      if (err) { S.knobError = err; fillSelect(sel, integratorsOf(p.side), p.integrator); return; }
      S.knobError = null;
      S.cost.window = [];
      p.integrator = sel.value;
      if (idx === 0 && S.compare !== "none") syncRuns(); else p.segment = null;
    };
  };
  el("integ-0").addEventListener("change", integ(0));
  el("integ-1").addEventListener("change", integ(1));
  el("compare").addEventListener("change", function () { setCompare(el("compare").value); });
  el("scene").innerHTML = META.scenes.map(function (s) {
    return "<option>" + esc(s.name) + "</option>";
  }).join("");
  el("scene").addEventListener("change", function () { loadScene(el("scene").value); });
  el("speed").innerHTML = [0.1, 0.25, 0.5, 1, 2, 4].map(function (v) {
    return '<option value="' + v + '"' + (v === 1 ? " selected" : "") + ">" +
      (v === 1 ? "real time" : "×" + v) + "</option>";
  }).join("");
  el("speed").addEventListener("change", function () { S.speed = +el("speed").value; });
  el("c-trails").addEventListener("change", function () {
    S.trails = el("c-trails").checked;
    S.panes.forEach(function (p) { p.trail = []; });
  });
  el("knobs").addEventListener("input", function (e) {
    const j = +e.target.dataset.j;
    if (e.target.type === "range") {
      const v = knobValue(j, +e.target.value);
      document.querySelector('#knobs input[type=number][data-j="' + j + '"]').value = v;
      setKnob(j, v);
    }
  });
  el("knobs").addEventListener("change", function (e) {
    if (e.target.type !== "number") return;
    const j = +e.target.dataset.j, v = +e.target.value;
    if (!isFinite(v)) return;
    setKnobSlider(j, v);
    setKnob(j, v);
  });
  window.addEventListener("keydown", function (e) {
    if (e.target.tagName === "INPUT" || e.target.tagName === "SELECT") return;
    if (e.key === " ") { e.preventDefault(); el("b-play").click(); }
    else if (e.key === "ArrowRight") el("b-step").click();
    else if (e.key === "r" || e.key === "R") el("b-reset").click();
    else if (e.key === "f" || e.key === "F") el("b-fit").click();
  });
  window.addEventListener("resize", function () {
    S.panes.forEach(function (p) { p.resize(); });
    if (RIGID) fit3(); else fit2();
  });
  el("help").textContent = (RIGID
    ? "Drag a body to pull it (a spring to the cursor); drag elsewhere to turn the camera, Shift+drag to move it, wheel to zoom."
    : "Drag a particle to pull it (a spring to the cursor), drag a marked point of the scene to move it; drag elsewhere to move the camera, wheel to zoom.") +
    " Space play/pause · → one step · R reset · F fit. Your code runs here as WebAssembly, built from " +
    META.built.from + " by " + META.built.command + ".";
}
function playLabel() { el("b-play").textContent = S.playing ? "pause" : "play"; }

// ---------------------------------------------------------------- start
async function start() {
  const factories = window.WB_LIVE_MODULES || {};
  for (const side of META.modules) {
    if (!factories[side]) throw new Error("the " + side + " module is missing from the page");
    S.modules[side] = await factories[side]({
      print: function (t) { console.log(t); },
      printErr: function (t) { console.warn(t); } });
    S.info[side] = JSON.parse(S.modules[side].ccall("wb_live_info", "string", [], []));
  }
  S.main = META.main;
  S.frameTimes = [];
  S.panes = [new Pane(0), new Pane(1)];
  el("title").textContent = META.lab + " — live";
  el("subtitle").textContent = (S.main === "student" ? "your code (" : "the solution (") +
    META.built.from + ")";
  document.title = META.lab + " — live";
  controls();
  S.panes.forEach(function (p) { mouse(p); p.resize(); });
  loadScene(META.default_scene);
  playLabel();
  S.ready = true;
  requestAnimationFrame(frame);
}

// What tools/live-check reads and does (docs/live.md, "The browser check").
window.wbLive = {
  get ready() { return S.ready; },
  lab: META.lab, kind: META.kind,
  scenes: META.scenes.map(function (s) { return s.name; }),
  load: function (name) { loadScene(name); },
  // Play (true) or pause (false), as the play button does.
  play: function (on) { S.playing = !!on; S.debt = 0; playLabel(); },
  run: function (i) {
    const p = S.panes[i || 0];
    if (!p || !p.ro) return null;
    const g = growth(p);
    return { kind: p.kind, side: p.side, integrator: p.integrator, h: S.h, t: p.ro[R.T],
      steps: p.ro[R.STEPS], E: p.ro[R.E], K: p.ro[R.K], V: p.ro[R.V],
      p: [p.ro[R.PX], p.ro[R.PY], p.ro[R.PZ]], L: [p.ro[R.LX], p.ro[R.LY], p.ro[R.LZ]],
      growth: g ? g.factor : null, growthSteps: g ? g.steps : 0, exact: p.ro[R.EXACT],
      status: p.status, error: p.error || null, n: p.n() };
  },
  position: function (i, item) { const p = S.panes[i || 0]; return Array.from(p.pos(item)); },
  // The page coordinates (CSS pixels) where item's centre is drawn in pane i.
  screen: function (i, item) {
    const p = S.panes[i || 0], r = p.canvas.getBoundingClientRect();
    if (RIGID) {
      const q = project(camera(p), p.pose(item).x);
      return q ? [r.left + q[0], r.top + q[1]] : null;
    }
    const q = p.pos(item);
    return [r.left + sx(p, q[0]), r.top + sy(p, q[1])];
  },
  // What the cursor holds: the item, the target and where the held point is now.
  // The item of pane i drawn nearest the middle of its canvas (one to drag).
  central: function (i) {
    const p = S.panes[i || 0], n = p.n();
    let best = null, bd = Infinity;
    for (let k = 0; k < n; k++) {
      const q = this.screen(i, k), r = p.canvas.getBoundingClientRect();
      if (!q) continue;
      const d = Math.hypot(q[0] - (r.left + r.width / 2), q[1] - (r.top + r.height / 2));
      if (d < bd) { bd = d; best = k; }
    }
    return best;
  },
  canvasRect: function (i) {
    const r = S.panes[i || 0].canvas.getBoundingClientRect();
    return [r.left, r.top, r.right, r.bottom];
  },
  grabbed: function () {
    if (!S.grab) return null;
    const p = S.panes[S.grab.pane];
    let point = p.pos(S.grab.item);
    if (RIGID) { const P = p.pose(S.grab.item); point = add3(P.x, apply(P.R, S.grab.at)); }
    return { item: S.grab.item, target: Array.from(S.grab.target), point: Array.from(point) };
  },
  // The scene's movable points: label, path in the scene, world and page coordinates.
  marks: function () {
    if (RIGID) return [];
    const p = S.panes[0], r = p.canvas.getBoundingClientRect();
    return marks().map(function (m) {
      return { label: m.label, path: m.path, at: m.at,
        screen: [r.left + sx(p, m.at[0]), r.top + sy(p, m.at[1])] };
    });
  },
  // True while the mouse holds a marked point of the scene (a press on it, not yet released).
  holdingMark: function () { return !!S.dragging; },
  doc: function () { return JSON.parse(S.docText); },
  frames: function () { return S.frames; },
  integrators: function () { return integratorsOf(S.main); },
  // The world point under page point [X, Y] in the first run's view (2D).
  worldOf: function (P) {
    const p = S.panes[0], r = p.canvas.getBoundingClientRect();
    return world2(p, P[0] - r.left, P[1] - r.top);
  },
  // A knob turned as a user types into its box: false when the scene has no such number.
  setKnob: function (path, value) {
    const j = S.knobs.findIndex(function (k) { return JSON.stringify(k.path) === JSON.stringify(path); });
    if (j < 0) return false;
    const box = document.querySelector('#knobs input[type=number][data-j="' + j + '"]');
    box.value = String(value);
    box.dispatchEvent(new Event("change", { bubbles: true }));
    return true;
  },
  knobs: function () { return S.knobs.map(function (k) { return { path: k.path, value: k.value }; }); },
  fps: function () {
    const t = S.frameTimes, k = t.length;
    return k > 10 ? 1000 * (k - 1) / (t[k - 1] - t[0]) : null;
  },
  stepMs: stepCostMs,
  drawMs: function () { return S.drawMs; },
  realtime: function () { return S.realtime; },
  banner: function () { return el("banner").textContent; },
  // Times n steps of a scene from its start in a fresh Sim of the main module, `repeats`
  // times (wall ms per step, the fastest): tools/live-check --bench against bench_live.
  bench: function (scene, integrator, h, n, repeats) {
    const sim = new Sim(S.modules[S.main], S.main), sc = META.scenes.find(function (s) { return s.name === scene; });
    const err = sim.load(sc.file, sc.text) || (integrator ? sim.setIntegrator(integrator) : null);
    if (err) return { error: err };
    let best = Infinity;
    for (let r = 0; r < (repeats || 5); r++) {
      sim.reset();
      const t0 = performance.now();
      const k = sim.step(h || sc.dt, n);
      const ms = performance.now() - t0;
      if (k !== n) return { error: "stopped after " + k + " steps", status: sim.status() };
      best = Math.min(best, ms / n);
    }
    sim.free();
    return { ms: best };
  }
};

start().catch(function (e) { fail("the page could not start: " + (e && e.message || e)); });
