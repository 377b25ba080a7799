// tools/view's page, part 6 of 6: the frame budget, the picked particle, the playhead,
// playing, the controls, the test hooks and the start.
// ---------------------------------------------------------------- budget and inspector
function budget() {
  const b = META.budget, box = el("budget");
  if (R1.summary.stub) {  // a stub's cost is not the lab's: nothing to claim
    box.innerHTML = '<p class="muted">Not given: this run ran stubs (its summary\'s warnings, ' +
      "above), so its cost is not what the lab's step costs.</p>";
    return;
  }
  if (!b.available) {
    box.innerHTML = '<p class="muted">Not available: ' + esc(b.why) + ".</p>";
    return;
  }
  const pct = 100 * b.share;
  const fit = b.fit === null ? "—" : b.fit.toLocaleString("en");
  let text = "<p>The step loop took <b>" + esc(fmt(b.ms_per_frame, 3)) + " ms</b> of CPU per "
    + "simulated 1/60 s (" + esc(fmt(b.steps_per_frame, 3)) + " steps of dt), "
    + "<b>" + esc(fmt(pct, 3)) + " %</b> of a 16.7 ms frame at 60 Hz.</p>"
    + '<div class="bar"><div class="' + (b.share > 1 ? "over" : "") + '" style="width:'
    + Math.min(100, pct).toFixed(2) + '%"></div></div>'
    + "<p>At this cost one frame holds about <b>" + esc(fit) + "</b> " + esc(b.what)
    + " (this run: " + esc(b.n) + "; cost taken to grow as " + esc(b.scaling) + ").</p>"
    + '<p class="muted">From the summary: cpu_s = ' + esc(fmt(b.cpu_s, 4)) + " s over t = "
    + esc(fmt(b.t, 6)) + " s (" + esc(b.steps) + " steps). cpu_s includes writing the trace: "
    + "a run without --out (or with a larger --every) times the step loop alone.</p>";
  const s2 = R2 ? R2.summary : {};
  if (isFinite(s2.cpu_s) && s2.t > 0) {
    text += '<p class="muted">' + esc(R2.label) + ": " + esc(fmt(s2.cpu_s * 1000 / (s2.t * 60), 3))
      + " ms per simulated 1/60 s.</p>";
  }
  box.innerHTML = text;
}
const PICK_HINT = '<p class="muted">Click a particle or body to follow its numbers.</p>';
function inspect() {  // the picked particle's or body's numbers at the playhead
  if (S.pick === null) return;
  const k = S.frame, i = S.pick;
  const k2 = R2 ? frameAt(R2, R1.t[k]) : null;
  const row = function (name, a, b) {
    return "<tr><td>" + esc(name) + "</td><td>" + a + "</td>" + (b ? "<td>" + b + "</td>" : "")
      + "</tr>";
  };
  const rows = [];
  if (RIGID) {
    const groups = [["x, y, z", 0, 3], ["qw, qx, qy, qz", 3, 7], ["vx, vy, vz", 7, 10],
      ["wx, wy, wz", 10, 13]];
    const vals = function (run, kk, a, b) {
      const out = [];
      for (let d = a; d < b; d++) out.push(fmt(value(run, kk, i, d), 7));
      return out.join(", ");
    };
    if (k2 !== null) rows.push(row("", esc(R1.label), esc(R2.label)));
    groups.forEach(function (g) {
      rows.push(row(g[0], vals(R1, k, g[1], g[2]), k2 !== null ? vals(R2, k2, g[1], g[2]) : ""));
    });
  } else {
    const x = value(R1, k, i, 0), y = value(R1, k, i, 1);
    rows.push(row("x, y", fmt(x, 7) + ", " + fmt(y, 7)));
    if (C >= 4) {  // the velocity, where the page kept it (docs/view.md, "Large runs")
      const vx = value(R1, k, i, 2), vy = value(R1, k, i, 3);
      rows.push(row("vx, vy", fmt(vx, 7) + ", " + fmt(vy, 7) + " (|v| " +
        fmt(Math.hypot(vx, vy), 5) + " m/s)"));
    } else rows.push(row("vx, vy", "not kept: with them the page would hold fewer written steps"));
    if (SCENE) rows.push(row("radius", fmt(SCENE.radii[i], 6)));
    if (k2 !== null) {
      const x2 = value(R2, k2, i, 0), y2 = value(R2, k2, i, 1);
      rows.push(row(R2.label, fmt(x2, 7) + ", " + fmt(y2, 7) + " (t = " + fmtT(R2.t[k2]) + ")"));
      rows.push(row("distance", fmt(Math.hypot(x - x2, y - y2), 4) + " m"));
    }
    if (EXACT) {
      const ex = EXACT.pos[(k * N + i) * 2] + ORIGIN[0];
      const ey = EXACT.pos[(k * N + i) * 2 + 1] + ORIGIN[1];
      rows.push(row("exact", fmt(ex, 7) + ", " + fmt(ey, 7)));
      rows.push(row("error", fmt(Math.hypot(x - ex, y - ey), 4) + " m"));
    }
  }
  el("inspect").innerHTML = "<p><b>" + (RIGID ? "Body " : "Particle ") + i + "</b> at t = "
    + fmtT(R1.t[k]) + ' <button id="b-unpick">drop</button></p><table>' + rows.join("")
    + '</table><p class="muted">Values stored as 32-bit floats (7 digits); the CSV has all 17.</p>';
  el("b-unpick").addEventListener("click", function () {
    S.pick = null; S.dirty = true; el("inspect").innerHTML = PICK_HINT;
  });
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
    s += "   │ " + R2.label + ": t = " + fmtT(R2.t[k2]);
    if (R2.steps) s += ", step " + R2.steps[k2];
    if (R2.diverged && k2 === R2.frames - 1 && R1.t[k] >= R2.t[k2]) s += " (ended: diverged)";
  }
  s += S.playing ? "   ▶ " + (S.everyFrame ? "every written step" : "×" + fmt(S.speed, 3)) : "";
  if (S.offView) s += "   " + S.offView + " out of view (arrows at the edge)";
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
  for (let k = 0; k < R1.frames; k++) {
    if (Math.abs(R1.steps[k] - step) < Math.abs(R1.steps[best] - step)) best = k;
  }
  setFrame(best);
}
function drawTicks() {
  const c = el("ticks"), g = c.getContext("2d");
  const r = c.getBoundingClientRect();
  c.width = Math.round(r.width * DPR); c.height = Math.round(r.height * DPR);
  g.setTransform(DPR, 0, 0, DPR, 0, 0); g.clearRect(0, 0, r.width, r.height);
  RUNS.forEach(function (run) {
    if (!run.diverged || run.diverged.t === null) return;
    const span = R1.t[R1.frames - 1] - R1.t[0] || 1;
    const x = 8 + (run.diverged.t - R1.t[0]) / span * (r.width - 16);  // the range's thumb inset
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
      + (v === auto && v !== 1 ? " (whole run in 10 s)" : v === 1 ? " (real time)" : "")
      + "</option>";
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
    const typing = ev.target.tagName === "INPUT" && ev.target.type !== "range"
      && ev.target.type !== "checkbox";
    if (typing) return;
    const k = ev.key;
    if (k === " ") { play(); ev.preventDefault(); }
    else if (k === "ArrowRight" || k === "ArrowLeft") {
      play(false);
      setFrame(S.frame + (k === "ArrowRight" ? 1 : -1) * (ev.shiftKey ? 10 : 1));
      ev.preventDefault();
    }
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
    else {
      const x = value(R1, S.frame, i, 0), y = value(R1, S.frame, i, 1);
      p = isFinite(x + y) ? [sx(x), sy(y)] : null;
    }
    if (!p) continue;
    const d = Math.hypot(p[0] - mx, p[1] - my) - (RIGID ? 0 : radiusPx(i));
    if (d < bd) { bd = d; best = i; }
  }
  S.pick = best; S.dirty = true;
  if (best === null) el("inspect").innerHTML = PICK_HINT;
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
  // Positions drawn at the current frame: world coordinates (as stored) and page pixels.
  drawn: function (ids) {
    const k = S.lastDrawn.frame;
    const r = canvas.getBoundingClientRect();
    return ids.map(function (i) {
      const p = [];
      for (let d = 0; d < ORIGIN.length; d++) p.push(value(R1, k, i, d));
      let s = RIGID ? S.lastDrawn.screen[i] : [sx(p[0]), sy(p[1])];
      s = s ? [s[0] + r.left, s[1] + r.top] : null;
      const q = RIGID ? [3, 4, 5, 6].map(function (d) { return value(R1, k, i, d); }) : null;
      return { id: i, world: p, q: q, screen: s, radius_px: RIGID ? 3.5 : radiusPx(i) };
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
    const at = { left: r.left, top: r.top, W: W, H: H };
    if (!RIGID) {
      return Object.assign(at, { kind: "2d", cx: S.view2.cx, cy: S.view2.cy, s: S.view2.s });
    }
    const c = camera();
    return Object.assign(at, { kind: "3d", eye: c.eye, r: c.r, u: c.u, f: c.f, F: c.F });
  },
  colors: function () {
    return { run: COLORS.run, com: COLORS.com, cursor: COLORS.cursor, diverged: COLORS.diverged };
  },
  // Each chart: its cursor and divergence marks in page pixels, and its time axis.
  charts: function () {
    return charts.map(function (c) {
      const r = c.canvas.getBoundingClientRect(), m = c.margins;
      return { id: c.opts.id, title: c.title,
        cursor: c.cursor ? { t: c.cursor.t, px: c.cursor.px + r.left } : null,
        marks: (c.marks || []).map(function (x) {
          return { t: x.t, step: x.step, px: x.px + r.left };
        }),
        top: r.top + m.t, bottom: r.bottom - m.b,
        t_of_px: [c.tOf(m.l), c.tOf(c.w - m.r)], px_range: [m.l + r.left, c.w - m.r + r.left] };
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
