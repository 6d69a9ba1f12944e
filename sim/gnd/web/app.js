// The ground station page: telemetry in (server-sent events), commands out
// (POST /api/command), products fetched as they complete. window.petra
// exposes the decoded state for inspection (and for the end-to-end test).
import { RoiCanvas } from './roi_canvas.js';
import { fetchProduct, toImageData, drawImageProduct, drawDisparity, drawColourBar, toPoints } from './products.js';
import { ProposalsPanel } from './proposals.js';

const $ = (id) => document.getElementById(id);
const fmt = (x, d = 1) => Number(x).toFixed(d);
const vec = (a, d) => `(${a.map((x) => fmt(x, d)).join(', ')})`;
// The colours of every picture, `petra eval`'s included (tlm/palette.hpp).
const palette = await fetch('/api/palette').then((r) => r.json());
const planeColour = (rank) => palette.planes[Math.min(rank, palette.planes.length - 1)];
// Planes are numbered 1..c for the operator; the wire's plane_rank is 0..c-1.
const planeNumber = (rank) => rank + 1;

const state = {
  commands: new Map(),  // counter -> {command, args, stage, reason, detail}
  evalResult: null, planes: [], ground: null, picked: null,
  hk: null, lastPacketMs: 0, view3d: 'loading', events: [], products: {}, arm: 'not requested',
  armGeometry: null, armTlm: null, plan: null,
};
window.petra = state;
state.palette = palette;
state.view3dStats = () => (view3d ? view3d.stats() : null);
state.view3dFrame = (mode) => view3d && view3d.frame(mode);

// The 3D view is created once: every caller awaits the same load (a page
// opened during an evaluation gets its point cloud before three.js has
// loaded; a second View3D would be a second WebGL canvas).
let view3d = null;
let view3dLoad = null;
function get3d() {
  if (!view3dLoad) view3dLoad = load3d();
  return view3dLoad;
}

async function load3d() {
  try {
    const { View3D } = await import('./view3d.js');
    view3d = new View3D($('view3d'), palette);
    view3d.setLabel('no point cloud yet');
    if (state.armTlm) view3d.setArm('arm', state.armTlm.skeleton);
    $('view3d-status').remove();
    state.view3d = 'ready';
  } catch (e) {
    const why = String(e.message || e);
    state.view3d = why;
    $('view3d-status').textContent = `3D view unavailable: ${why} (install the page assets: cmake --build <build folder> --target gnd_web)`;
  }
  return view3d;
}

const roi = new RoiCanvas($('left'), () => {
  const r = roi.roi;
  state.roi = r;
  state.click = roi.click;
  $('roi-text').textContent = r ? `x ${r.x}, y ${r.y}, ${r.w} × ${r.h} px` : 'none';
  $('click-text').textContent = roi.click ? `(${roi.click.u}, ${roi.click.v})` : 'none';
  $('send-eval').disabled = !r;
});

// ---- commands -------------------------------------------------------------
async function send(command, args = {}) {
  $('request-error').textContent = '';
  const r = await fetch('/api/command', { method: 'POST', headers: { 'Content-Type': 'application/json' },
                                          body: JSON.stringify({ command, args }) });
  const body = await r.json().catch(() => ({ error: `HTTP ${r.status}` }));
  if (!r.ok) {
    $('request-error').textContent = `${command} not sent: ${body.error}`;
    return null;
  }
  noteCommand(body.counter, { command, args });
  return body.counter;
}

function noteCommand(counter, fields) {
  const row = state.commands.get(counter) || { counter, command: '?', args: {}, stage: 'SENT', reason: '', detail: '' };
  Object.assign(row, fields);
  state.commands.set(counter, row);
  renderCommands();
  return row;
}

// EVALUATE goes up only once SELECT_ROI completed, so a refused ROI never
// evaluates a stale selection.
let pendingEvaluate = null;
$('send-eval').addEventListener('click', async () => {
  const r = roi.roi;
  if (!r) return;
  const args = { x_px: r.x, y_px: r.y, w_px: r.w, h_px: r.h, planes: Number($('planes').value) };
  if (roi.click) Object.assign(args, { has_click: 1, click_u_px: roi.click.u, click_v_px: roi.click.v });
  const counter = await send('SELECT_ROI', args);
  if (counter === null) return;
  pendingEvaluate = { after: counter, acquire: $('acquire').checked ? 1 : 0 };
  continueEvaluate(state.commands.get(counter));  // its ack may have come before the reply
});

