// End-to-end test of the ground station: petra-fsw on a simulated scene,
// `petra gnd serve` bridging it, headless Chromium driving the page as an
// operator would. Usage: node e2e_gnd.mjs PETRA PETRA_FSW BUILD_DIR
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

async function main() {
  // 1. A simulated scene and petra-fsw's configuration (as `petra demo`).
  // Rendered once per build tree: scenes are deterministic, and rendering one
  // in a Debug build takes most of the test's time.
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
  const config = { uplink: { host: '127.0.0.1', port: cmdPort, key_file: 'petra.key' },
                   downlink: { host: '127.0.0.1', port: tlmPort },
                   budget: { image_width: size.width, image_height: size.height, arena_mb: 512 },
                   camera: { kind: 'file', dir: 'pairs' } };
  if (fs.existsSync(path.join(scene, 'calib.json'))) config.calib = path.join(scene, 'calib.json');
  fs.writeFileSync(path.join(work, 'fsw.json'), JSON.stringify(config));
  log(`scene seed 1: ${size.width} x ${size.height}, ROI [${truth.roi}], c = ${c}`);

  // 2. The ground station first (it listens for telemetry), then petra-fsw.
  const gnd = spawn(petra, ['gnd', 'serve', '--port', '0', '--key', path.join(work, 'petra.key'),
    '--cmd-port', String(cmdPort), '--tlm-port', String(tlmPort), '--left-image', path.join(scene, 'left.png')],
    { stdio: ['ignore', 'pipe', 'inherit'] });
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
  const telemetry = [];
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
  const offsite = [];
  page.on('request', (r) => { if (!r.url().startsWith(url)) offsite.push(r.url()); });
  page.on('pageerror', (e) => pageErrors.push(String(e)));
  // Console errors other than HTTP statuses (the test's own refused request is one).
  page.on('console', (m) => { if (m.type() === 'error' && !m.text().startsWith('Failed to load resource')) pageErrors.push(m.text()); });
  await page.goto(url);
  await until('the scene image on the page', () => page.evaluate(() => document.getElementById('left').width > 0), 10000);
  await until('petra-fsw housekeeping in IDLE', () => page.evaluate(() => window.petra.hk?.names.mode === 'IDLE'), 15000);
  const view3d = await until('the 3D view', () => page.evaluate(() => window.petra.view3d !== 'loading' && window.petra.view3d), 10000);
  check(view3d === 'ready', `3D view (three.js from /vendor, WebGL): ${view3d}`);
  check(await page.evaluate(() => window.petra.events.some((e) => e.startsWith('BOOT_COMPLETE'))), 'the page shows the BOOT_COMPLETE event');

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
  await page.click('#send-eval');
  const finalAck = (name) => telemetry.find((m) => m.event === 'tlm' && m.data.tlm.packet === 'ACK' &&
    m.data.names.command === name && m.data.names.stage !== 'ACCEPTED');
  const selAck = await until('SELECT_ROI acknowledgement', () => finalAck('SELECT_ROI'), 10000);
  check(selAck.data.names.stage === 'COMPLETED', `SELECT_ROI ${selAck.data.names.stage} ${selAck.data.names.reason}`);
  const sentSel = telemetry.find((m) => m.event === 'sent' && m.data.command === 'SELECT_ROI').data;
  const a = sentSel.args;
  check(a.x_px === sel.roi.x && a.y_px === sel.roi.y && a.w_px === sel.roi.w && a.h_px === sel.roi.h &&
        a.planes === c && a.has_click === 1 && a.click_u_px === sel.click.u && a.click_v_px === sel.click.v, `signed SELECT_ROI carries the dragged ROI, point and c: ${JSON.stringify(sentSel.args)}`);
  const evalAck = await until('EVALUATE final acknowledgement', () => finalAck('EVALUATE'), 120000);
  const evalStage = evalAck.data.names.stage, evalReason = evalAck.data.names.reason;
  const rowStatus = (name) => page.evaluate((n) => [...document.querySelectorAll('#cmd-table tbody tr')]
    .filter((tr) => tr.dataset.command === n).map((tr) => tr.cells[3].textContent)[0], name);
  await until('EVALUATE status in the command table', async () => (await rowStatus('EVALUATE'))?.startsWith(evalStage), 3000);
  check(await rowStatus('SELECT_ROI') === 'COMPLETED', 'command table: SELECT_ROI COMPLETED');

  let planesChecked = false;
  if (evalStage === 'COMPLETED') {
    // 6. Planes: the table against the GRIND_PLANE telemetry.
    const result = await until('EVAL_RESULT', () => telemetry.find((m) => m.event === 'tlm' && m.data.tlm.packet === 'EVAL_RESULT'), 10000);
    const found = result.data.tlm.fields.planes_found;
    const planes = await until(`${found} GRIND_PLANE packets`, () => {
      const p = telemetry.filter((m) => m.event === 'tlm' && m.data.tlm.packet === 'GRIND_PLANE').map((m) => m.data.tlm.fields);
      return p.length >= found ? p : null;
    }, 10000);
    check(found > 0, `${found} grind planes of ${c} requested`);
    await until('plane rows', async () => (await page.$$('#plane-table tbody tr')).length === found, 5000);
    const rows = await page.$$eval('#plane-table tbody tr', (trs) => trs.map((tr) => [...tr.cells].map((td) => td.textContent)));
    for (const p of planes) {
      const row = rows[p.rank];
      const expect = [String(p.rank), `(${p.normal.map((x) => x.toFixed(3)).join(', ')})`,
        `(${p.centroid_mm.map((x) => x.toFixed(1)).join(', ')})`, p.area_mm2.toFixed(0), p.flatness_rms_mm.toFixed(2), String(p.triangles)];
      check(JSON.stringify(row) === JSON.stringify(expect), `plane row ${p.rank} = telemetry ${JSON.stringify(expect)}`);
    }
    await until('disparity, overlay and point cloud products', () => page.evaluate(() =>
      ['disparity', 'overlay', 'point_cloud'].every((k) => window.petra.products[k])), 30000);
    await page.click('#plane-table tbody tr[data-rank="0"]');
    await until('planned pose', async () => (await page.textContent('#arm-status')).startsWith('Planned plane 0'), 3000);
    await page.waitForTimeout(500);
    await page.locator('#products').screenshot({ path: path.join(shots, 'gnd_products.png') });
    await page.locator('#planes-panel').screenshot({ path: path.join(shots, 'gnd_planes.png') });
    await page.click('#send-goto');
    const armAck = await until('ARM_GOTO final acknowledgement', () => finalAck('ARM_GOTO'), 60000);
    if (armAck.data.names.stage === 'COMPLETED') {
      check((await page.textContent('#arm-status')).startsWith('Arm reached plane 0'), 'the page shows the arm at plane 0');
    } else {
      const text = await until('arm rejection on the page', async () => {
        const t = await page.textContent('#arm-status');
        return t.includes(armAck.data.names.reason) ? t : null;
      }, 3000);
      check(true, `ARM_GOTO ${armAck.data.names.stage} shown with its reason: "${text}"`);
    }
    await page.locator('#planes-panel').screenshot({ path: path.join(shots, 'gnd_arm.png') });
    planesChecked = true;
  } else {
    // No pipeline in this build: the refusal must reach the operator with its reason.
    check(await rowStatus('EVALUATE') === `${evalStage}: ${evalReason}`, `command table: EVALUATE ${evalStage}: ${evalReason}`);
    check((await page.textContent('#planes-status')).includes(evalReason), `plane panel explains: ${await page.textContent('#planes-status')}`);
    await page.locator('#planes-panel').screenshot({ path: path.join(shots, 'gnd_planes.png') });
  }

  // 7. A command petra-fsw rejects (IDLE cannot be re-entered from IDLE) and a
  // request the server refuses (out of range), both shown with their reason.
  await page.evaluate(() => fetch('/api/command', { method: 'POST', body: JSON.stringify({ command: 'SET_MODE', args: { mode: 1 } }) }));
  await until('SET_MODE rejection on the page', async () => (await rowStatus('SET_MODE'))?.startsWith('REJECTED: BAD_TRANSITION'), 5000);
  check(true, `command table: SET_MODE ${await rowStatus('SET_MODE')}`);
  const bad = await page.evaluate(async () => {
    const r = await fetch('/api/command', { method: 'POST', body: '{"command":"SELECT_ROI","args":{"planes":9}}' });
    return [r.status, (await r.json()).error];
  });
  check(bad[0] === 400 && bad[1].includes('SELECT_ROI.planes'), `out-of-range request refused: HTTP ${bad[0]} "${bad[1]}"`);
  await page.waitForTimeout(1200);  // one more housekeeping packet
  await page.locator('#log').screenshot({ path: path.join(shots, 'gnd_log.png') });
  await page.screenshot({ path: path.join(shots, 'gnd_full.png'), fullPage: true });

  check(offsite.length === 0, `no request left localhost (${offsite.join(', ') || 'none'})`);
  check(pageErrors.length === 0, `no script errors on the page (${pageErrors.join('; ') || 'none'})`);
  follower.abort();
  if (!planesChecked)
    log(`NOTE: EVALUATE ${evalStage} ${evalReason}: this build has no pipeline, so planes, products and the arm were not checked`);
  log(`screenshots in ${shots}`);
}

let status = 0;
try {
  await main();
} catch (e) {
  console.error(`FAILED: ${e.message}`);
  if (pageErrors.length) console.error(`page errors: ${pageErrors.join('; ')}`);
  const fswLog = path.join(work, 'fsw.log');
  if (fs.existsSync(fswLog)) console.error(`petra-fsw log:\n${fs.readFileSync(fswLog, 'utf8').slice(-2000)}`);
  status = 1;
} finally {
  if (context) await context.close().catch(() => {});
  for (const p of children) if (p.exitCode === null) p.kill('SIGTERM');
  fs.rmSync(work, { recursive: true, force: true });
}
process.exit(status);
