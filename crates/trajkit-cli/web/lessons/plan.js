// Lesson 5: plan a path within a robot's limits (POST /api/plan, GET /api/plan/defaults).

import { post, get } from '../js/api.js';
import { linePlot, fmt } from '../js/plot.js';
import { h, select, checkbox, numberField, errorBox, showError } from '../js/ui.js';

const ORDERS = [
  ['q', 'q', 'position'],
  ['qd', 'q̇', 'velocity'],
  ['qdd', 'q̈', 'acceleration'],
  ['qddd', 'q⃛', 'jerk'],
];

/** Reads a chosen file as text: {name, text}. */
function readFile(input) {
  const f = input.files && input.files[0];
  if (!f) return Promise.resolve(null);
  return f.text().then((text) => ({ name: f.name, text }));
}

const METHOD_NAMES = { toppra: 'TOPP-RA', ni: 'NI (numerical integration)', totg: 'TOTG', poly: 'polynomials' };

export async function mount(root) {
  const defaults = await get('/api/plan/defaults');
  const s = {
    source: 'preset',
    preset: 'panda',
    limitsFile: null,
    format: 'auto',
    fillFrom: '',
    vScale: 1,
    aScale: 1,
    jScale: 1,
    waypointsName: defaults.waypoints_name,
    method: 'toppra',
    path: 'natural',
    gridpoints: 'auto',
    jerkLimit: true,
    maxDeviation: 0.1,
    degree: 'quintic',
    via: 'heuristic',
  };
  const err = errorBox();
  const results = h('div', { 'data-testid': 'plan-results' });
  const textarea = h('textarea', { rows: 10, spellcheck: 'false', 'data-testid': 'waypoints' }, defaults.waypoints_csv);
  textarea.addEventListener('input', () => { if (!s.waypointsName.endsWith('.json')) s.waypointsName = 'waypoints.csv'; });
  const limitsFileInput = h('input', { type: 'file', accept: '.urdf,.xml,.yaml,.yml,.json', 'data-testid': 'limits-file' });
  const limitsFileName = h('span', { class: 'muted' }, 'no file');
  limitsFileInput.addEventListener('change', async () => {
    s.limitsFile = await readFile(limitsFileInput);
    limitsFileName.textContent = s.limitsFile ? `${s.limitsFile.name} (${s.limitsFile.text.length} bytes)` : 'no file';
    if (s.limitsFile) { s.source = 'file'; sourceSel.querySelector('select').value = 'file'; }
  });
  const waypointsFileInput = h('input', { type: 'file', accept: '.csv,.json,.txt', 'data-testid': 'waypoints-file' });
  waypointsFileInput.addEventListener('change', async () => {
    const f = await readFile(waypointsFileInput);
    if (f) { textarea.value = f.text; s.waypointsName = f.name; }
  });
  const set = (k) => (v) => { s[k] = v; };
  const sourceSel = select({
    id: 'limits-source', label: 'Limits', value: 'preset',
    options: [['preset', 'robot preset'], ['file', 'uploaded file']],
    onChange: set('source'),
  });
  const methodOptions = h('div', { class: 'controls' });
  const planButton = h('button', { 'data-testid': 'plan-button', onclick: () => plan() }, 'Plan');
  const csvButton = h('button', { class: 'secondary', 'data-testid': 'download-csv', disabled: true, onclick: () => download('csv') }, 'Download CSV (1 kHz)');
  const jsonButton = h('button', { class: 'secondary', 'data-testid': 'download-json', disabled: true, onclick: () => download('json') }, 'Download JSON (1 kHz)');

  function drawMethodOptions() {
    const parts = [];
    if (s.method === 'toppra' || s.method === 'ni') {
      parts.push(
        select({ id: 'path', label: 'path', value: s.path, options: defaults.paths.map((p) => [p, p]), onChange: set('path') }),
        select({
          id: 'gridpoints', label: 'gridpoints', value: String(s.gridpoints),
          options: [['auto', 'auto (1e-4 of the optimum)'], ['100', '100'], ['1000', '1000'], ['10000', '10000']],
          onChange: (v) => { s.gridpoints = v === 'auto' ? 'auto' : Number(v); },
        }),
        checkbox({ id: 'jerk', label: 'bound jerk', checked: s.jerkLimit, onChange: set('jerkLimit') }));
    } else if (s.method === 'totg') {
      parts.push(numberField({ id: 'maxdev', label: 'max deviation [rad]', value: s.maxDeviation, step: 0.01, onChange: set('maxDeviation') }));
    } else {
      parts.push(
        select({ id: 'degree', label: 'degree', value: s.degree, options: [['cubic', 'cubic'], ['quintic', 'quintic'], ['septic', 'septic']], onChange: set('degree') }),
        select({ id: 'via', label: 'via velocities', value: s.via, options: [['heuristic', 'heuristic'], ['zero', 'zero (stop)']], onChange: set('via') }));
    }
    methodOptions.replaceChildren(...parts);
  }

  root.append(
    h('h2', {}, 'Plan: waypoints → a trajectory within the robot\'s limits'),
    h('p', { class: 'lead' },
      'The main job of trajkit: a planner\'s waypoints in joint space become a time-parameterized ',
      'trajectory (q, q̇, q̈, q⃛ for every joint) that respects velocity, acceleration and jerk limits. ',
      'The phase plane shows the path velocity ṡ along the path parameter s: the maximum velocity curve ',
      '(no admissible acceleration above it), the time-optimal profile riding it, and the profile played ',
      'after the jerk stage. The result is checked at 1 kHz against every limit before it is shown.'),
    h('div', { class: 'card form' },
      h('div', {},
        h('div', { class: 'controls' },
          sourceSel,
          select({ id: 'preset', label: 'preset', value: s.preset, options: defaults.presets.map((p) => [p, p]), onChange: (v) => { s.preset = v; s.source = 'preset'; sourceSel.querySelector('select').value = 'preset'; } })),
        h('div', { class: 'controls' },
          h('span', { class: 'name' }, 'limits file (URDF, trajkit JSON/YAML, or a MoveIt joint_limits.yaml that overrides the preset by joint name):'), limitsFileInput, limitsFileName),
        h('div', { class: 'controls' },
          select({ id: 'format', label: 'format', value: 'auto', options: [['auto', 'by extension'], ['urdf', 'URDF'], ['moveit', 'MoveIt YAML'], ['json', 'trajkit JSON'], ['yaml', 'trajkit YAML']], onChange: set('format') }),
          select({ id: 'fill', label: 'complete missing limits from', value: '', options: [['', '(nothing)'], ...defaults.presets.map((p) => [p, p])], onChange: set('fillFrom') })),
        h('div', { class: 'controls' },
          numberField({ id: 'vscale', label: 'velocity ×', value: 1, step: 0.1, onChange: set('vScale') }),
          numberField({ id: 'ascale', label: 'acceleration ×', value: 1, step: 0.1, onChange: set('aScale') }),
          numberField({ id: 'jscale', label: 'jerk ×', value: 1, step: 0.1, onChange: set('jScale') })),
        h('div', { class: 'controls' },
          select({
            id: 'method', label: 'Method', value: s.method,
            options: [['toppra', 'TOPP-RA'], ['ni', 'numerical integration'], ['totg', 'TOTG'], ['poly', 'polynomials']],
            onChange: (v) => { s.method = v; drawMethodOptions(); },
          })),
        methodOptions,
        h('div', { class: 'controls' }, planButton, csvButton, jsonButton)),
      h('div', {},
        h('div', { class: 'controls' }, h('span', { class: 'name' }, 'Waypoints (CSV: a row per waypoint, a column per joint; or JSON):'), waypointsFileInput),
        textarea)),
    err,
    results);
  drawMethodOptions();

  function request(rate) {
    // A MoveIt joint_limits.yaml carries velocities, accelerations and jerks, not the robot's
    // position ranges: as in MoveIt, it overrides the robot's (the preset's) limits by joint name.
    const moveit = s.source === 'file' && (s.format === 'moveit'
      || (s.format === 'auto' && /^joint_limits:/m.test(s.limitsFile.text)));
    const limits = s.source !== 'file'
      ? { preset: s.preset }
      : moveit
        ? { preset: s.preset, joint_limits: s.limitsFile }
        : { file: s.limitsFile, format: s.format === 'auto' ? null : s.format };
    if (s.fillFrom) limits.fill_from = s.fillFrom;
    if (s.vScale !== 1) limits.velocity_scale = s.vScale;
    if (s.aScale !== 1) limits.acceleration_scale = s.aScale;
    if (s.jScale !== 1) limits.jerk_scale = s.jScale;
    const body = {
      waypoints_file: { name: s.waypointsName, text: textarea.value },
      limits,
      method: s.method,
      rate,
    };
    if (s.method === 'toppra' || s.method === 'ni') {
      Object.assign(body, { path: s.path, gridpoints: s.gridpoints, jerk_limit: s.jerkLimit });
    } else if (s.method === 'totg') {
      body.max_deviation = s.maxDeviation;
    } else {
      Object.assign(body, { degree: s.degree, via_velocity: s.via });
    }
    return body;
  }

  async function plan() {
    if (s.source === 'file' && !s.limitsFile) {
      showError(err, { message: 'choose a limits file first, or pick a robot preset' });
      return;
    }
    planButton.disabled = true;
    try {
      const r = await post('/api/plan', request(200));
      showError(err, null);
      render(r);
      csvButton.disabled = false;
      jsonButton.disabled = false;
    } catch (e) {
      showError(err, e);
      results.replaceChildren();
      csvButton.disabled = true;
      jsonButton.disabled = true;
    } finally {
      planButton.disabled = false;
    }
  }

  async function download(format) {
    try {
      const r = await post(`/api/plan?format=${format}`, request(1000), { raw: true });
      const blob = await r.blob();
      const a = h('a', { href: URL.createObjectURL(blob), download: `trajectory.${format}` });
      document.body.appendChild(a);
      a.click();
      a.remove();
    } catch (e) {
      showError(err, e);
    }
  }

  function render(r) {
    const joints = r.check.joints;
    const worst = r.check.worst;
    const summary = h('div', { class: 'card' },
      h('div', { class: 'controls' },
        h('span', {}, `${METHOD_NAMES[r.method]}: T = `, h('span', { class: 'big', 'data-testid': 'plan-duration' }, r.duration.toFixed(4)), ' s'),
        h('span', {}, `${r.waypoints.length} waypoints, ${r.joint_names.length} joints`,
          r.removed_duplicates ? `, ${r.removed_duplicates} duplicate(s) removed` : ''),
        h('span', { class: worst <= 1 + 1e-6 ? 'good' : 'bad', 'data-testid': 'plan-verdict' },
          `worst limit ratio ${fmt(worst, 6)} (checked at ${fmt(r.check_rate)} Hz)`)),
      h('ul', { class: 'notes' }, r.notes.map((n) => h('li', {}, n))),
      h('table', { class: 'data', 'data-testid': 'plan-check' },
        h('tr', {}, ['joint', 'velocity', 'acceleration', 'jerk', 'position range used'].map((t) => h('th', {}, t))),
        joints.map((j, k) => h('tr', {},
          h('td', {}, `${k + 1} ${j.name}`),
          ['velocity', 'acceleration', 'jerk'].map((o) => {
            const p = j[o] && j[o].pointwise;
            return h('td', {}, p ? `${(100 * p.ratio).toFixed(1)} %` : 'not checked');
          }),
          h('td', {}, `${fmt(j.position.min)} … ${fmt(j.position.max)} in [${fmt(r.limits[k].position[0])}, ${fmt(r.limits[k].position[1])}]`)))));
    const grid = h('div', { class: 'joints', 'data-testid': 'plan-plots' },
      h('div', {}), ...ORDERS.map(([, t]) => h('div', { class: 'colhead' }, t)));
    r.joint_names.forEach((name, j) => {
      grid.appendChild(h('div', { class: 'rowhead' }, `${j + 1} ${name}`));
      for (const [key, , limitName] of ORDERS) {
        const [lo, hi] = r.limits[j][limitName];
        grid.appendChild(linePlot({
          width: 230,
          height: 110,
          testid: `plan-${j}-${key}`,
          xdomain: [0, r.duration],
          series: [{ x: r.samples.t, y: r.samples[key][j], cls: 'c1' }],
          hlines: [{ y: lo, fit: key !== 'qddd' }, { y: hi, fit: key !== 'qddd' }],
        }));
      }
    });
    const phase = h('div', { class: 'card', 'data-testid': 'phase-plane' }, h('h3', {}, 'Phase plane (s, ṡ)'));
    if (r.phase_plane) {
      phase.appendChild(h('div', { class: 'legend' },
        h('span', {}, h('i', { class: 'mvc' }), 'maximum velocity curve'),
        h('span', {}, h('i', { class: 'c1' }), `${METHOD_NAMES[r.method]} profile`),
        h('span', {}, h('i', { class: 'c3' }), 'played (after the jerk stage)')));
      const row = h('div', { class: 'split' });
      r.phase_plane.pieces.forEach((p, k) => {
        const series = [
          { x: p.s, y: p.mvc, cls: 'mvc' },
          { x: p.s, y: p.solver, cls: 'c1' },
        ];
        if (p.played) series.push({ x: p.played.s, y: p.played.sd, cls: 'c3 dashed' });
        const top = Math.max(...p.solver) * 1.6;
        row.appendChild(h('div', {},
          h('div', { class: 'muted' }, `piece ${k + 1} (starts at t = ${fmt(p.start_time)} s)`),
          linePlot({ width: 520, height: 240, xlabel: 's (path length)', series, ydomain: [0, 0], testid: `phase-${k}`, ycap: top })));
      });
      phase.appendChild(row);
    } else {
      phase.appendChild(h('p', { class: 'muted' }, 'No phase plane: polynomial segments are not a timing of one geometric path.'));
    }
    results.replaceChildren(summary, phase, h('div', { class: 'card' }, h('h3', {}, 'Joints: q, q̇, q̈, q⃛ with their limits (dashed)'), grid));
  }

  await plan();
}