function continueEvaluate(row) {
  if (!pendingEvaluate || row.counter !== pendingEvaluate.after || row.stage === 'SENT' || row.stage === 'ACCEPTED') return;
  const acquire = pendingEvaluate.acquire;
  pendingEvaluate = null;
  if (row.stage === 'COMPLETED') send('EVALUATE', { acquire });
  else $('request-error').textContent = `EVALUATE not sent: SELECT_ROI ${row.stage} ${row.reason}`;
}
$('send-acquire').addEventListener('click', () => send('ACQUIRE'));
$('send-abort').addEventListener('click', () => send('ABORT'));
$('send-stow').addEventListener('click', () => send('ARM_STOW'));
$('clear-click').addEventListener('click', () => roi.clearClick());
$('view-arm').addEventListener('click', () => view3d && view3d.frame('arm'));
$('view-rock').addEventListener('click', () => view3d && view3d.frame('rock'));
$('send-goto').addEventListener('click', () => {
  if (state.picked === null) return;
  send('ARM_GOTO', { plane_rank: state.picked, standoff_mm: Number($('standoff').value) });
  state.arm = 'requested';
  state.armGotoRank = state.picked;
  renderArm();
});
$('standoff').addEventListener('change', () => pick(state.picked));

// A pick sends SELECT_PROPOSAL (server side); EVALUATE follows on the operator's word.
const proposals = new ProposalsPanel(
  { table: $('proposal-table'), status: $('proposals-status'), picture: $('proposals-picture'), caption: $('proposals-caption') },
  send, palette, (answer) => {
    if (answer) noteCommand(answer.counter, { command: answer.command });
    $('send-eval-picked').disabled = !answer;
  });
state.proposals = proposals;
$('send-propose').addEventListener('click', () => send('PROPOSE', proposals.request($('propose-form').elements)));
$('send-eval-picked').addEventListener('click', () => send('EVALUATE', { acquire: 0 }));

// ---- telemetry --------------------------------------------------------------
const events = new EventSource('/api/events');
events.addEventListener('sent', (e) => {
  const m = JSON.parse(e.data);
  const row = state.commands.get(m.counter);
  noteCommand(m.counter, { command: m.command, args: m.args || (row ? row.args : {}) });
});
events.addEventListener('product', (e) => onProduct(JSON.parse(e.data)));
events.addEventListener('tlm', (e) => onTlm(JSON.parse(e.data)));
events.addEventListener('bad_packet', (e) => addEvent('ERROR', `bad packet: ${JSON.parse(e.data).error}`));
events.onerror = () => { $('link').textContent = 'ground server: disconnected'; $('link').className = 'badge bad'; };

function onTlm(m) {
  state.lastPacketMs = Date.now();
  const f = m.tlm.fields;
  switch (m.tlm.packet) {
    case 'HK': state.hk = { ...f, names: m.names }; renderHk(); break;
    case 'EVENT': addEvent(m.names.severity, `${m.names.event}: ${f.text}`); break;
    case 'ACK': onAck(f, m.names); break;
    case 'EVAL_RESULT':
      state.evalResult = f;
      state.planes = [];
      state.picked = null;
      renderPlanes();
      break;
    case 'GRIND_PLANE':
      if (state.evalResult && f.eval_id !== state.evalResult.eval_id) break;
      state.planes = state.planes.filter((p) => p.rank !== f.rank).concat([f]).sort((a, b) => a.rank - b.rank);
      renderPlanes();
      break;
    case 'GROUND_PLANE': state.ground = f; break;
    case 'PROPOSALS': proposals.onPacket(f, m.names); break;
    case 'PROPOSAL_PLANES': proposals.onPlanes(f); break;
    case 'ARM_STATUS': onArmStatus(f, m.skeleton); break;
    case 'PARAM_VALUE': addEvent('INFO', m.line); break;
  }
}

function onAck(f, names) {
  const row = noteCommand(f.counter, { command: names.command, stage: names.stage,
                                       reason: f.reason ? names.reason : '', detail: names.detail || '' });
  continueEvaluate(row);
  if (row.command === 'EVALUATE' && (names.stage === 'FAILED' || names.stage === 'REJECTED'))
    $('planes-status').textContent = `EVALUATE ${names.stage}: ${names.reason} - no planes.`;
  if (row.command === 'ARM_GOTO' && names.stage !== 'ACCEPTED') {
    state.arm = names.stage === 'COMPLETED' ? 'reached' : `${names.stage} ${names.reason}`;
    renderArm();
  }
}

