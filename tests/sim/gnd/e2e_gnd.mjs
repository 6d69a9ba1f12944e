// End-to-end test of the ground station: petra-fsw on a simulated scene with
// the arm's five simulated CANopen drives (`petra sim-arm`, CAN over UDP on
// loopback), `petra gnd serve` bridging it, headless Chromium driving the
// page as an operator would: ROI, SELECT_ROI + EVALUATE, planes, products,
// planned pose, ARM_GOTO, the arm reaching the plane, rejected commands,
// reloads during and after an evaluation (one 3D view, no script error), the
// pictures in `petra eval`'s palette, and the station's archive holding every
// packet the relay saw.
// Then the rock proposals panel: PROPOSE over the whole pair, the ranked
// list and its picture, a click on the picture picking a rock
// (SELECT_PROPOSAL) and EVALUATE giving the proposal's plane.
// The downlink passes through a relay here that decodes GRIND_PLANE, PROPOSALS and
// ARM_STATUS itself from the docs/icd.md layout (and checks the CRC): the
// reference the page and the server are compared with.
// Usage: node e2e_gnd.mjs PETRA PETRA_FSW BUILD_DIR
// Screenshots go to BUILD_DIR/gnd/screenshots. Exit 0 pass, 1 fail.
import { spawn, execFileSync } from 'node:child_process';
import { createRequire } from 'node:module';
import crypto from 'node:crypto';
import dgram from 'node:dgram';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

const [petra, fswBin, buildDir] = process.argv.slice(2).map((p) => path.resolve(p));
const require = createRequire(path.join(buildDir, 'gnd', 'package.json'));
const { chromium } = require('playwright-core');
const shots = path.join(buildDir, 'gnd', 'screenshots');
fs.mkdirSync(shots, { recursive: true });
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'petra-gnd-e2e-'));
const children = [];
const telemetry = [];  // the server's event stream, as received
const pageErrors = [];
let context = null;
const t0 = Date.now();
const log = (s) => console.log(`[${((Date.now() - t0) / 1000).toFixed(1)} s] ${s}`);

function check(ok, what) {
  if (!ok) throw new Error(`check failed: ${what}`);
  log(`ok: ${what}`);
}

async function freeUdpPort() {
  const s = dgram.createSocket('udp4');
  await new Promise((r) => s.bind(0, '127.0.0.1', r));
  const { port } = s.address();
  s.close();
  return port;
}

function pgmSize(file) {
  const head = fs.readFileSync(file).subarray(0, 64).toString('latin1').split(/\s+/);
  return { width: Number(head[1]), height: Number(head[2]) };
}

// The server's event stream, read independently of the page: the reference
// the page is checked against (decoded by the same code as `petra tlm --json`).
function followEvents(url, sink) {
  const controller = new AbortController();
  (async () => {
    const r = await fetch(url, { signal: controller.signal });
    const decoder = new TextDecoder();
    let buf = '';
    for await (const chunk of r.body) {
      buf += decoder.decode(chunk, { stream: true });
      let end;
      while ((end = buf.indexOf('\n\n')) >= 0) {
        const block = buf.slice(0, end);
        buf = buf.slice(end + 2);
        const ev = /^event: (.*)$/m.exec(block), data = /^data: (.*)$/m.exec(block);
        if (ev && data) sink.push({ event: ev[1], data: JSON.parse(data[1]) });
      }
    }
  })().catch(() => {});
  return controller;
}

async function until(what, fn, timeoutMs) {
  const end = Date.now() + timeoutMs;
  for (;;) {
    const v = await fn();
    if (v) return v;
    if (Date.now() > end) throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 100));
  }
}

// ---- an independent telemetry decoder (docs/icd.md) ----------------------
// CRC-16-CCITT (poly 0x1021, init 0xFFFF) over every byte before the last two.
function crc16(buf, n) {
  let c = 0xFFFF;
  for (let i = 0; i < n; ++i) {
    c ^= buf[i] << 8;
    for (let k = 0; k < 8; ++k) c = c & 0x8000 ? ((c << 1) ^ 0x1021) & 0xFFFF : (c << 1) & 0xFFFF;
  }
  return c;
}
const f64s = (b, o, n) => Array.from({ length: n }, (_, k) => b.readDoubleBE(o + 8 * k));
const f32s = (b, o, n) => Array.from({ length: n }, (_, k) => b.readFloatBE(o + 4 * k));
function decodeRaw(b) {
  const apid = b.readUInt16BE(0) & 0x7FF;
  const crcOk = b.length >= 16 && crc16(b, b.length - 2) === b.readUInt16BE(b.length - 2);
  switch (apid) {
    case 0x011: return { packet: 'EVENT', crcOk };
    case 0x014: return { packet: 'ARM_STATUS', crcOk, state: b[14], progress: b[15], joint_deg: f32s(b, 16, 5),
      tip_mm: f64s(b, 56, 3), axis: f64s(b, 80, 3), tip_error_mm: b.readFloatBE(106), axis_error_deg: b.readFloatBE(110) };
    case 0x020: return { packet: 'EVAL_RESULT', crcOk, eval_id: b.readUInt32BE(14), status: b[22], planes_found: b[33] };
    case 0x021: return { packet: 'GRIND_PLANE', crcOk, eval_id: b.readUInt32BE(14), rank: b[18], plane_count: b[19],
      normal: f64s(b, 20, 3), centroid_mm: f64s(b, 44, 3), area_mm2: b.readDoubleBE(68),
      flatness_rms_mm: b.readDoubleBE(76), triangles: b.readUInt32BE(84) };
    case 0x023: return { packet: 'PROPOSALS', crcOk, proposal_id: b.readUInt32BE(14), status: b[22], count: b[25],
      candidates: b.readUInt16BE(26), picture_step: b[40], rank: [...b.subarray(41, 49)],
      roi_px: Array.from({ length: 32 }, (_, k) => b.readUInt16BE(49 + 2 * k)),
      click_px: Array.from({ length: 16 }, (_, k) => b.readUInt16BE(113 + 2 * k)),
      plane_offered: [...b.subarray(233, 241)], normal: f32s(b, 401, 24), centroid_mm: f32s(b, 497, 24) };
    default: return { packet: `0x${apid.toString(16)}`, crcOk };
  }
}

