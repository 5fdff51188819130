// The replay player of `usar replay` (docs/replay.md). Everything it shows comes from the
// recording in this page: metadata in #meta (JSON), the sampled trial in #data (base64 of raw
// deflate of zigzag LEB128 varints, delta-coded per robot along time). Nothing is simulated
// here. The state shown is written as JSON into #replay-state for tests.
(() => {
  'use strict';

  // ---- errors: caught, shown, and reported in #replay-state --------------------------------
  const errors = [];
  const stateEl = document.getElementById('replay-state');
  const fatalEl = document.getElementById('fatal');
  function noteError(msg) {
    errors.push(String(msg));
    stateEl.textContent = JSON.stringify({ ready: false, errors });
  }
  window.addEventListener('error', (e) => noteError(e.message || e));
  window.addEventListener('unhandledrejection', (e) => noteError(e.reason && e.reason.message ? e.reason.message : e.reason));
  const consoleError = console.error.bind(console);
  console.error = (...args) => { noteError(args.map(String).join(' ')); consoleError(...args); };
  function fatal(msg) {
    fatalEl.hidden = false;
    fatalEl.textContent = 'This replay cannot be shown: ' + msg;
    noteError(msg);
  }

  const meta = JSON.parse(document.getElementById('meta').textContent);
  const R = meta.robots.length;
  const S = meta.samples;
  const K = meta.tasks.length;
  const CH = {};
  meta.channels.forEach((c, i) => { CH[c.name] = i; });
  const [F_LEAVING, F_PICKING, F_CLAIM, F_HELD, F_BLOCKED] = meta.flags;
  const duration = meta.total_steps * meta.dt_s;
  const sampleTime = (i) => Math.min(i * meta.every_steps, meta.total_steps) * meta.dt_s;
  const rescueeOffset = [];
  let totalRescuees = 0;
  for (const t of meta.tasks) { rescueeOffset.push(totalRescuees); totalRescuees += t.rescuees.length; }

  // ---- decoding -------------------------------------------------------------------------------
  let channels = null; // Int32Array per channel, sample-major
  let changes = null; // { sample, index, code } typed arrays

  function decodeStream(bytes) {
    let pos = 0;
    const n = bytes.length;
    function rv() {
      if (pos >= n) throw new Error('recording truncated at byte ' + pos);
      let b = bytes[pos++];
      if (b < 128) return b;
      let u = b & 127;
      let m = 128;
      do {
        if (pos >= n) throw new Error('recording truncated at byte ' + pos);
        b = bytes[pos++];
        u += (b & 127) * m;
        m *= 128;
      } while (b >= 128);
      return u;
    }
    const unzig = (u) => (u % 2 === 1 ? -(u + 1) / 2 : u / 2);
    const out = meta.channels.map(() => new Int32Array(S * R));
    for (const arr of out) {
      for (let r = 0; r < R; r++) {
        let v = 0;
        for (let i = 0; i < S; i++) {
          v += unzig(rv());
          arr[i * R + r] = v;
        }
      }
    }
    const count = rv();
    const sample = new Int32Array(count);
    const index = new Int32Array(count);
    const code = new Uint8Array(count);
    let s = 0;
    for (let c = 0; c < count; c++) {
      s += rv();
      sample[c] = s;
      index[c] = rv();
      code[c] = rv();
    }
    if (pos !== n) throw new Error((n - pos) + ' bytes left over in the recording');
    channels = out;
    changes = { sample, index, code };
  }

  async function load() {
    if (typeof DecompressionStream === 'undefined') {
      throw new Error('this browser has no DecompressionStream (use a current Chrome, Firefox or Safari)');
    }
    const text = document.getElementById('data').textContent.trim();
    const raw = atob(text);
    const packed = new Uint8Array(raw.length);
    for (let i = 0; i < raw.length; i++) packed[i] = raw.charCodeAt(i);
    const stream = new Blob([packed]).stream().pipeThrough(new DecompressionStream('deflate-raw'));
    const bytes = new Uint8Array(await new Response(stream).arrayBuffer());
    decodeStream(bytes);
  }

  // ---- elements -------------------------------------------------------------------------------
  const $ = (id) => document.getElementById(id);
  const mapImg = $('map');
  const layer = $('layer');
  const ctx = layer.getContext('2d');
  const slider = $('slider');
  const playBtn = $('play');
  const speedSel = $('speed');
  const timeline = $('timeline');
  const tctx = timeline.getContext('2d');
  const hoverTip = $('hover');
  const markTip = $('mark-tip');
  const SPEEDS = [1, 2, 4, 8, 16, 32, 64];

  // ---- view state -----------------------------------------------------------------------------
  let t = 0;
  let playing = false;
  let speed = 8;
  let selected = -1;
  let lastFrame = 0;
  let scale = { sx: 1, sy: 1, w: 0, h: 0, dpr: 1 };
  const resCode = new Uint8Array(totalRescuees);
  let resApplied = 0; // changes applied to resCode
  let resSample = -1; // the sample resCode shows

  const fmt = (v, d = 1) => Number(v).toFixed(d);
  const taskName = (g) => (g > 0 && g <= K ? meta.tasks[g - 1].name : null);
  const groupColor = (g) => (g > 0 && g <= K ? meta.tasks[g - 1].color : meta.no_group_color);

  function sampleAt(time) {
    const step = meta.every_steps * meta.dt_s;
    let i0 = Math.min(Math.max(Math.floor(time / step + 1e-9), 0), S - 1);
    while (i0 > 0 && sampleTime(i0) > time + 1e-9) i0--;
    const i1 = Math.min(i0 + 1, S - 1);
    const span = sampleTime(i1) - sampleTime(i0);
    const frac = span > 0 ? Math.min(Math.max((time - sampleTime(i0)) / span, 0), 1) : 0;
    return { i0, i1, frac };
  }
  const val = (ch, i, r) => channels[CH[ch]][i * R + r];
  function position(at, r) {
    const { i0, i1, frac } = at;
    const x0 = val('x_cm', i0, r), y0 = val('y_cm', i0, r);
    const x1 = val('x_cm', i1, r), y1 = val('y_cm', i1, r);
    return [(x0 + (x1 - x0) * frac) / 100, (y0 + (y1 - y0) * frac) / 100];
  }
  function rescueesAt(i) {
    if (i < resSample) { resCode.fill(0); resApplied = 0; }
    while (resApplied < changes.sample.length && changes.sample[resApplied] <= i) {
      resCode[changes.index[resApplied]] = changes.code[resApplied];
      resApplied++;
    }
    resSample = i;
  }
  function roundAt(time) {
    let k = -1;
    for (let i = 0; i < meta.rounds.length; i++) if (meta.rounds[i].start_s <= time + 1e-9) k = i;
    return k;
  }
  function rescuedAt(time) {
    const total = new Array(K).fill(0);
    for (const m of meta.marks) {
      if (m.t > time + 1e-9) break;
      if (m.k === 5 && m.task !== null) total[m.task] += m.v;
    }
    return total;
  }

  // ---- drawing --------------------------------------------------------------------------------
  // Zoom: the canvas draws at `zoom` around the pan offset; the map picture follows by a CSS
  // transform.
  let zoom = 1;
  let pan = { x: 0, y: 0 };
  const X = (x) => (x - meta.map.x0_m) * scale.sx * zoom + pan.x;
  const Y = (y) => (meta.map.y1_m - y) * scale.sy * zoom + pan.y;
  function setZoom(z, cx, cy) {
    const nz = Math.min(Math.max(z, 1), 24);
    pan.x = cx - ((cx - pan.x) * nz) / zoom;
    pan.y = cy - ((cy - pan.y) * nz) / zoom;
    zoom = nz;
    clampPan();
  }
  function clampPan() {
    pan.x = Math.min(0, Math.max(pan.x, scale.w - scale.w * zoom));
    pan.y = Math.min(0, Math.max(pan.y, scale.h - scale.h * zoom));
    mapImg.style.transform = zoom === 1 ? '' : 'translate(' + pan.x + 'px,' + pan.y + 'px) scale(' + zoom + ')';
    render();
  }

  function resize() {
    const oldW = scale.w;
    const w = mapImg.clientWidth;
    const h = mapImg.clientHeight || (w * meta.map.height_px) / meta.map.width_px;
    const dpr = window.devicePixelRatio || 1;
    scale = {
      sx: w / (meta.map.x1_m - meta.map.x0_m),
      sy: h / (meta.map.y1_m - meta.map.y0_m),
      w, h, dpr,
    };
    // Keep the zoomed view on the same place when the page is resized.
    const ratio = oldW > 0 ? w / oldW : 1;
    pan = { x: pan.x * ratio, y: pan.y * ratio };
    mapImg.style.transform = zoom === 1 ? '' : 'translate(' + pan.x + 'px,' + pan.y + 'px) scale(' + zoom + ')';
    layer.style.width = w + 'px';
    layer.style.height = h + 'px';
    layer.width = Math.round(w * dpr);
    layer.height = Math.round(h * dpr);
    const tw = timeline.clientWidth;
    const th = meta.mark_kinds.length * 14 + 16;
    timeline.style.height = th + 'px';
    timeline.width = Math.round(tw * dpr);
    timeline.height = Math.round(th * dpr);
    render();
  }

  function robotRadiusPx(r) {
    const k = meta.kinds[meta.robots[r]];
    const min = meta.labels ? 6 : 2.2;
    return Math.max(k.radius_m * scale.sx * zoom, min);
  }

  function shapePath(c, role, x, y, rad) {
    c.beginPath();
    if (role === 'Supplier') {
      const s = rad * 0.9;
      c.rect(x - s, y - s, 2 * s, 2 * s);
    } else if (role === 'Observer') {
      const s = rad * 1.25;
      c.moveTo(x, y - s); c.lineTo(x + s, y); c.lineTo(x, y + s); c.lineTo(x - s, y); c.closePath();
    } else {
      c.arc(x, y, rad, 0, 2 * Math.PI);
    }
  }

  function drawRescuees(at) {
    rescueesAt(at.i0);
    const rad = Math.max(0.25 * scale.sx * zoom, meta.labels ? 2.2 : 1.4);
    for (let k = 0; k < K; k++) {
      const task = meta.tasks[k];
      for (let i = 0; i < task.rescuees.length; i++) {
        const code = resCode[rescueeOffset[k] + i];
        if (code === 2 || code === 3 || code === 4) continue; // carried, delivered, abandoned
        const [x, y] = task.rescuees[i];
        const px = X(x), py = Y(y);
        if (code === 5) { // unreachable
          ctx.strokeStyle = '#8a8a8a'; ctx.lineWidth = 1;
          ctx.beginPath(); ctx.moveTo(px - rad, py - rad); ctx.lineTo(px + rad, py + rad);
          ctx.moveTo(px + rad, py - rad); ctx.lineTo(px - rad, py + rad); ctx.stroke();
          continue;
        }
        ctx.fillStyle = code === 1 ? task.color : meta.rescuee_color;
        ctx.beginPath(); ctx.arc(px, py, code === 1 ? rad * 1.3 : rad, 0, 2 * Math.PI); ctx.fill();
      }
    }
  }

  function drawTrail(at, r) {
    const from = Math.max(0, at.i0 - Math.round(30 * meta.hz));
    ctx.strokeStyle = groupColor(val('group', at.i0, r));
    ctx.globalAlpha = 0.7;
    ctx.lineWidth = 2;
    ctx.setLineDash([]);
    ctx.beginPath();
    for (let i = from; i <= at.i0; i++) {
      const x = X(val('x_cm', i, r) / 100), y = Y(val('y_cm', i, r) / 100);
      if (i === from) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    }
    const [px, py] = position(at, r);
    ctx.lineTo(X(px), Y(py));
    ctx.stroke();
    ctx.globalAlpha = 1;
  }

  function drawBar(x, y, w, frac, color) {
    ctx.fillStyle = 'rgba(30,30,30,0.55)';
    ctx.fillRect(x - 0.5, y - 0.5, w + 1, 4);
    ctx.fillStyle = color;
    ctx.fillRect(x, y, w * Math.min(Math.max(frac, 0), 1), 3);
  }

  function drawRobot(at, r) {
    const kind = meta.kinds[meta.robots[r]];
    const [wx, wy] = position(at, r);
    const x = X(wx), y = Y(wy);
    const rad = robotRadiusPx(r);
    const g = val('group', at.i0, r);
    const flags = val('flags', at.i0, r);
    if (kind.aerial) {
      ctx.strokeStyle = groupColor(g); ctx.lineWidth = 1.5;
      ctx.beginPath(); ctx.arc(x, y, rad * 1.8 + (kind.role === 'Observer' ? 1.5 : 0), 0, 2 * Math.PI); ctx.stroke();
    }
    if (flags & (F_HELD | F_BLOCKED)) {
      ctx.strokeStyle = flags & F_HELD ? '#d62728' : '#ff7f0e';
      ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(x, y, rad + 3, 0, 2 * Math.PI); ctx.stroke();
    }
    shapePath(ctx, kind.role, x, y, rad);
    ctx.fillStyle = groupColor(g);
    ctx.fill();
    ctx.strokeStyle = '#1d2129'; ctx.lineWidth = 1;
    ctx.stroke();
    if (val('load', at.i0, r) > 0) {
      ctx.fillStyle = '#ffffff';
      ctx.beginPath(); ctx.arc(x, y, Math.max(rad * 0.42, 1.2), 0, 2 * Math.PI); ctx.fill();
    }
    return [x, y, rad];
  }

  function render() {
    if (!channels) return;
    const at = sampleAt(t);
    ctx.setTransform(scale.dpr, 0, 0, scale.dpr, 0, 0);
    ctx.clearRect(0, 0, scale.w, scale.h);
    drawRescuees(at);
    if (selected >= 0) drawTrail(at, selected);
    const placed = new Array(R);
    for (let r = 0; r < R; r++) placed[r] = drawRobot(at, r);
    // Ids and bars for small teams, or once robots are drawn large enough (zoomed in).
    const showBars = meta.labels || 0.3 * scale.sx * zoom >= 5;
    ctx.font = '600 10px system-ui, sans-serif';
    ctx.textAlign = 'center';
    for (let r = 0; r < R; r++) {
      if (!(showBars || r === selected)) continue;
      const [x, y, rad] = placed[r];
      const kind = meta.kinds[meta.robots[r]];
      const top = y - rad * (kind.aerial ? 1.8 : 1) - 10;
      const bw = Math.max(2 * rad, 16);
      drawBar(x - bw / 2, top, bw, val('energy_centi_pct', at.i0, r) / 10000, '#f2b705');
      drawBar(x - bw / 2, top + 4, bw, val('hp_centi_pct', at.i0, r) / 10000, '#3aa655');
      ctx.fillStyle = 'rgba(255,255,255,0.85)';
      const label = String(r);
      const lw = ctx.measureText(label).width + 4;
      const ly = y + rad * (kind.aerial ? 1.8 : 1) + 2;
      ctx.fillRect(x - lw / 2, ly, lw, 11);
      ctx.fillStyle = '#1d2129';
      ctx.textBaseline = 'top';
      ctx.fillText(label, x, ly + 1);
    }
    if (selected >= 0) {
      const [x, y, rad] = placed[selected];
      ctx.strokeStyle = '#111'; ctx.lineWidth = 1.5; ctx.setLineDash([3, 2]);
      ctx.beginPath(); ctx.arc(x, y, rad * 2.4 + 4, 0, 2 * Math.PI); ctx.stroke();
      ctx.setLineDash([]);
    }
    renderSide(at);
    drawTimeline();
    writeState(at);
  }

  // ---- side panel -----------------------------------------------------------------------------
  function stateText(at, r) {
    const p = meta.phases[val('phase', at.i0, r)];
    const flags = val('flags', at.i0, r);
    const load = val('load', at.i0, r);
    const role = meta.kinds[meta.robots[r]].role;
    const carry = load > 0 ? 'carrying ' + load + ' rescuee' + (load > 1 ? 's' : '') : '';
    let s;
    switch (p) {
      case 'AtStart': s = 'at its start, waiting for the next round'; break;
      case 'ToSearchArea': s = 'travelling to the search area'; break;
      case 'Searching':
        if (flags & F_PICKING) s = 'rescuing (picking a rescuee up)';
        else if (flags & F_CLAIM) s = 'searching: driving to a rescuee';
        else s = role === 'Observer' ? 'observing the search area' : 'searching';
        if (carry) s += ', ' + carry;
        break;
      case 'Waiting': s = 'waiting in the search area' + (carry ? ', ' + carry : ''); break;
      case 'ToDropOff':
        s = (carry || 'going') + ' to the drop-off' + (flags & F_LEAVING ? ', then to rest' : '');
        break;
      case 'ToStart': s = 'returning to its start'; break;
      case 'ToRest': s = 'going to recharge'; break;
      case 'Recharging': s = 'recharging'; break;
      case 'RestToStart': s = 'rested, returning to its start'; break;
      default: s = p;
    }
    if (flags & F_HELD) s += ' · held by the resolver';
    else if (flags & F_BLOCKED) s += ' · blocked';
    return s;
  }

  const esc = (s) => String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
  function bar(frac, color) {
    return '<span class="bar"><i style="width:' + fmt(Math.min(Math.max(frac, 0), 1) * 100, 1) + '%;background:' + color + '"></i></span>';
  }

  let lastSide = '';
  function renderSide(at) {
    $('time').textContent = fmt(t, 1);
    const k = roundAt(t);
    let roundText = 'before the first round';
    if (k >= 0) {
      const rd = meta.rounds[k];
      const n = meta.rounds.length;
      if (t <= rd.end_s + 1e-9 || (k === n - 1 && !rd.completed)) {
        roundText = 'Round ' + (k + 1) + ' of ' + n + ' · started at ' + fmt(rd.start_s, 1) + ' s';
      } else {
        roundText = 'Round ' + (k + 1) + ' ended at ' + fmt(rd.end_s, 1) + ' s · waiting for the team';
      }
    }
    $('round').textContent = roundText;
    const total = rescuedAt(t);
    const round = k >= 0 ? meta.rounds[k] : null;
    const inRound = new Array(K).fill(0);
    const members = new Array(K).fill(0);
    if (round) {
      for (const m of meta.marks) {
        if (m.t > t + 1e-9) break;
        if (m.k === 5 && m.task !== null && m.t >= round.start_s - 1e-9) inRound[m.task] += m.v;
      }
    }
    for (let r = 0; r < R; r++) { const g = val('group', at.i0, r); if (g > 0) members[g - 1]++; }
    let html = '<tr><th>task</th><th>total</th><th>this round</th><th>group</th></tr>';
    let sum = 0;
    for (let i = 0; i < K; i++) {
      sum += total[i];
      html += '<tr><td><span class="sw" style="background:' + meta.tasks[i].color + '"></span>' + esc(meta.tasks[i].name) +
        '</td><td><b>' + total[i] + '</b></td><td>' + inRound[i] + '</td><td>' + members[i] + ' robots</td></tr>';
    }
    if (K > 1) html += '<tr><td>all</td><td><b>' + sum + '</b></td><td></td><td></td></tr>';
    if (html !== lastSide) { $('rescued').innerHTML = html; lastSide = html; }
    renderRobot(at);
  }

  function renderRobot(at) {
    const box = $('robot');
    if (selected < 0) { box.className = 'dim'; box.textContent = 'Click a robot on the map.'; return; }
    const r = selected;
    const kind = meta.kinds[meta.robots[r]];
    const g = val('group', at.i0, r);
    const [x, y] = position(at, r);
    const e = val('energy_centi_pct', at.i0, r) / 100;
    const hp = val('hp_centi_pct', at.i0, r) / 100;
    let needs = '<table><tr>' + meta.needs.map((n) => '<th>' + n + '</th>').join('') + '</tr><tr>';
    for (let i = 0; i < meta.needs.length; i++) needs += '<td>' + fmt(val('needs_' + i, at.i0, r) / 1000, i >= 4 && i <= 5 ? 0 : 2) + '</td>';
    needs += '</tr></table>';
    box.className = '';
    box.innerHTML =
      '<div class="head">Robot ' + r + ' <span class="dim">· ' + esc(kind.name) + ' (' + (kind.aerial ? 'aerial' : 'ground') + ')</span></div>' +
      '<div>group: <span class="sw" style="background:' + groupColor(g) + '"></span>' + (g > 0 ? esc(taskName(g)) : 'none') + '</div>' +
      '<div class="state">' + esc(stateText(at, r)) + '</div>' +
      '<div>' + bar(e / 100, '#f2b705') + 'energy ' + fmt(e, 1) + ' %</div>' +
      '<div>' + bar(hp / 100, '#3aa655') + 'HP ' + fmt(hp, 1) + ' %</div>' +
      '<div class="dim">at (' + fmt(x, 2) + ', ' + fmt(y, 2) + ') m · phase ' + meta.phases[val('phase', at.i0, r)] + '</div>' +
      '<div style="margin-top:4px">needs vector (Eqs. 19-21)</div>' + needs;
  }

  // ---- timeline -------------------------------------------------------------------------------
  const ROW = 14;
  const PAD = 7; // matches half the slider thumb, so marks line up with it
  const tlX = (time) => PAD + (time / duration) * (timeline.clientWidth - 2 * PAD);
  const tlTime = (x) => Math.min(Math.max(((x - PAD) / (timeline.clientWidth - 2 * PAD)) * duration, 0), duration);

  function drawTimeline() {
    const w = timeline.clientWidth;
    const rows = meta.mark_kinds.length;
    const h = rows * ROW + 16;
    tctx.setTransform(scale.dpr, 0, 0, scale.dpr, 0, 0);
    tctx.clearRect(0, 0, w, h);
    meta.rounds.forEach((rd, i) => {
      tctx.fillStyle = i % 2 ? '#eef2f7' : '#e5ebf3';
      tctx.fillRect(tlX(rd.start_s), 0, Math.max(tlX(rd.end_s) - tlX(rd.start_s), 1), rows * ROW);
    });
    for (let k = 0; k <= rows; k++) {
      tctx.fillStyle = '#ffffff';
      tctx.fillRect(PAD, k * ROW - 0.5, w - 2 * PAD, 1);
    }
    for (const m of meta.marks) {
      tctx.fillStyle = meta.mark_kinds[m.k].color;
      const wide = m.k <= 1 ? 2 : 1.5;
      tctx.fillRect(tlX(m.t) - wide / 2, m.k * ROW + 2, wide, ROW - 4);
    }
    tctx.fillStyle = '#6b7280';
    tctx.font = '10px system-ui, sans-serif';
    tctx.textBaseline = 'top';
    const stepS = niceStep(duration / Math.max(w / 90, 1));
    for (let s = 0; s <= duration + 1e-9; s += stepS) {
      const x = tlX(s);
      tctx.fillRect(x, rows * ROW, 1, 4);
      tctx.textAlign = s === 0 ? 'left' : s + stepS > duration + 1e-9 && x > w - 30 ? 'right' : 'center';
      tctx.fillText(fmt(s, stepS < 1 ? 1 : 0) + ' s', x, rows * ROW + 5);
    }
    tctx.fillStyle = '#2563eb';
    tctx.fillRect(tlX(t) - 1, 0, 2, rows * ROW + 2);
  }
  function niceStep(raw) {
    const p = Math.pow(10, Math.floor(Math.log10(Math.max(raw, 1e-6))));
    for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
    return 10 * p;
  }
  function markText(m) {
    const who = m.robots.length === 1 ? 'robot ' + m.robots[0] : 'robots ' + m.robots.join(', ');
    const task = m.task !== null ? meta.tasks[m.task].name : '';
    switch (m.k) {
      case 0: return 'round ' + (m.v + 1) + ' starts';
      case 1: return 'round ends' + (m.v ? ' (everyone back)' : ' (cut by the time limit)');
      case 2: return 'deadlock detected: ' + who;
      case 3: return 'deadlock resolved: ' + who;
      case 4: return who + ' leaves ' + (task || 'its task') + ' to recharge (' +
        [m.v & 1 ? 'low energy' : '', m.v & 2 ? 'low HP' : ''].filter(Boolean).join(', ') + ')';
      case 5: return who + ' delivers ' + m.v + ' to the ' + task + ' drop-off';
      default: return meta.mark_kinds[m.k].label;
    }
  }
  function marksNear(x, y) {
    const k = Math.floor(y / ROW);
    if (k < 0 || k >= meta.mark_kinds.length) return [];
    return meta.marks.filter((m) => m.k === k && Math.abs(tlX(m.t) - x) <= 3);
  }

  // ---- state for tests ------------------------------------------------------------------------
  let stateTimer = 0;
  function writeState(at) {
    if (playing && performance.now() - stateTimer < 500) return;
    stateTimer = performance.now();
    const positions = [];
    for (let r = 0; r < R; r++) {
      const [x, y] = position(at, r);
      positions.push([Math.round(x * 1000) / 1000, Math.round(y * 1000) / 1000]);
    }
    stateEl.textContent = JSON.stringify({
      ready: true, t, sample: at.i0, frac: at.frac, round: roundAt(t), rescued: rescuedAt(t),
      selected, playing, speed, positions, errors,
    });
  }

  // ---- control --------------------------------------------------------------------------------
  function seek(time) {
    t = Math.min(Math.max(Number(time) || 0, 0), duration);
    slider.value = String(t);
    render();
  }
  function setPlaying(p) {
    playing = p && t < duration;
    playBtn.innerHTML = playing ? '&#10074;&#10074;' : '&#9654;';
    if (playing) { lastFrame = performance.now(); requestAnimationFrame(tick); } else render();
  }
  function tick(now) {
    if (!playing) return;
    const dt = Math.min((now - lastFrame) / 1000, 0.25);
    lastFrame = now;
    t = Math.min(t + dt * speed, duration);
    slider.value = String(t);
    render();
    if (t >= duration) setPlaying(false); else requestAnimationFrame(tick);
  }
  function setSpeed(s) { speed = s; speedSel.value = String(s); }
  function jumpMark(dir) {
    const eps = 1e-6;
    const list = dir > 0 ? meta.marks.filter((m) => m.t > t + eps) : meta.marks.filter((m) => m.t < t - eps);
    if (list.length) seek(dir > 0 ? list[0].t : list[list.length - 1].t);
  }
  function fromHash() {
    const h = new URLSearchParams(location.hash.replace(/^#/, ''));
    if (h.has('robot')) {
      const r = parseInt(h.get('robot'), 10);
      selected = r >= 0 && r < R ? r : -1;
    }
    if (h.has('zoom')) {
      // zoom=Z&at=X,Y: Z times closer, centred on the world point (X, Y) metres.
      const z = Math.min(Math.max(parseFloat(h.get('zoom')) || 1, 1), 24);
      const [ax, ay] = (h.get('at') || '').split(',').map(parseFloat);
      const cx = Number.isFinite(ax) ? (ax - meta.map.x0_m) * scale.sx : scale.w / 2;
      const cy = Number.isFinite(ay) ? (meta.map.y1_m - ay) * scale.sy : scale.h / 2;
      zoom = z;
      pan = { x: scale.w / 2 - cx * z, y: scale.h / 2 - cy * z };
      clampPan();
    }
    if (h.has('t')) seek(parseFloat(h.get('t'))); else render();
  }

  function setUp() {
    $('title').textContent = meta.scenario + ' · ' + meta.method + ' grouping · trial ' + meta.trial;
    $('subtitle').textContent = R + ' robots, ' + K + ' task' + (K > 1 ? 's' : '') + ', ' + fmt(duration, 1) +
      ' s at ' + fmt(meta.hz, meta.hz < 1 ? 2 : 0) + ' samples/s (seed ' + meta.seed + '). ' + meta.description;
    $('duration').textContent = fmt(duration, 0);
    slider.max = String(duration);
    for (const s of SPEEDS) {
      const o = document.createElement('option');
      o.value = String(s); o.textContent = s + 'x';
      speedSel.appendChild(o);
    }
    setSpeed(speed);
    const labels = $('mark-labels');
    meta.mark_kinds.forEach((k, i) => {
      const n = meta.marks.filter((m) => m.k === i).length;
      const li = document.createElement('li');
      li.innerHTML = '<span class="sw" style="background:' + k.color + '"></span>' + esc(k.label) + '<span class="n">' + n + '</span>';
      labels.appendChild(li);
    });
    buildLegend();
    playBtn.addEventListener('click', () => setPlaying(!playing));
    speedSel.addEventListener('change', () => setSpeed(Number(speedSel.value)));
    slider.addEventListener('input', () => seek(slider.value));
    timeline.addEventListener('click', (e) => {
      const near = marksNear(e.offsetX, e.offsetY);
      seek(near.length ? near[0].t : tlTime(e.offsetX));
    });
    timeline.addEventListener('mousemove', (e) => {
      const near = marksNear(e.offsetX, e.offsetY);
      if (!near.length) { markTip.hidden = true; return; }
      markTip.hidden = false;
      markTip.innerHTML = near.slice(0, 6).map((m) => fmt(m.t, 1) + ' s: ' + esc(markText(m))).join('<br>') +
        (near.length > 6 ? '<br>… ' + (near.length - 6) + ' more' : '');
      markTip.style.left = Math.min(e.offsetX + 10, timeline.clientWidth - markTip.offsetWidth) + 'px';
      markTip.style.top = (e.offsetY - markTip.offsetHeight - 6) + 'px';
    });
    timeline.addEventListener('mouseleave', () => { markTip.hidden = true; });
    let drag = null;
    layer.addEventListener('mousedown', (e) => { drag = { x: e.clientX, y: e.clientY, px: pan.x, py: pan.y, moved: false }; });
    window.addEventListener('mousemove', (e) => {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 3) drag.moved = true;
      if (drag.moved && zoom > 1) { pan.x = drag.px + dx; pan.y = drag.py + dy; clampPan(); }
    });
    window.addEventListener('mouseup', () => { setTimeout(() => { drag = null; }, 0); });
    layer.addEventListener('click', (e) => {
      if (drag && drag.moved) return;
      selected = robotNear(e.offsetX, e.offsetY);
      render();
    });
    layer.addEventListener('wheel', (e) => {
      e.preventDefault();
      setZoom(zoom * Math.exp(-e.deltaY * 0.0015), e.offsetX, e.offsetY);
    }, { passive: false });
    layer.addEventListener('dblclick', () => { zoom = 1; pan = { x: 0, y: 0 }; clampPan(); });
    layer.addEventListener('mousemove', (e) => {
      const r = robotNear(e.offsetX, e.offsetY);
      if (r < 0) { hoverTip.hidden = true; return; }
      const at = sampleAt(t);
      hoverTip.hidden = false;
      hoverTip.textContent = 'robot ' + r + ' (' + meta.kinds[meta.robots[r]].name + '): ' + stateText(at, r);
      hoverTip.style.left = Math.min(e.offsetX + 12, scale.w - hoverTip.offsetWidth - 4) + 'px';
      hoverTip.style.top = Math.max(e.offsetY - 28, 2) + 'px';
    });
    layer.addEventListener('mouseleave', () => { hoverTip.hidden = true; });
    document.addEventListener('keydown', onKey);
    window.addEventListener('resize', resize);
    window.addEventListener('hashchange', fromHash);
  }

  function robotNear(px, py) {
    if (!channels) return -1;
    const at = sampleAt(t);
    let best = -1, bestD = Infinity;
    for (let r = 0; r < R; r++) {
      const [x, y] = position(at, r);
      const d = Math.hypot(X(x) - px, Y(y) - py);
      if (d < bestD) { bestD = d; best = r; }
    }
    return bestD <= Math.max(12, best >= 0 ? robotRadiusPx(best) * 2 : 0) ? best : -1;
  }

  function onKey(e) {
    if (e.target === speedSel) return;
    const sample = meta.every_steps * meta.dt_s;
    let handled = true;
    switch (e.key) {
      case ' ': setPlaying(!playing); break;
      case 'ArrowRight': seek(t + (e.shiftKey ? 10 : 1)); break;
      case 'ArrowLeft': seek(t - (e.shiftKey ? 10 : 1)); break;
      case '.': seek(t + sample); break;
      case ',': seek(t - sample); break;
      case '+': case '=': setSpeed(SPEEDS[Math.min(SPEEDS.indexOf(speed) + 1, SPEEDS.length - 1)]); break;
      case '-': case '_': setSpeed(SPEEDS[Math.max(SPEEDS.indexOf(speed) - 1, 0)]); break;
      case 'n': jumpMark(1); break;
      case 'p': jumpMark(-1); break;
      case 'Home': seek(0); break;
      case 'End': seek(duration); break;
      case 'Escape': selected = -1; render(); break;
      case 'z': setZoom(zoom * 1.5, scale.w / 2, scale.h / 2); break;
      case 'x': setZoom(zoom / 1.5, scale.w / 2, scale.h / 2); break;
      case '0': zoom = 1; pan = { x: 0, y: 0 }; clampPan(); break;
      default: handled = false;
    }
    if (handled) e.preventDefault();
  }

  function legendIcon(draw) {
    const c = document.createElement('canvas');
    const dpr = window.devicePixelRatio || 1;
    c.width = 22 * dpr; c.height = 18 * dpr;
    const g = c.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    draw(g);
    return c;
  }
  function kindLegend(k) {
    const names = meta.kinds.filter((o) => o.role === k.role && o.aerial === k.aerial).map((o) => o.name);
    const role = k.role.toLowerCase();
    const what = names.length === 1 && names[0].toLowerCase() === role ? role : names.join(', ') + ' (' + role + ')';
    return what + (k.aerial ? ', aerial (ringed)' : ', ground');
  }
  function buildLegend() {
    const box = $('legend');
    const add = (icon, text) => {
      box.appendChild(icon);
      const span = document.createElement('span');
      span.textContent = text;
      box.appendChild(span);
    };
    meta.tasks.forEach((task) => add(legendIcon((g) => {
      g.fillStyle = task.color; g.beginPath(); g.arc(11, 9, 5.5, 0, 7); g.fill();
      g.strokeStyle = '#1d2129'; g.lineWidth = 1; g.stroke();
    }), 'in the ' + task.name + ' group'));
    add(legendIcon((g) => {
      g.fillStyle = meta.no_group_color; g.beginPath(); g.arc(11, 9, 5.5, 0, 7); g.fill();
      g.strokeStyle = '#1d2129'; g.stroke();
    }), 'in no group (between rounds, resting)');
    const seen = new Set();
    meta.kinds.forEach((k) => {
      if (seen.has(k.role + k.aerial)) return;
      seen.add(k.role + k.aerial);
      add(legendIcon((g) => {
        if (k.aerial) { g.strokeStyle = '#555'; g.lineWidth = 1.2; g.beginPath(); g.arc(11, 9, 8, 0, 7); g.stroke(); }
        shapePath(g, k.role, 11, 9, 4.5);
        g.fillStyle = '#ffffff'; g.fill(); g.strokeStyle = '#1d2129'; g.lineWidth = 1; g.stroke();
      }), kindLegend(k));
    });
    add(legendIcon((g) => {
      g.fillStyle = '#9e9e9e'; g.beginPath(); g.arc(11, 9, 5.5, 0, 7); g.fill(); g.stroke();
      g.fillStyle = '#fff'; g.beginPath(); g.arc(11, 9, 2.3, 0, 7); g.fill();
    }), 'carrying rescuees');
    add(legendIcon((g) => {
      g.strokeStyle = '#d62728'; g.lineWidth = 2; g.beginPath(); g.arc(11, 9, 7, 0, 7); g.stroke();
      g.fillStyle = '#9e9e9e'; g.beginPath(); g.arc(11, 9, 4, 0, 7); g.fill();
    }), 'held by the resolver (orange: blocked)');
    add(legendIcon((g) => {
      g.fillStyle = 'rgba(30,30,30,0.55)'; g.fillRect(2, 4, 18, 4); g.fillRect(2, 9, 18, 4);
      g.fillStyle = '#f2b705'; g.fillRect(2.5, 4.5, 12, 3);
      g.fillStyle = '#3aa655'; g.fillRect(2.5, 9.5, 16, 3);
    }), 'energy (top) and HP bars');
    add(legendIcon((g) => {
      g.fillStyle = meta.rescuee_color; g.beginPath(); g.arc(7, 9, 2.2, 0, 7); g.fill();
      g.fillStyle = meta.tasks[0].color; g.beginPath(); g.arc(15, 9, 2.9, 0, 7); g.fill();
    }), 'rescuee waiting / claimed (gone once picked up)');
    add(legendIcon((g) => {
      g.strokeStyle = '#8a8a8a'; g.lineWidth = 1; g.beginPath();
      g.moveTo(8, 6); g.lineTo(14, 12); g.moveTo(14, 6); g.lineTo(8, 12); g.stroke();
    }), 'rescuee out of reach');
  }

  // ---- start ----------------------------------------------------------------------------------
  setUp();
  const started = load().then(() => {
    if (mapImg.complete) resize(); else mapImg.addEventListener('load', resize);
    resize();
    fromHash();
  });
  started.catch((e) => fatal(e && e.message ? e.message : e));
})();