async function onProduct(info) {
  const p = await fetchProduct(info.kind);
  if (!p) return;
  state.products[info.kind] = { id: p.id, width: p.width, height: p.height };
  if (info.kind === 'left_image') {
    const img = toImageData(p);
    if (img) roi.setImage(img);
    $('image-source').textContent = p.id ? `LEFT_IMAGE of frame ${p.id}, ${p.width} × ${p.height}` : `scene image, ${p.width} × ${p.height}`;
  } else if (info.kind === 'disparity') {
    if (drawDisparity($('disparity'), p, palette)) {
      $('disparity-caption').textContent = `disparity of evaluation ${p.id}, ${p.width} × ${p.height} px`;
      renderDisparityScale(p.id);
    }
  } else if (info.kind === 'overlay') {
    if (drawImageProduct($('overlay'), p))
      $('overlay-caption').textContent = `overlay of evaluation ${p.id}, ${p.width} × ${p.height} px`;
  } else if (info.kind === 'proposals') {
    proposals.onPicture(p);
  } else if (info.kind === 'point_cloud') {
    const xyz = toPoints(p);
    const v = await get3d();
    if (xyz && v) {
      v.setGround(state.ground);
      v.setCloud(xyz);
      v.setPlanes(state.planes);
      v.setLabel(`evaluation ${p.id}: ${xyz.length / 3} points`);
    }
  }
}

// ---- rendering --------------------------------------------------------------
function addEvent(severity, text) {
  const li = document.createElement('li');
  li.className = severity;
  li.textContent = `${new Date().toLocaleTimeString()} ${severity} ${text}`;
  $('events').prepend(li);
  while ($('events').children.length > 200) $('events').lastChild.remove();
  state.events.push(text);
}

function renderCommands() {
  const rows = [...state.commands.values()].sort((a, b) => b.counter - a.counter).slice(0, 40);
  $('cmd-table').tBodies[0].replaceChildren(...rows.map((c) => {
    const tr = document.createElement('tr');
    tr.dataset.counter = c.counter;
    tr.dataset.command = c.command;
    tr.dataset.stage = c.stage;
    const args = Object.entries(c.args || {}).map(([k, v]) =>
      k === 'plane_rank' ? `plane ${planeNumber(Number(v))} (plane_rank=${v})` : `${k}=${v}`).join(' ');
    const status = c.reason ? `${c.stage}: ${c.reason}${c.detail ? ` (${c.detail})` : ''}` : c.stage;
    for (const [text, cls] of [[c.counter, ''], [c.command, ''], [args, ''], [status, c.stage]]) {
      const td = document.createElement('td');
      td.textContent = text;
      if (cls) td.className = cls;
      tr.append(td);
    }
    return tr;
  }));
}

function renderHk() {
  const h = state.hk;
  $('mode').textContent = `mode ${h.names.mode}`;
  $('mode').className = `badge ${h.names.mode === 'SAFE' ? 'bad' : 'good'}`;
  $('hk-summary').textContent = `up ${h.uptime_s} s · commands ${h.cmd_accepted} accepted, ${h.cmd_rejected} rejected · tlm dropped ${h.tlm_dropped}`;
  const rows = [
    ['mode', h.names.mode], ['uptime', `${h.uptime_s} s`], ['cycles / overruns', `${h.cycles} / ${h.cycle_overruns}`],
    ['longest cycle', `${h.max_cycle_us} µs`],
    ['commands received / accepted / rejected', `${h.cmd_received} / ${h.cmd_accepted} / ${h.cmd_rejected}`],
    ['commands completed / failed', `${h.cmd_completed} / ${h.cmd_failed}`],
    ['last command, reason', `${h.names.last_command}, ${h.names.last_reason}`],
    ['telemetry sent / dropped', `${h.tlm_sent} / ${h.tlm_dropped}`],
    ['frames / evaluations', `${h.frames} / ${h.evaluations}`],
    ['evaluation running, elapsed', `${h.eval_running ? 'yes' : 'no'}, ${h.eval_elapsed_ms} ms`],
    ['arena high water', `${fmt(h.arena_high_water_bytes / 1048576)} of ${fmt(h.arena_bytes / 1048576)} MiB`],
    ['faults', h.faults],
  ];
  $('hk').tBodies[0].replaceChildren(...rows.map(([k, v]) => {
    const tr = document.createElement('tr');
    tr.innerHTML = '<td></td><td></td>';
    tr.cells[0].textContent = k;
    tr.cells[1].textContent = v;
    return tr;
  }));
}