// petra-fsw -> relay -> petra gnd serve; every datagram decoded here too. The
// fifth HK packet is lost on the way (kept in `lost`): a gap the station shows.
async function startRelay(toPort, sink, lost) {
  const s = dgram.createSocket('udp4');
  await new Promise((r) => s.bind(0, '127.0.0.1', r));
  let hk = 0;
  s.on('message', (msg) => {
    const apid = msg.readUInt16BE(0) & 0x7FF;
    if (apid === 0x010 && ++hk === 5) return lost.push({ apid, seq: msg.readUInt16BE(2) & 0x3FFF });
    s.send(msg, toPort, '127.0.0.1');
    sink.push({ t: Date.now(), apid: msg.readUInt16BE(0) & 0x7FF, ...decodeRaw(msg) });
  });
  return s;
}

const dist3 = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
const maxAbsDiff = (a, b) => Math.max(...a.map((x, i) => Math.abs(x - b[i])));

async function main() {
  // 1. A simulated scene and petra-fsw's configuration (as `petra demo`).
  // Rendered once per build tree: scenes are deterministic, and rendering one
  // in a Debug build takes a good part of the test's time.
  const scene = path.join(buildDir, 'gnd', 'scene-seed1');
  if (!fs.existsSync(path.join(scene, 'truth.json')))
    execFileSync(petra, ['sim', 'scene', '--seed', '1', '--out', scene], { stdio: 'ignore' });
  const truth = JSON.parse(fs.readFileSync(path.join(scene, 'truth.json'), 'utf8'));
  const [rx, ry, rw, rh] = truth.roi;
  const c = truth.planes ?? 2;
  const size = pgmSize(path.join(scene, 'left.pgm'));
  fs.mkdirSync(path.join(work, 'pairs'));
  for (const f of ['left.pgm', 'right.pgm']) fs.copyFileSync(path.join(scene, f), path.join(work, 'pairs', f));
  fs.writeFileSync(path.join(work, 'petra.key'), crypto.randomBytes(32).toString('hex') + '\n');
  const cmdPort = await freeUdpPort(), tlmPort = await freeUdpPort();
  const canFsw = await freeUdpPort(), canDrives = await freeUdpPort();
  const raw = [], lost = [];
  const relay = await startRelay(tlmPort, raw, lost);
  const mount = [300, 100, 100, 90];
  // counter_floor 0: a new key, so petra-fsw may start without its counter file (docs/ops.md).
  const config = { uplink: { host: '127.0.0.1', port: cmdPort, key_file: 'petra.key', counter_floor: 0 },
                   downlink: { host: '127.0.0.1', port: relay.address().port },
                   budget: { image_width: size.width, image_height: size.height, arena_mb: 512 },
                   camera: { kind: 'file', dir: 'pairs' },
                   // Heartbeat consumer time both ways 5 s instead of the flight's
                   // 350/500 ms, and 3 s for each configuration answer instead of
                   // 200 ms, so a host stalled by other work is not taken for a lost
                   // drive (the flight defaults are tested with a simulated clock).
                   arm: { can_interface: `udp:${canFsw}:${canDrives}`, mount,
                          heartbeat_timeout_ms: 5000, sdo_timeout_ms: 3000 } };
  check(fs.existsSync(path.join(scene, 'calib.json')), 'the scene has its calib.json');
  config.calib = path.join(scene, 'calib.json');
  fs.writeFileSync(path.join(work, 'fsw.json'), JSON.stringify(config));
  log(`scene seed 1: ${size.width} x ${size.height}, ROI [${truth.roi}], c = ${c}`);

  // 2. The arm's drives, the ground station (it listens for telemetry), then petra-fsw.
  const drives = spawn(petra, ['sim-arm', '--can', `udp:${canDrives}:${canFsw}`],
    { stdio: ['ignore', fs.openSync(path.join(work, 'sim-arm.log'), 'w'), 'inherit'] });
  children.push(drives);
  const gnd = spawn(petra, ['gnd', 'serve', '--port', '0', '--key', path.join(work, 'petra.key'),
    '--cmd-port', String(cmdPort), '--tlm-port', String(tlmPort), '--left-image', path.join(scene, 'left.png'),
    '--arm-mount', mount.join(','), '--archive', path.join(work, 'archive.db')], { stdio: ['ignore', 'pipe', 'inherit'] });
  children.push(gnd);
  const url = await new Promise((resolve, reject) => {
    let out = '';
    gnd.stdout.on('data', (d) => {
      out += d;
      const m = /serving (http:\/\/[0-9.:]+\/)/.exec(out);
      if (m) resolve(m[1]);
    });
    gnd.on('exit', (code) => reject(new Error(`petra gnd serve exited ${code}: ${out}`)));
  });
  log(`petra gnd serve at ${url}`);
  const follower = followEvents(`${url}api/events`, telemetry);
  const fsw = spawn(fswBin, ['--config', path.join(work, 'fsw.json')],
    { cwd: work, stdio: ['ignore', 'ignore', fs.openSync(path.join(work, 'fsw.log'), 'w')] });
  children.push(fsw);

  // 3. The browser.
  context = await chromium.launchPersistentContext(path.join(work, 'chromium-profile'), {
    executablePath: '/usr/bin/chromium', headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--enable-unsafe-swiftshader'],
    viewport: { width: 1600, height: 1000 } });
  const page = context.pages()[0] || await context.newPage();
  const requests = [];
  page.on('request', (r) => requests.push(r.url()));
  page.on('pageerror', (e) => pageErrors.push(String(e)));
  // Console errors other than HTTP statuses (the test's own refused request is one).
  page.on('console', (m) => { if (m.type() === 'error' && !m.text().startsWith('Failed to load resource')) pageErrors.push(m.text()); });
  await page.goto(url);
  await until('the scene image on the page', () => page.evaluate(() => document.getElementById('left').width > 0), 10000);
  await until('petra-fsw housekeeping in IDLE', () => page.evaluate(() => window.petra?.hk?.names.mode === 'IDLE'), 15000);
  const view3d = await until('the 3D view', () => page.evaluate(() => window.petra?.view3d !== 'loading' && window.petra?.view3d), 10000);
  check(view3d === 'ready', `3D view (three.js from /vendor, WebGL): ${view3d}`);
  check(await page.evaluate(() => window.petra.events.some((e) => e.startsWith('BOOT_COMPLETE'))), 'the page shows the BOOT_COMPLETE event');
  await until('ARM_READY (five simulated drives booted over CAN/UDP)',
    () => page.evaluate(() => window.petra.events.some((e) => e.startsWith('ARM_READY'))), 15000);
  const stow = await until('ARM_STATUS holding at the stowed pose on the page', () => page.evaluate(() =>
    window.petra.armTlm?.state_name === 'holding' && window.petra.armTlm), 10000);
  check(maxAbsDiff(stow.joint_deg, [0, 0, 145, 35, 0]) < 0.01, `arm at its stowed pose: joints ${JSON.stringify(stow.joint_deg.map((x) => +x.toFixed(3)))} deg`);
  // Arm telemetry four times a second while it moves (the operator's SET_PARAM).
  await page.evaluate(() => fetch('/api/command', { method: 'POST', body: JSON.stringify({ command: 'SET_PARAM', args: { param_id: 1, value: 250 } }) }));

  // 4. The operator drags the ROI and clicks a point on the rock.
  const canvas = await page.$('#left');
  const box = await canvas.boundingBox();
  const at = (u, v) => [box.x + (u + 0.5) * box.width / size.width, box.y + (v + 0.5) * box.height / size.height];
  await page.mouse.move(...at(rx, ry));
  await page.mouse.down();
  await page.mouse.move(...at(rx + rw - 1, ry + rh - 1), { steps: 12 });
  await page.mouse.up();
  const [cu, cv] = truth.click ?? [rx + Math.floor(rw / 2), ry + Math.floor(rh / 2)];
  await page.mouse.click(...at(cu, cv));
  await page.selectOption('#planes', String(c));
  // The mouse moves in whole screen pixels, so the ROI may land a pixel or
  // two off the truth; what must be exact is display == signed command.
  const sel = await page.evaluate(() => ({ roi: window.petra.roi, click: window.petra.click }));
  const near = (a, b) => Math.abs(a - b) <= 2;
  check(sel.roi && near(sel.roi.x, rx) && near(sel.roi.y, ry) && near(sel.roi.w, rw) && near(sel.roi.h, rh),
        `dragged ROI ${JSON.stringify(sel.roi)} within 2 px of [${truth.roi}]`);
  const roiText = await page.textContent('#roi-text');
  check(roiText === `x ${sel.roi.x}, y ${sel.roi.y}, ${sel.roi.w} × ${sel.roi.h} px`, `page shows ROI "${roiText}"`);
  check(sel.click && near(sel.click.u, cu) && near(sel.click.v, cv), `clicked point ${JSON.stringify(sel.click)} near (${cu}, ${cv})`);
  await page.locator('#select').screenshot({ path: path.join(shots, 'gnd_select.png') });

  // 5. Send: SELECT_ROI, then EVALUATE once SELECT_ROI completed.
  const tEval = Date.now();
  await page.click('#send-eval');
  const finalAck = (name) => telemetry.find((m) => m.event === 'tlm' && m.data.tlm.packet === 'ACK' &&
    m.data.names.command === name && m.data.names.stage !== 'ACCEPTED');
  const selAck = await until('SELECT_ROI acknowledgement', () => finalAck('SELECT_ROI'), 10000);
  check(selAck.data.names.stage === 'COMPLETED', `SELECT_ROI ${selAck.data.names.stage} ${selAck.data.names.reason}`);
  // The operator reloads while the evaluation runs: the page rebuilds from the
  // server's recent messages, with one 3D view and no script error.
  await until('EVALUATE sent by the page', () => telemetry.find((m) => m.event === 'sent' && m.data.command === 'EVALUATE'), 10000);
  const evalRunning = !finalAck('EVALUATE');
  await page.reload();
  await until('the 3D view after the reload', () => page.evaluate(() => window.petra?.view3d === 'ready'), 10000);
  check(true, `page reloaded ${evalRunning ? 'while the evaluation ran' : 'after the evaluation (it finished first)'}`);
  const sentSel = telemetry.find((m) => m.event === 'sent' && m.data.command === 'SELECT_ROI').data;
  const a = sentSel.args;
  check(a.x_px === sel.roi.x && a.y_px === sel.roi.y && a.w_px === sel.roi.w && a.h_px === sel.roi.h &&
        a.planes === c && a.has_click === 1 && a.click_u_px === sel.click.u && a.click_v_px === sel.click.v, `signed SELECT_ROI carries the dragged ROI, point and c: ${JSON.stringify(sentSel.args)}`);
  const evalAck = await until('EVALUATE final acknowledgement', () => finalAck('EVALUATE'), 120000);
  const rowStatus = (name) => page.evaluate((n) => [...document.querySelectorAll('#cmd-table tbody tr')]
    .filter((tr) => tr.dataset.command === n).map((tr) => tr.cells[3].textContent)[0], name);
  check(evalAck.data.names.stage === 'COMPLETED', `EVALUATE ${evalAck.data.names.stage} ${evalAck.data.names.reason} after ${((Date.now() - tEval) / 1000).toFixed(1)} s`);
  await until('EVALUATE COMPLETED in the command table', async () => (await rowStatus('EVALUATE')) === 'COMPLETED', 3000);
  check(await rowStatus('SELECT_ROI') === 'COMPLETED', 'command table: SELECT_ROI COMPLETED');

  // 6. Planes: the page's table against the telemetry decoded here from the
  // raw datagrams, and the server's own record against the same.
  const result = await until('EVAL_RESULT', () => raw.find((m) => m.packet === 'EVAL_RESULT'), 10000);
  const found = result.planes_found;
  check(found > 0, `${found} grind planes of ${c} requested (EVAL_RESULT status ${result.status})`);
  const planes = await until(`${found} GRIND_PLANE packets`, () => {
    const p = raw.filter((m) => m.packet === 'GRIND_PLANE' && m.eval_id === result.eval_id);
    return p.length >= found ? p.sort((x, y) => x.rank - y.rank) : null;
  }, 10000);
  check(raw.every((m) => m.crcOk), `every one of ${raw.length} telemetry packets so far passes the CRC`);
  const served = telemetry.filter((m) => m.event === 'tlm' && m.data.tlm.packet === 'GRIND_PLANE').map((m) => m.data.tlm.fields);
  for (const p of planes) {
    const s = served.find((q) => q.rank === p.rank && q.eval_id === p.eval_id);
    const diff = s ? Math.max(maxAbsDiff(s.normal, p.normal), maxAbsDiff(s.centroid_mm, p.centroid_mm),
      Math.abs(s.area_mm2 - p.area_mm2) / p.area_mm2, Math.abs(s.flatness_rms_mm - p.flatness_rms_mm)) : Infinity;
    check(s && diff < 1e-6 && s.triangles === p.triangles, `server's GRIND_PLANE ${p.rank} = raw packet (largest difference ${diff.toExponential(1)})`);
  }
  await until('plane rows', async () => (await page.$$('#plane-table tbody tr')).length === found, 5000);
  const rows = await page.$$eval('#plane-table tbody tr', (trs) => trs.map((tr) => [...tr.cells].map((td) => td.textContent)));
  for (const p of planes) {
    const expect = [String(p.rank + 1), `(${p.normal.map((x) => x.toFixed(3)).join(', ')})`,
      `(${p.centroid_mm.map((x) => x.toFixed(1)).join(', ')})`, p.area_mm2.toFixed(0), p.flatness_rms_mm.toFixed(2), String(p.triangles)];
    check(JSON.stringify(rows[p.rank]) === JSON.stringify(expect), `plane row ${p.rank + 1} (wire rank ${p.rank}) = raw telemetry ${JSON.stringify(expect)}`);
  }

  // 7. Products: disparity and overlay drawn at their size, the cloud in 3D
  // coloured by plane, and the view turns under the mouse.
  await until('disparity, overlay and point cloud products', () => page.evaluate(() =>
    ['disparity', 'overlay', 'point_cloud'].every((k) => window.petra.products[k])), 30000);
  const prods = await page.evaluate(() => window.petra.products);
  for (const k of ['disparity', 'overlay']) {
    const drawn = await page.evaluate((id) => { const cv = document.getElementById(id); return [cv.width, cv.height]; }, k);
    check(drawn[0] === prods[k].width && drawn[1] === prods[k].height && drawn[0] > 0, `${k} drawn ${drawn.join(' x ')} px`);
  }
  const overlayColours = await page.evaluate(() => {
    const cv = document.getElementById('overlay');
    const d = cv.getContext('2d').getImageData(0, 0, cv.width, cv.height).data;
    let coloured = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.max(d[i], d[i + 1], d[i + 2]) - Math.min(d[i], d[i + 1], d[i + 2]) > 60) ++coloured;
    return coloured;
  });
  check(overlayColours > 100, `overlay shows the clusters in colour (${overlayColours} coloured pixels)`);
  const cloud = await until('the cloud in the 3D view', () => page.evaluate(() => {
    const s = window.petra.view3dStats();
    return s && s.points > 0 && s.colourCounts.length === window.petra.planes.length ? s : null;
  }), 10000);
  check(cloud.points * 12 === (await (await fetch(`${url}api/product/point_cloud`)).arrayBuffer()).byteLength,
        `3D view holds the ${cloud.points} points of the POINT_CLOUD product`);
  check(cloud.colourCounts.every((n) => n > 20), `points coloured by plane: ${cloud.colourCounts.join(', ')} of ${cloud.points}`);
  check(cloud.meshTriangles > cloud.points / 2, `the 3D view draws the surface mesh: ${cloud.meshTriangles} triangles over ${cloud.points} points`);
  check(cloud.canvases === 1, `one WebGL view (${cloud.canvases} canvas in #view3d)`);
  // One palette: the page's is the server's (tlm/palette.hpp); the disparity
  // is drawn with its ramp, the legend names the planes 1..c in its colours.
  const pal = await (await fetch(`${url}api/palette`)).json();
  check(pal.planes.length === 8 && pal.disparity_ramp.length === 5 && pal.shadow !== pal.planes[1], `palette served: planes ${pal.planes.join(' ')}, shadow ${pal.shadow}`);
  const dispPixels = await page.evaluate((ramp) => {
    const cv = document.getElementById('disparity');
    const d = cv.getContext('2d').getImageData(0, 0, cv.width, cv.height).data;
    const stops = ramp.map((h) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16)));
    let coloured = 0, far = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (Math.max(d[i], d[i + 1], d[i + 2]) - Math.min(d[i], d[i + 1], d[i + 2]) > 60) ++coloured;
      if (d[i] === stops[0][0] && d[i + 1] === stops[0][1] && d[i + 2] === stops[0][2]) ++far;
    }
    return { coloured, far, total: d.length / 4 };
  }, pal.disparity_ramp);
  check(dispPixels.coloured > dispPixels.total / 3 && dispPixels.far > 0, `disparity drawn in the ramp: ${dispPixels.coloured} of ${dispPixels.total} px coloured, ${dispPixels.far} at the far end`);
  const legend = await page.$$eval('#overlay-legend > span', (items) => items.map((i) => [i.textContent, i.firstChild.style.background]));
  const rgb = (h) => `rgb(${[1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16)).join(', ')})`;
  check(planes.every((p) => legend.some(([t, c]) => t === `plane ${p.rank + 1}` && c === rgb(pal.planes[p.rank]))),
        `overlay legend: ${legend.map(([t]) => t).join(', ')} in the palette's colours`);
  const scale = await page.textContent('#disparity-far');
  check(/px \(far\)$/.test(scale), `disparity colour bar labelled "${scale}" ... "${await page.textContent('#disparity-near')}"`);
  // The proposals panel (1b) pushed the 3D view down the page: scroll to it
  // as the operator would, or the drag lands outside the viewport.
  await page.$eval('#view3d canvas', (e) => e.scrollIntoView({ block: 'center' }));
  const view = await (await page.$('#view3d canvas')).boundingBox();
  await page.mouse.move(view.x + view.width / 2, view.y + view.height / 2);
  await page.mouse.down();
  await page.mouse.move(view.x + view.width / 2 + 120, view.y + view.height / 2 + 20, { steps: 8 });
  await page.mouse.up();
  const turned = (await page.evaluate(() => window.petra.view3dStats())).camera;
  check(dist3(turned, cloud.camera) > 10, `dragging turns the 3D view (camera moved ${dist3(turned, cloud.camera).toFixed(0)} mm)`);
  await page.click('#view-arm');  // back to the framed view for the pictures
  await page.waitForTimeout(300);
  await page.locator('#products').screenshot({ path: path.join(shots, 'gnd_products.png') });

  // 8. A plane the evaluation does not have: ARM_GOTO fails with its reason.
  await page.evaluate((rank) => fetch('/api/command', { method: 'POST', body: JSON.stringify({ command: 'ARM_GOTO', args: { plane_rank: rank, standoff_mm: 50 } }) }), found);
  await until('ARM_GOTO NO_SUCH_PLANE on the page', async () => (await rowStatus('ARM_GOTO'))?.startsWith('FAILED: NO_SUCH_PLANE'), 5000);
  check(true, `command table: ARM_GOTO rank ${found}: ${await rowStatus('ARM_GOTO')}`);

  // 9. Pick the best plane: the planned pose (ghost arm) ends on its centroid.
  const p0 = planes[0];
  await page.click('#plane-table tbody tr[data-rank="0"]');
  await until('planned pose', async () => (await page.textContent('#arm-status')).startsWith('Planned plane 1'), 5000);
  const plan = await page.evaluate(() => window.petra.plan);
  check(plan.ok && dist3(plan.contact.tip_mm, p0.centroid_mm) < 1e-6, `plan: contact tip on the centroid, joints ${JSON.stringify(plan.contact.joint_deg.map((x) => +x.toFixed(2)))} deg`);
  const planTip = (await page.evaluate(() => window.petra.view3dStats())).planTip;
  check(planTip && dist3(planTip, p0.centroid_mm) < 0.01, `ghost arm drawn with its tip ${dist3(planTip, p0.centroid_mm).toFixed(4)} mm from the centroid`);
  await page.waitForTimeout(300);
  await page.locator('#products').screenshot({ path: path.join(shots, 'gnd_plan_3d.png') });
  await page.locator('#planes-panel').screenshot({ path: path.join(shots, 'gnd_planes.png') });

  // 10. ARM_GOTO: the arm model follows ARM_STATUS and reaches the plane.
  const nStatusBefore = raw.filter((m) => m.packet === 'ARM_STATUS').length;
  const tips = [];
  const sampler = setInterval(() => page.evaluate(() => window.petra.view3dStats()?.armTip).then((t) => t && tips.push(t)).catch(() => {}), 200);
  const tGoto = Date.now();
  await page.click('#send-goto');
  const armAck = await until('ARM_GOTO final acknowledgement', () => telemetry.find((m) => m.event === 'tlm' && m.data.tlm.packet === 'ACK' &&
    m.data.names.command === 'ARM_GOTO' && m.data.names.stage !== 'ACCEPTED' && m.data.names.reason !== 'NO_SUCH_PLANE'), 90000);
  check(armAck.data.names.stage === 'COMPLETED', `ARM_GOTO plane 0 ${armAck.data.names.stage} ${armAck.data.names.reason} after ${((Date.now() - tGoto) / 1000).toFixed(1)} s`);
  await page.waitForTimeout(800);  // the next ARM_STATUS
  clearInterval(sampler);
  const statuses = raw.filter((m) => m.packet === 'ARM_STATUS');
  const last = statuses[statuses.length - 1];
  const tipErr = dist3(last.tip_mm, p0.centroid_mm);
  const axisErr = Math.acos(Math.min(1, -last.axis.reduce((s, x, i) => s + x * p0.normal[i], 0))) * 180 / Math.PI;
  check(tipErr < 1, `arm tip (ARM_STATUS, measured joints) ${tipErr.toFixed(4)} mm from the plane centroid (target 1 mm); axis ${axisErr.toFixed(4)} deg off -normal; verification ${last.tip_error_mm.toFixed(4)} mm`);
  const shown = await page.evaluate(() => ({ t: window.petra.armTlm, s: window.petra.view3dStats() }));
  check(maxAbsDiff(shown.t.joint_deg, last.joint_deg) < 1e-4, `page's arm joints = last ARM_STATUS ${JSON.stringify(last.joint_deg.map((x) => +x.toFixed(3)))} deg`);
  check(dist3(shown.s.armTip, last.tip_mm) < 0.01, `3D arm model (ground kinematics) tip ${dist3(shown.s.armTip, last.tip_mm).toFixed(4)} mm from the onboard tip`);
  const distinct = tips.filter((t, i) => i === 0 || dist3(t, tips[i - 1]) > 1);
  check(statuses.length - nStatusBefore >= 8 && distinct.length >= 5, `the arm model moved through ${distinct.length} poses (${statuses.length - nStatusBefore} ARM_STATUS packets during the move)`);
  check(await page.evaluate(() => window.petra.events.some((e) => e.startsWith('ARM_REACHED'))), 'the page shows ARM_REACHED');
  await until('the page reports the arm at plane 1', async () => (await page.textContent('#arm-status')).startsWith('Arm reached plane 1'), 3000);
  await page.waitForTimeout(300);
  await page.locator('#products').screenshot({ path: path.join(shots, 'gnd_arm_3d.png') });
  await page.locator('#planes-panel').screenshot({ path: path.join(shots, 'gnd_arm.png') });
  await page.click('#view-rock');
  await page.waitForTimeout(300);
  await page.locator('#view3d').screenshot({ path: path.join(shots, 'gnd_arm_rock.png') });
  await page.click('#view-arm');

  // 11. A command petra-fsw rejects (IDLE cannot be re-entered from IDLE) and a
  // request the server refuses (out of range), both shown with their reason.
  await page.evaluate(() => fetch('/api/command', { method: 'POST', body: JSON.stringify({ command: 'SET_MODE', args: { mode: 1 } }) }));
  await until('SET_MODE rejection on the page', async () => (await rowStatus('SET_MODE'))?.startsWith('REJECTED: BAD_TRANSITION'), 5000);
  check(true, `command table: SET_MODE ${await rowStatus('SET_MODE')}`);
  const bad = await page.evaluate(async () => {
    const r = await fetch('/api/command', { method: 'POST', body: '{"command":"SELECT_ROI","args":{"planes":9}}' });
    return [r.status, (await r.json()).error];
  });
  check(bad[0] === 400 && bad[1].includes('SELECT_ROI.planes'), `out-of-range request refused: HTTP ${bad[0]} "${bad[1]}"`);
  await page.waitForTimeout(600);  // one more housekeeping packet
  await page.locator('#log').screenshot({ path: path.join(shots, 'gnd_log.png') });
  await page.screenshot({ path: path.join(shots, 'gnd_full.png'), fullPage: true });

  // Opened again after the evaluation (the old race: the cloud arrived before
  // three.js had loaded and a second WebGL view was made).
  await page.reload();
  const again = await until('the cloud in the 3D view after the reload', () => page.evaluate(() => {
    const s = window.petra?.view3dStats();
    return s && s.points > 0 && s.meshTriangles > 0 ? s : null;
  }), 15000);
  check(again.canvases === 1 && (await page.$$('#view3d canvas')).length === 1, `after a reload: one WebGL view, ${again.points} points, ${again.meshTriangles} triangles`);
  await page.waitForTimeout(300);
  await page.locator('#products').screenshot({ path: path.join(shots, 'gnd_products_reloaded.png') });

  await proposeAndPick(page, raw, finalAck, rowStatus, size);

  const offsite = requests.filter((u) => !u.startsWith(url));
  check(offsite.length === 0, `all ${requests.length} page requests went to ${url} (${offsite.join(', ') || 'none elsewhere'})`);
  check(pageErrors.length === 0, `no script errors on the page (${pageErrors.join('; ') || 'none'})`);

  // Open MCT with the Petra plugin: the dictionary's points, history from the
  // archive (HK plot against spacecraft time), the event list filtered by severity.
  const mct = await context.newPage();
  const mctErrors = [];
  mct.on('pageerror', (e) => mctErrors.push(String(e)));
  await mct.goto(`${url}openmct.html#/browse/petra:root/petra:HK/petra:HK.uptime_s`);
  await until('Open MCT started', () => mct.evaluate(() => window.openmctReady === true), 20000);
  const mctAsked = Date.now();
  const history = await mct.evaluate(async () => {
    const id = (key) => ({ namespace: 'petra', key });
    const now = Date.now();
    const hk = await openmct.objects.get(id('HK.uptime_s'));
    const points = await openmct.telemetry.request(hk, { start: now - 3600e3, end: now + 60e3 });
    const events = await openmct.objects.get(id('events'));
    const warnings = await openmct.telemetry.request(events, { start: now - 3600e3, end: now + 60e3,
      filters: { severity: { equals: ['WARNING', 'ERROR', 'FATAL'] } } });
    const all = await openmct.telemetry.request(events, { start: now - 3600e3, end: now + 60e3 });
    const acks = await openmct.telemetry.request(await openmct.objects.get(id('commands')), { start: now - 3600e3, end: now + 60e3 });
    const root = await openmct.composition.get(await openmct.objects.get(id('root'))).load();
    const gaps = await openmct.telemetry.request(await openmct.objects.get(id('gaps')), { start: now - 3600e3, end: now + 60e3 });
    return { hk: points.length, gaps: gaps.map((g) => `${g.packet} ${g.seq} ${g.missing}`), increasing: points.every((p, i) => i === 0 || p.value >= points[i - 1].value),
             warnings: warnings.map((e) => e.severity), all: all.length, acks: acks.map((a) => `${a.command} ${a.stage}`),
             folders: root.length };
  });
  // The archive commits at least every 0.5 s: what the relay passed on a second
  // before the request is in the history.
  const hkRelayed = raw.filter((m) => m.apid === 0x010).length;
  const hkCommitted = raw.filter((m) => m.apid === 0x010 && m.t <= mctAsked - 1000).length;
  check(history.hk >= hkCommitted && history.hk <= hkRelayed && history.hk > 10 && history.increasing,
        `Open MCT: ${history.hk} HK uptime_s points from the archive (relay: ${hkCommitted} a second before, ${hkRelayed} in all), uptime never decreasing`);
  check(history.warnings.length > 0 && history.warnings.every((s) => s !== 'INFO') && history.all > history.warnings.length,
        `Open MCT event list: ${history.warnings.length} of ${history.all} events at WARNING or above with the severity filter`);
  check(history.acks.includes('EVALUATE COMPLETED') && history.acks.includes('SET_MODE REJECTED'),
        `Open MCT command history: ${history.acks.length} acknowledgements (EVALUATE COMPLETED, SET_MODE REJECTED among them)`);
  const hkGap = lost.length === 1 ? `HK ${(lost[0].seq + 1) & 0x3FFF} 1` : 'none';
  check(history.gaps.includes(hkGap),
        `Open MCT link gaps from the archive: ${history.gaps.join(', ') || 'none'} (the relay lost HK seq ${lost.map((l) => l.seq).join(', ')})`);
  check(history.folders >= 9, `Open MCT tree: ${history.folders} items under Petra (tables and one folder per packet)`);
  await mct.waitForTimeout(2000);
  await mct.screenshot({ path: path.join(shots, 'gnd_openmct_hk_plot.png') });
  await mct.goto(`${url}openmct.html#/browse/petra:root/petra:events`);
  await mct.waitForTimeout(2000);
  await mct.screenshot({ path: path.join(shots, 'gnd_openmct_events.png') });
  check(mctErrors.length === 0, `no script errors in Open MCT (${mctErrors.join('; ') || 'none'})`);
  await mct.close();

  // The archive: stop petra-fsw, then the station; every packet the relay
  // passed on is in the station's archive (counts per APID equal).
  fsw.kill('SIGTERM');
  await new Promise((r) => setTimeout(r, 1500));
  gnd.kill('SIGTERM');
  await new Promise((r) => gnd.exitCode !== null ? r() : gnd.on('exit', r));
  const counted = execFileSync(petra, ['archive', 'query', '--db', path.join(work, 'archive.db'), '--count'], { encoding: 'utf8' });
  const archived = Object.fromEntries([...counted.matchAll(/apid +(\d+) +(\d+) packets/g)].map((m) => [Number(m[1]), Number(m[2])]));
  const relayed = {};
  for (const m of raw) relayed[m.apid] = (relayed[m.apid] || 0) + 1;
  check(JSON.stringify(archived) === JSON.stringify(relayed), `archive holds every packet per APID: ${JSON.stringify(archived)} (relay ${JSON.stringify(relayed)})`);
  const events = execFileSync(petra, ['archive', 'query', '--db', path.join(work, 'archive.db'), '--apid', 'EVENT', '--min-severity', 'WARNING'], { encoding: 'utf8' });
  check(/CMD_REJECTED_BAD_TRANSITION/.test(events) && !/ INFO /.test(events), `archive query of WARNING events and above: ${events.trim().split('\n').length} lines, the SET_MODE rejection among them`);

  follower.abort();
  relay.close();
  log(`screenshots in ${shots}`);
}

