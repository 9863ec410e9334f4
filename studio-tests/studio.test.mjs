// Browser tests of `trajkit studio`: a real headless Chromium (Debian's `chromium`) driven by
// playwright-core uses the page as a person would and compares what it shows with the API.
//
//   TRAJKIT_BIN=../target/release/trajkit node --test studio.test.mjs
//
// Environment: TRAJKIT_BIN (default ../target/release/trajkit), CHROMIUM (default
// /usr/bin/chromium), SCREENSHOTS (default ./screenshots).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdtempSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const BIN = process.env.TRAJKIT_BIN || '../target/release/trajkit';
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const SHOTS = process.env.SCREENSHOTS || 'screenshots';
const LESSONS = ['polynomials', 'catmull_rom', 'bspline', 'profiles', 'plan', 'primitives'];

let server;
let url;
let context;
let userDir;

/** Starts `trajkit studio` on a free port; resolves to its URL (the line it prints). */
function startServer() {
  return new Promise((resolve, reject) => {
    server = spawn(BIN, ['studio', '--addr', '127.0.0.1:0'], { stdio: ['ignore', 'pipe', 'inherit'] });
    let out = '';
    const timer = setTimeout(() => reject(new Error(`no URL from ${BIN} in 30 s: ${out}`)), 30000);
    server.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/\S+\//);
      if (m) {
        clearTimeout(timer);
        resolve(m[0]);
      }
    });
    server.on('exit', (code) => reject(new Error(`${BIN} exited with ${code}: ${out}`)));
  });
}

before(async () => {
  url = await startServer();
  userDir = mkdtempSync(join(tmpdir(), 'trajkit-chromium-'));
  mkdirSync(SHOTS, { recursive: true });
  context = await chromium.launchPersistentContext(userDir, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: 1280, height: 860 },
    acceptDownloads: true,
    args: [
      '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
    ],
  });
});

after(async () => {
  if (context) await context.close();
  if (server) server.kill('SIGINT');
  if (userDir) rmSync(userDir, { recursive: true, force: true });
});

/** The API's answer to `body` at `path`, fetched directly (not through the page). */
async function api(path, body) {
  const r = await fetch(new URL(path, url), {
    method: body === undefined ? 'GET' : 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: body === undefined ? undefined : JSON.stringify(body),
  });
  assert.equal(r.status, 200, `${path}: ${await r.clone().text()}`);
  return r.json();
}

/** Opens a lesson, collecting console errors, page errors and failed requests. */
async function open(lesson) {
  const page = await context.newPage();
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`page: ${e.message}`));
  page.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  page.on('response', (r) => { if (r.status() >= 400) errors.push(`HTTP ${r.status()}: ${r.url()}`); });
  await page.goto(`${url}#/${lesson}`);
  await page.waitForFunction((l) => document.body.dataset.ready === l, lesson, { timeout: 60000 });
  return { page, errors };
}

/** Waits until the page has no request in flight and has completed more than `before`. */
async function settled(page, before) {
  await page.waitForFunction(
    (b) => document.body.dataset.busy === '0' && Number(document.body.dataset.completed) > b,
    before,
    { timeout: 30000 },
  );
}

const completed = (page) => page.evaluate(() => Number(document.body.dataset.completed || 0));

for (const lesson of LESSONS) {
  test(`lesson ${lesson} loads with no console error`, async () => {
    const { page, errors } = await open(lesson);
    // Every plot the lesson drew has data in it.
    const drawn = await page.evaluate(() => [...document.querySelectorAll('svg path.series, svg path.curve')]
      .filter((p) => (p.getAttribute('d') || '').length > 20).length);
    assert.ok(drawn > 0, `${lesson}: nothing drawn`);
    assert.equal(await page.locator('[data-testid=error]:visible').count(), 0);
    await page.screenshot({ path: join(SHOTS, `${lesson}.png`) });
    assert.deepEqual(errors, []);
    await page.close();
  });
}

