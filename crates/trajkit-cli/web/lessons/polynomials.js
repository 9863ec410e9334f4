// Lesson 1: cubic, quintic and septic rest-to-rest profiles (POST /api/polynomials).

import { post, coalesce } from '../js/api.js';
import { linePlot, fmt } from '../js/plot.js';
import { h, numberField, errorBox, showError } from '../js/ui.js';

const COLORS = { cubic: 'c1', quintic: 'c2', septic: 'c3' };
const ORDERS = [
  ['q', 'q(t)', null],
  ['qd', 'q̇(t)', 'velocity'],
  ['qdd', 'q̈(t)', 'acceleration'],
  ['qddd', 'q⃛(t)', 'jerk'],
];

export async function mount(root) {
  const state = { delta_q: 1, duration: 1, velocity: 2.175, acceleration: 15, jerk: 7500 };
  const err = errorBox();
  const plots = h('div', { class: 'grid4', 'data-testid': 'poly-plots' });
  const tables = h('div', {});
  const set = (k) => (v) => { state[k] = v; update(state); };
  root.append(
    h('h2', {}, 'Point-to-point polynomials: cubic, quintic, septic'),
    h('p', { class: 'lead' },
      'One rest-to-rest move q: 0 → Δq in T seconds with each of the three polynomials. ',
      'Higher order makes more derivatives vanish at the ends (smoother start and stop) ',
      'at the price of higher peaks: the peak velocity is Δq/T·c_v with c_v = 1.5, 1.875, 2.1875. ',
      'Change Δq, T and the joint limits (default: Panda joint 1) and see which profile exceeds them.'),
    h('div', { class: 'card' },
      h('div', { class: 'controls' },
        numberField({ id: 'dq', label: 'Δq [rad]', value: state.delta_q, step: 0.1, onChange: set('delta_q') }),
        numberField({ id: 'T', label: 'T [s]', value: state.duration, step: 0.1, onChange: set('duration') }),
        numberField({ id: 'vmax', label: 'q̇max', value: state.velocity, step: 0.1, onChange: set('velocity') }),
        numberField({ id: 'amax', label: 'q̈max', value: state.acceleration, step: 1, onChange: set('acceleration') }),
        numberField({ id: 'jmax', label: 'q⃛max', value: state.jerk, step: 100, onChange: set('jerk') })),
      h('div', { class: 'legend' },
        h('span', {}, h('i', { class: 'c1' }), 'cubic'),
        h('span', {}, h('i', { class: 'c2' }), 'quintic'),
        h('span', {}, h('i', { class: 'c3' }), 'septic'),
        h('span', {}, '– – robot limit (a red frame: exceeded)')),
      err, plots),
    tables);

  async function run(s) {
    const r = await post('/api/polynomials', {
      delta_q: s.delta_q,
      duration: s.duration,
      samples: 201,
      limits: { velocity: s.velocity, acceleration: s.acceleration, jerk: s.jerk },
    });
    render(r, s);
  }

  function render(r, s) {
    plots.replaceChildren(h('div', {}), ...ORDERS.map(([, title]) => h('div', { class: 'colhead' }, title)));
    for (const p of r.profiles) {
      plots.appendChild(h('div', { class: 'rowhead' }, `${p.degree} (${p.order}°)`,
        h('div', { class: 'muted' }, `coeffs: ${p.coefficients.filter((c) => c !== 0).map((c) => fmt(c)).join(', ')}`)));
      ORDERS.forEach(([key, title, limitName], k) => {
        const lim = limitName ? s[limitName] : null;
        const exceeded = limitName && p.exceeds.includes(limitName);
        plots.appendChild(linePlot({
          width: 240,
          height: 130,
          testid: `poly-${p.degree}-${key}`,
          alert: exceeded,
          series: [{ x: p.samples.t, y: p.samples[key][0], cls: COLORS[p.degree] }],
          hlines: lim ? [{ y: lim, fit: false }, { y: -lim, fit: false }] : [{ y: r.delta_q, cls: 'vline' }],
          title: k === 0 ? `T = ${fmt(r.duration)} s` : `peak ${fmt(p.peaks[k - 1])}`,
        }));
      });
    }
    const mark = (ok, yes, no) => h('td', { class: ok ? 'good' : 'bad' }, ok ? yes : no);
    tables.replaceChildren(h('div', { class: 'card' },
      h('h3', {}, 'Peak coefficients of the unit move (0 → 1 in T = 1) and the boundary'),
      h('table', { class: 'data', 'data-testid': 'peak-table' },
        h('tr', {}, ['order', 'peak |q̇|·T', 'peak |q̈|·T²', 'peak |q⃛|·T³', 'q̇ = 0 at ends?', 'q̈ = 0?', 'q⃛ = 0?'].map((t) => h('th', {}, t))),
        r.profiles.map((p) => h('tr', {},
          h('td', {}, `${p.degree} (${p.order}°)`),
          p.peak_coefficients.map((c) => h('td', {}, c.toFixed(4))),
          p.zero_at_ends.map((z, k) => mark(z, '✓', `✗ (jumps: ${fmt(p.at_start[k])} at t = 0)`))))),
      h('h3', {}, `This move: Δq = ${fmt(r.delta_q)} in T = ${fmt(r.duration)} s against the limits`),
      h('table', { class: 'data', 'data-testid': 'limit-table' },
        h('tr', {}, ['order', 'peak |q̇|', 'peak |q̈|', 'peak |q⃛|', 'verdict', 'shortest T within the limits'].map((t) => h('th', {}, t))),
        r.profiles.map((p) => h('tr', {},
          h('td', {}, p.degree),
          p.peaks.map((v, k) => h('td', { class: p.limit_ratios[k] > 1 ? 'bad' : '' }, `${fmt(v)} (${(100 * p.limit_ratios[k]).toFixed(1)} %)`)),
          h('td', { class: p.exceeds.length ? 'bad' : 'good' }, p.exceeds.length ? `exceeds ${p.exceeds.join(', ')}` : 'within limits'),
          h('td', {}, `${fmt(p.min_duration)} s`)))),
      h('p', { class: 'muted' }, 'Percentages are peak / limit. For the cubic the jerk is a constant 12·Δq/T³ between two impulses at the ends.')));
  }

  const update = coalesce(run, (e) => showError(err, e));
  await update(state);
}