// 12. Rock proposals: PROPOSE over the whole pair from the panel; its table
// against the PROPOSALS packet decoded here; the picture; a click on the
// rock in the picture sends SELECT_PROPOSAL; EVALUATE then gives the plane
// the proposal listed.
async function proposeAndPick(page, raw, finalAck, rowStatus, size) {
  await page.$eval('#proposals-panel', (e) => e.scrollIntoView({ block: 'start' }));
  await page.click('#send-propose');
  const ack = await until('PROPOSE final acknowledgement', () => finalAck('PROPOSE'), 120000);
  check(ack.data.names.stage === 'COMPLETED', `PROPOSE ${ack.data.names.stage} ${ack.data.names.reason}`);
  const list = await until('PROPOSALS packet', () => raw.find((m) => m.packet === 'PROPOSALS'), 10000);
  check(list.crcOk && list.status === 0 && list.count >= 1 && list.plane_offered[0] === 1,
        `PROPOSALS ${list.proposal_id}: ${list.count} of ${list.candidates} rocks, rank 1 offers a plane`);
  await until('proposal rows', async () => (await page.$$('#proposal-table tbody tr')).length === list.count, 5000);
  const rows = await page.$$eval('#proposal-table tbody tr', (trs) => trs.map((tr) => [...tr.cells].slice(0, 3).map((td) => td.textContent)));
  for (let i = 0; i < list.count; ++i) {
    const [x, y, w, h] = list.roi_px.slice(4 * i, 4 * i + 4), [u, v] = list.click_px.slice(2 * i, 2 * i + 2);
    const expect = [String(list.rank[i]), `${x}, ${y}, ${w} × ${h}`, `${u}, ${v}`];
    check(JSON.stringify(rows[i]) === JSON.stringify(expect), `proposal row ${i + 1} = raw telemetry ${JSON.stringify(expect)}`);
  }
  const step = list.picture_step;
  // The canvas is 300 x 150 until the picture (PRODUCT 5) is drawn on it.
  const fits = ([w, h]) => Math.abs(w * step - size.width) < step && Math.abs(h * step - size.height) < step;
  const drawn = await until('the proposals picture', async () => {
    const wh = await page.evaluate(() => [document.getElementById('proposals-picture').width,
                                          document.getElementById('proposals-picture').height]);
    return step > 0 && fits(wh) ? wh : null;
  }, 30000);
  check(/^proposals \d+: /.test(await page.textContent('#proposals-caption')),
        `proposals picture drawn ${drawn.join(' x ')} px, 1/${step} of the image`);
  // The operator clicks the rock of proposal 1 on the picture.
  const pic = await (await page.$('#proposals-picture')).boundingBox();
  const [u, v] = list.click_px;
  await page.mouse.click(pic.x + (u + 0.5) / step * pic.width / drawn[0], pic.y + (v + 0.5) / step * pic.height / drawn[1]);
  const sent = await until('SELECT_PROPOSAL sent', () => telemetry.find((m) => m.event === 'sent' && m.data.command === 'SELECT_PROPOSAL'), 5000);
  check(sent.data.args.proposal_id === list.proposal_id && sent.data.args.rank === 1,
        `a click on rock 1 in the picture signs SELECT_PROPOSAL ${JSON.stringify(sent.data.args)}`);
  const selAck = await until('SELECT_PROPOSAL acknowledgement', () => finalAck('SELECT_PROPOSAL'), 10000);
  check(selAck.data.names.stage === 'COMPLETED', `SELECT_PROPOSAL ${selAck.data.names.stage} ${selAck.data.names.reason}`);
  await page.locator('#proposals-panel').screenshot({ path: path.join(shots, 'gnd_proposals.png') });
  // EVALUATE on the picked rock: the proposal's plane is among the planes.
  const evals = raw.filter((m) => m.packet === 'EVAL_RESULT').length;
  await page.click('#send-eval-picked');
  const result = await until('EVAL_RESULT of the picked proposal', () => raw.filter((m) => m.packet === 'EVAL_RESULT')[evals], 120000);
  const planes = await until(`${result.planes_found} GRIND_PLANE packets`, () => {
    const p = raw.filter((m) => m.packet === 'GRIND_PLANE' && m.eval_id === result.eval_id);
    return p.length >= result.planes_found && result.planes_found > 0 ? p : null;
  }, 10000);
  const n = list.normal.slice(0, 3), c = list.centroid_mm.slice(0, 3);
  const same = planes.find((p) => maxAbsDiff(p.normal, n) < 1e-6 && dist3(p.centroid_mm, c) < 1e-3);
  check(same, `EVALUATE on proposal 1 gives its plane (rank ${same?.rank}: normal ${n.map((x) => x.toFixed(4))}, centroid ${c.map((x) => x.toFixed(1))} mm)`);
  check(await rowStatus('SELECT_PROPOSAL') === 'COMPLETED', 'command table: SELECT_PROPOSAL COMPLETED');
}

let status = 0;
try {
  await main();
} catch (e) {
  console.error(`FAILED: ${e.message}`);
  if (pageErrors.length) console.error(`page errors: ${pageErrors.join('; ')}`);
  const events = telemetry.filter((m) => m.event === 'tlm' && m.data.tlm.packet === 'EVENT').map((m) => m.data.line);
  if (events.length) console.error(`last events:\n  ${events.slice(-15).join('\n  ')}`);
  for (const [name, file] of [['petra-fsw', 'fsw.log'], ['petra sim-arm', 'sim-arm.log']]) {
    const f = path.join(work, file);
    if (fs.existsSync(f)) console.error(`${name} log:\n${fs.readFileSync(f, 'utf8').slice(-2000)}`);
  }
  status = 1;
} finally {
  if (context) await context.close().catch(() => {});
  for (const p of children) if (p.exitCode === null) p.kill('SIGTERM');
  fs.rmSync(work, { recursive: true, force: true });
}
process.exit(status);