test('polynomials: the peak table is the library\'s', async () => {
  const { page, errors } = await open('polynomials');
  const rows = await page.locator('[data-testid=peak-table] tr').allInnerTexts();
  const r = await api('/api/polynomials', {});
  r.profiles.forEach((p, k) => {
    for (const c of p.peak_coefficients) assert.ok(rows[k + 1].includes(c.toFixed(4)), `${rows[k + 1]} lacks ${c.toFixed(4)}`);
  });
  assert.match(rows[1], /1\.5000\s+6\.0000\s+12\.0000/);
  assert.match(rows[2], /1\.8750\s+5\.7735\s+60\.0000/);
  assert.match(rows[3], /2\.1875\s+7\.5132\s+52\.5000/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('bspline: dragging a control point changes the curve only near it', async () => {
  const { page, errors } = await open('bspline');
  const curve = page.locator('[data-testid=bspline-curve]');
  const points = (d) => d.slice(1).split('L');
  const before = points(await curve.getAttribute('d'));
  assert.equal(before.length, 301);
  // Drag P6 (the last point) down and left.
  const box = await page.locator('[data-handle=P6] circle').boundingBox();
  const [x, y] = [box.x + box.width / 2, box.y + box.height / 2];
  const n = await completed(page);
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x - 60, y + 80, { steps: 8 });
  await page.mouse.up();
  await settled(page, n);
  const after = points(await curve.getAttribute('d'));
  assert.notDeepEqual(after, before, 'the curve did not change');
  // Local control: P6's basis function (degree 3, 7 points, clamped uniform knots) lives on
  // u ∈ [0.75, 1]; the curve before u = 0.75 (samples 0..225 of 301) must not move.
  assert.deepEqual(after.slice(0, 225), before.slice(0, 225));
  assert.notDeepEqual(after.slice(226), before.slice(226));
  // The support of the dragged point is highlighted on the curve and in the basis plot.
  assert.ok((await page.locator('[data-testid=support-curve]').getAttribute('d')).length > 50);
  assert.equal(await page.locator('[data-testid=weight-label]').innerText(), 'weight of P6');
  // NURBS: select P3, raise its weight to 5: the curve is pulled towards it.
  await page.locator('[data-testid=check-nurbs]').check();
  await settled(page, await completed(page) - 1);
  await page.locator('[data-handle=P3] circle').click();
  assert.equal(await page.locator('[data-testid=weight-label]').innerText(), 'weight of P3');
  const unweighted = await curve.getAttribute('d');
  const m = await completed(page);
  await page.locator('[data-testid=weight-5]').click();
  await settled(page, m);
  assert.match(await page.locator('[data-testid=weight-value]').innerText(), /w = 5/);
  assert.notEqual(await curve.getAttribute('d'), unweighted);
  assert.deepEqual(errors, []);
  await page.screenshot({ path: join(SHOTS, 'bspline-dragged.png') });
  await page.close();
});

test('profiles: moving the sliders shows the duration the API computes', async () => {
  const { page, errors } = await open('profiles');
  const shown = async () => [
    await page.locator('[data-testid=duration-trapezoid]').innerText(),
    await page.locator('[data-testid=duration-scurve]').innerText(),
  ];
  // The specification's defaults: D = 1, v = 0.6, a = 1, j = 4.
  assert.deepEqual(await shown(), ['2.267', '2.517']);
  const n = await completed(page);
  const jmax = page.locator('[data-testid=slider-jmax]');
  await jmax.focus();
  for (let k = 0; k < 40; k += 1) await page.keyboard.press('ArrowRight');
  const d = page.locator('[data-testid=slider-D]');
  await d.focus();
  for (let k = 0; k < 30; k += 1) await page.keyboard.press('ArrowRight');
  await settled(page, n);
  const values = await page.evaluate(() => Object.fromEntries(
    [...document.querySelectorAll('input[type=range]')].map((i) => [i.id, Number(i.value)])));
  assert.equal(values.jmax, 8);
  assert.equal(values.D, 1.3);
  const r = await api('/api/profiles', { distance: values.D, v_max: values.vmax, a_max: values.amax, j_max: values.jmax });
  assert.deepEqual(await shown(), [r.trapezoid.duration.toFixed(3), r.s_curve.duration.toFixed(3)]);
  // j_max doubled: the S-curve is a_max/j_max = 0.125 s longer than the trapezoid.
  assert.ok(Math.abs(r.s_curve.duration - r.trapezoid.duration - 0.125) < 1e-9);
  assert.deepEqual(errors, []);
  await page.close();
});

test('plan: the default path is planned, plotted and downloadable', async () => {
  const { page, errors } = await open('plan');
  const defaults = await api('/api/plan/defaults');
  const r = await api('/api/plan', {
    waypoints_file: { name: defaults.waypoints_name, text: defaults.waypoints_csv },
    limits: { preset: 'panda' },
    method: 'toppra',
    path: 'natural',
    gridpoints: 'auto',
    jerk_limit: true,
    rate: 200,
  });
  assert.equal(await page.locator('[data-testid=plan-duration]').innerText(), r.duration.toFixed(4));
  // 7 joints × (q, q̇, q̈, q⃛), each with a curve; the phase plane with its three curves.
  const plots = await page.locator('[data-testid=plan-plots] svg').count();
  assert.equal(plots, 28);
  const curves = await page.evaluate(() => [...document.querySelectorAll('[data-testid=plan-plots] path.series')]
    .filter((p) => p.getAttribute('d').split('L').length > 100).length);
  assert.equal(curves, 28);
  const phase = await page.locator('[data-testid=phase-0] path.series').count();
  assert.equal(phase, 3);
  assert.match(await page.locator('[data-testid=plan-verdict]').innerText(), /worst limit ratio 0\.9\d+/);
  // Download the CSV (1 kHz) and check it against the duration.
  const [download] = await Promise.all([
    page.waitForEvent('download'),
    page.locator('[data-testid=download-csv]').click(),
  ]);
  const csv = readFileSync(await download.path(), 'utf8').trim().split('\n');
  assert.match(csv[0], /^t,q_panda_joint1,q_panda_joint2,/);
  assert.equal(csv.length - 1, Math.floor(r.duration * 1000 + 1e-9) + 2);
  // Another method from the form: TOTG.
  await page.locator('[data-testid=select-method]').selectOption('totg');
  const n = await completed(page);
  await page.locator('[data-testid=plan-button]').click();
  await settled(page, n);
  const totg = await page.locator('[data-testid=plan-duration]').innerText();
  assert.notEqual(totg, r.duration.toFixed(4));
  // Upload limits: a MoveIt joint_limits.yaml, slower than the Panda, overriding the preset by
  // joint name (positions stay the preset's); TOPP-RA again.
  const joints = [1, 2, 3, 4, 5, 6, 7].map((j) => `  panda_joint${j}:\n    has_velocity_limits: true\n    max_velocity: 1.0\n`
    + '    has_acceleration_limits: true\n    max_acceleration: 5.0\n    has_jerk_limits: true\n    max_jerk: 1000\n').join('');
  await page.locator('[data-testid=limits-file]').setInputFiles({
    name: 'joint_limits.yaml', mimeType: 'text/yaml', buffer: Buffer.from(`joint_limits:\n${joints}`),
  });
  await page.locator('[data-testid=select-method]').selectOption('toppra');
  const m = await completed(page);
  await page.locator('[data-testid=plan-button]').click();
  await settled(page, m);
  const slower = Number(await page.locator('[data-testid=plan-duration]').innerText());
  assert.ok(slower > r.duration * 1.5, `${slower} vs ${r.duration}`);
  assert.match(await page.locator('[data-testid=plan-check]').innerText(), /100\.0 %|99\.\d %/);
  assert.deepEqual(errors, []);
  await page.close();
});

test('primitives: dragging the DMP goal moves the rollout\'s end', async () => {
  const { page, errors } = await open('primitives');
  const rollout = page.locator('[data-testid=dmp-rollout]');
  const before = await rollout.getAttribute('d');
  const box = await page.locator('[data-handle=goal] circle').boundingBox();
  const n = await completed(page);
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x - 40, box.y + 60, { steps: 6 });
  await page.mouse.up();
  await settled(page, n);
  assert.notEqual(await rollout.getAttribute('d'), before);
  await page.locator('[data-testid=replay]').click();
  await page.screenshot({ path: join(SHOTS, 'primitives-goal.png') });
  // Draw a demonstration with the mouse: the DMP is learned from it.
  await page.locator('[data-testid=draw-demo]').click();
  const area = await page.locator('[data-testid=dmp-area]').boundingBox();
  const n2 = await completed(page);
  await page.mouse.move(area.x + 60, area.y + area.height - 60);
  await page.mouse.down();
  for (let k = 1; k <= 20; k += 1) {
    await page.mouse.move(area.x + 60 + 20 * k, area.y + area.height - 60 - 10 * k + (k % 5) * 6);
    await page.waitForTimeout(15);
  }
  await page.mouse.up();
  await settled(page, n2);
  const info = await page.locator('[data-testid=dmp-info]').innerText();
  const samples = Number(info.match(/demonstration: (\d+) samples/)[1]);
  assert.ok(samples >= 3 && samples !== 76, info);
  // ProMP: the conditioned mean is drawn.
  assert.ok(await page.locator('[data-testid=promp-svg] path.c2').count() > 0);
  assert.deepEqual(errors, []);
  await page.close();
});