function renderPlanes() {
  const r = state.evalResult;
  if (r) {
    $('eval-summary').textContent = `evaluation ${r.eval_id}: ${r.planes_found} of ${r.planes_requested} planes, ${r.total_ms} ms, ${r.filtered_points} points`;
    $('planes-status').textContent = r.status === 0 ? `${r.planes_found} planes, best first. Click one to plan the arm.`
      : r.status === 1 ? `Only ${r.planes_found} of ${r.planes_requested} planes qualified.`
      : `Evaluation ${r.status === 3 ? 'aborted' : 'failed'} (reason ${r.reason}).`;
  }
  $('plane-table').tBodies[0].replaceChildren(...state.planes.map((p) => {
    const tr = document.createElement('tr');
    tr.dataset.rank = p.rank;
    if (p.rank === state.picked) tr.className = 'picked';
    const cells = [planeNumber(p.rank), vec(p.normal, 3), vec(p.centroid_mm, 1), fmt(p.area_mm2, 0), fmt(p.flatness_rms_mm, 2), p.triangles];
    cells.forEach((text, i) => {
      const td = document.createElement('td');
      if (i === 0) {
        const s = document.createElement('span');
        s.className = 'swatch';
        s.style.background = planeColour(p.rank);
        td.append(s);
      }
      td.append(String(text));
      tr.append(td);
    });
    tr.addEventListener('click', () => pick(p.rank));
    return tr;
  }));
  if (view3d) view3d.setPlanes(state.planes);
  $('send-goto').disabled = state.picked === null;
  renderLegend();
}

// The overlay's legend: the classes and each plane of the evaluation, 1..c.
function renderLegend() {
  const entries = [['ground', palette.ground], ['rock', palette.rock], ['shadow', palette.shadow]]
    .concat(state.planes.map((p) => [`plane ${planeNumber(p.rank)}`, planeColour(p.rank)]));
  $('overlay-legend').replaceChildren(...entries.map(([name, colour]) => {
    const item = document.createElement('span');
    const s = document.createElement('span');
    s.className = 'swatch';
    s.style.background = colour;
    item.append(s, name);
    return item;
  }));
}

// The disparity's colour bar, far to near, in px when EVAL_RESULT gave the range.
function renderDisparityScale(id) {
  drawColourBar($('disparity-bar'), palette);
  const r = state.evalResult;
  const known = r && r.eval_id === id;
  $('disparity-far').textContent = known ? `${fmt(r.disparity_min, 1)} px (far)` : 'far';
  $('disparity-near').textContent = known ? `${fmt(r.disparity_max, 1)} px (near)` : 'near';
}

// Picking a plane asks the server to plan the approach as the arm service
// will (same kinematics, from the measured joints): the ghost arm shows the
// contact pose, the dot the standoff waypoint.
async function pick(rank) {
  if (rank === null) return;
  state.picked = rank;
  state.arm = 'planning';
  state.plan = null;
  renderPlanes();
  renderArm();
  const p = state.planes.find((q) => q.rank === rank);
  const standoff = Number($('standoff').value);
  const r = await fetch('/api/arm/plan', { method: 'POST', headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify({ centroid_mm: p.centroid_mm, normal: p.normal, standoff_mm: standoff }) });
  const body = await r.json().catch(() => ({ error: `HTTP ${r.status}` }));
  if (state.picked !== rank) return;  // picked another meanwhile
  state.plan = r.ok ? { rank, standoff, ...body } : { rank, ok: false, stage: 'request', reason: body.error };
  state.arm = state.plan.ok ? 'planned' : 'plan refused';
  const v = await get3d();
  if (v) {
    v.showPose(p);
    v.setArm('plan', state.plan.ok ? state.plan.contact.skeleton : null, { waypoint: state.plan.ok ? state.plan.standoff.tip_mm : null });
  }
  renderArm();
}

const ARM_STATES = ['off', 'booting', 'enabling', 'holding', 'moving', 'approaching', 'retreating', 'settling', 'stopped', 'fault'];
const ARM_PROGRESS = ['idle', 'moving', 'reached', 'failed'];
const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

