// Lesson 4: trapezoidal vs S-curve velocity profiles (POST /api/profiles).

import { post, coalesce } from '../js/api.js';
import { linePlot, fmt } from '../js/plot.js';
import { h, slider, errorBox, showError } from '../js/ui.js';

const ORDERS = [
  ['q', 'q(t)'],
  ['qd', 'q̇(t)'],
  ['qdd', 'q̈(t)'],
  ['qddd', 'q⃛(t)'],
];

export async function mount(root) {
  const s = { distance: 1, v_max: 0.6, a_max: 1, j_max: 4 };
  const err = errorBox();
  const plots = h('div', { class: 'grid4', 'data-testid': 'profile-plots' });
  const tTrap = h('span', { class: 'big', 'data-testid': 'duration-trapezoid' }, '…');
  const tS = h('span', { class: 'big', 'data-testid': 'duration-scurve' }, '…');
  const set = (k) => (v) => { s[k] = v; update({ ...s }); };
  root.append(
    h('h2', {}, 'Trapezoidal vs S-curve'),
    h('p', { class: 'lead' },
      'The trapezoid has three phases (accelerate, cruise, decelerate): its acceleration jumps, so ',
      'its jerk is a train of impulses. The S-curve limits jerk too: up to seven phases, the acceleration ',
      'is a trapezoid and the velocity an "S". It takes longer (here by a_max/j_max) but excites fewer ',
      'vibrations. Raise j_max and the S-curve approaches the trapezoid. Both come from trajkit\'s online ',
      'generator (the Ruckig-class otg), the trapezoid with an unlimited jerk.'),
    h('div', { class: 'card' },
      h('div', { class: 'controls' },
        slider({ id: 'D', label: 'D (distance)', min: 0.1, max: 5, step: 0.01, value: s.distance, onInput: set('distance') }),
        slider({ id: 'vmax', label: 'v_max', min: 0.05, max: 3, step: 0.01, value: s.v_max, onInput: set('v_max') }),
        slider({ id: 'amax', label: 'a_max', min: 0.05, max: 5, step: 0.01, value: s.a_max, onInput: set('a_max') }),
        slider({ id: 'jmax', label: 'j_max', min: 0.1, max: 50, step: 0.1, value: s.j_max, onInput: set('j_max') })),
      h('div', { class: 'controls' },
        h('span', {}, 'Trapezoidal: T = ', tTrap, ' s'),
        h('span', {}, 'S-curve: T = ', tS, ' s')),
      err, plots));

  async function run(state) {
    const r = await post('/api/profiles', { ...state, samples: 301 });
    render(r, state);
  }

  function render(r, st) {
    tTrap.textContent = r.trapezoid.duration.toFixed(3);
    tS.textContent = r.s_curve.duration.toFixed(3);
    plots.replaceChildren(h('div', {}), ...ORDERS.map(([, t]) => h('div', { class: 'colhead' }, t)));
    const limits = [null, st.v_max, st.a_max, st.j_max];
    for (const [name, p, cls] of [['Trapezoidal', r.trapezoid, 'c1'], ['S-curve', r.s_curve, 'c2']]) {
      plots.appendChild(h('div', { class: 'rowhead' }, name, h('div', { class: 'muted' }, `T = ${p.duration.toFixed(3)} s`)));
      const T = p.duration;
      ORDERS.forEach(([key], k) => {
        const lim = limits[k];
        const opts = {
          width: 240,
          height: 130,
          testid: `profile-${name === 'S-curve' ? 'scurve' : 'trapezoid'}-${key}`,
          xdomain: [0, T],
          series: [{ x: p.samples.t, y: p.samples[key][0], cls }],
          hlines: lim ? [{ y: lim, fit: true }, { y: -lim, fit: true }] : [{ y: st.distance, cls: 'vline' }],
          vlines: p.phases.slice(1).map((ph) => ({ x: ph.t })),
          title: k === 0 ? `D = ${fmt(st.distance)}` : `${['', 'v', 'a', 'j'][k]}_max = ${fmt(lim)}`,
        };
        if (key === 'qddd' && name === 'Trapezoidal') {
          // Acceleration jumps between phases: jerk impulses (drawn as arrows).
          const imps = [];
          let prev = 0;
          for (const ph of p.phases) {
            if (ph.start[2] !== prev) imps.push({ x: ph.t, up: ph.start[2] > prev });
            prev = ph.end[2];
          }
          if (prev !== 0) imps.push({ x: T, up: prev < 0 });
          opts.impulses = imps;
          opts.hlines = [];
          opts.ydomain = [-1, 1];
          opts.title = 'impulses (unbounded jerk)';
        }
        plots.appendChild(linePlot(opts));
      });
    }
  }

  const update = coalesce(run, (e) => showError(err, e));
  await update({ ...s });
}