function onArmStatus(f, skeleton) {
  state.armTlm = { ...f, skeleton, state_name: ARM_STATES[f.state] || `state ${f.state}` };
  if (view3d && skeleton) view3d.setArm('arm', skeleton);
  renderArmTable();
  if (state.arm === 'reached') renderArm();
}

function renderArmTable() {
  const a = state.armTlm;
  if (!a) return;
  const p = state.planes.find((q) => q.rank === (state.arm === 'reached' ? state.armGotoRank : state.picked));
  const rows = [
    ['state', `${a.state_name}, ${ARM_PROGRESS[a.progress] || a.progress}`],
    ['joints measured (deg)', vec(a.joint_deg, 2)],
    ['joints target (deg)', vec(a.target_deg, 2)],
    ['tip (mm, world)', vec(a.tip_mm, 2)],
    ['tool axis', vec(a.axis, 3)],
    ['tip to picked centroid', p ? `${fmt(dist(a.tip_mm, p.centroid_mm), 3)} mm` : '-'],
    ['last verification', a.moves_completed ? `tip ${fmt(a.tip_error_mm, 3)} mm, axis ${fmt(a.axis_error_deg, 3)} deg` : 'none yet'],
    ['moves completed', a.moves_completed],
    ['CAN sent / received / bad', `${a.can_sent} / ${a.can_received} / ${a.can_bad_frames}`],
  ];
  if (a.fault_node) rows.push(['fault', `node ${a.fault_node}, fault ${a.fault}, detail ${a.fault_detail}`]);
  $('arm-table').tBodies[0].replaceChildren(...rows.map(([k, v]) => {
    const tr = document.createElement('tr');
    tr.innerHTML = '<td></td><td></td>';
    tr.cells[0].textContent = k;
    tr.cells[1].textContent = v;
    return tr;
  }));
}

function renderArm() {
  const rank = state.arm === 'reached' ? state.armGotoRank : state.picked;
  const p = state.planes.find((q) => q.rank === rank);
  const where = p ? `plane ${planeNumber(p.rank)}: grinder face on ${vec(p.centroid_mm, 1)} mm, axis along ${vec(p.normal.map((x) => -x), 3)}` : '';
  const plan = state.plan;
  const a = state.armTlm;
  const text = {
    'not requested': 'Arm: pick a plane to see the planned pose.',
    planning: `Planning ${where}...`,
    planned: plan && plan.ok ? `Planned ${where}; joints ${vec(plan.contact.joint_deg, 1)} deg, approach ${plan.standoff.tip_mm ? fmt(dist(plan.standoff.tip_mm, plan.contact.tip_mm), 0) : '?'} mm along the normal.` : '',
    'plan refused': plan ? `Plane ${planeNumber(rank)} cannot be reached: ${plan.reason}` : '',
    requested: `ARM_GOTO sent for ${where}; waiting for the acknowledgement.`,
    reached: `Arm reached ${where}${a && p ? `; tip ${fmt(dist(a.tip_mm, p.centroid_mm), 3)} mm from the centroid` : ''}.`,
  }[state.arm] ?? `ARM_GOTO ${state.arm}: the arm did not reach the plane.`;
  $('arm-status').textContent = text;
  $('arm-status').className = /^(FAILED|REJECTED|plan refused)/.test(state.arm) ? 'error' : 'hint';
  renderArmTable();
  if (!$('send-goto').disabled && state.arm === 'plan refused') $('send-goto').title = 'the server could not plan this plane; petra-fsw will refuse it too';
}

// The arm is drawn only from its telemetry (no ARM_STATUS: no arm configured
// or not booted); its geometry is kept for reference.
fetch('/api/arm').then((r) => r.json()).then((g) => { state.armGeometry = g; }).catch(() => {});

get3d();  // three.js from /vendor and WebGL: ready before the first cloud
renderLegend();
drawColourBar($('disparity-bar'), palette);

setInterval(() => {
  const age = (Date.now() - state.lastPacketMs) / 1000;
  if (events.readyState !== EventSource.OPEN) return;
  const live = state.lastPacketMs && age < 5;
  $('link').textContent = live ? `telemetry: live` : state.lastPacketMs ? `telemetry: silent ${fmt(age, 0)} s` : 'telemetry: waiting';
  $('link').className = `badge ${live ? 'good' : 'bad'}`;
}, 500);
