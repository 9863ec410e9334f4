// Lesson 2: Catmull-Rom splines through draggable points (POST /api/catmull-rom).

import { post, coalesce } from '../js/api.js';
import { editArea, svgEl, fmt } from '../js/plot.js';
import { h, checkbox, errorBox, showError } from '../js/ui.js';

const KINDS = [
  ['uniform', 'uniform (α = 0)', 'c1'],
  ['centripetal', 'centripetal (α = ½)', 'c2'],
  ['chordal', 'chordal (α = 1)', 'c3'],
];

export async function mount(root) {
  const points = [[1, 1], [2.6, 4.6], [4.4, 4.2], [6.2, 1.4], [8.8, 3.6]];
  const shown = { uniform: true, centripetal: true, chordal: true };
  const err = errorBox();
  const area = editArea({ testid: 'catmull-area' });
  const knots = h('div', {});
  root.append(
    h('h2', {}, 'Catmull-Rom spline: drag the points'),
    h('p', { class: 'lead' },
      'An interpolating cubic spline: it passes through every point with a continuous tangent (C¹), ',
      'each tangent set by the neighbouring points. The three variants differ in the knot spacing ',
      '‖P_{i+1} − P_i‖^α: uniform curves can form cusps and loops when points are unevenly spaced, ',
      'centripetal ones cannot, chordal ones hug long chords. Drag a point close to its neighbour to see it.'),
    h('div', { class: 'card' },
      h('div', { class: 'controls' },
        KINDS.map(([k, label]) => checkbox({
          id: `cr-${k}`, label, checked: true, onChange: (c) => { shown[k] = c; update({}); },
        }))),
      h('div', { class: 'legend' }, KINDS.map(([, label, c]) => h('span', {}, h('i', { class: c }), label))),
      err, area.svg, knots));

  points.forEach((p, i) => area.handle(`P${i}`, p, `P${i}`, {
    onMove: (q) => { points[i] = q; update({}); },
  }));

  async function run() {
    const kinds = KINDS.map(([k]) => k).filter((k) => shown[k]);
    if (kinds.length === 0) {
      area.layer('curves').replaceChildren();
      return;
    }
    const r = await post('/api/catmull-rom', { points, kinds, samples_per_segment: 40 });
    area.layer('curves').replaceChildren();
    const g = area.layer('curves');
    for (const c of r.curves) {
      const cls = KINDS.find(([k]) => k === c.kind)[2];
      const d = c.points.map((p, i) => `${i ? 'L' : 'M'}${area.toPx(p).map((v) => v.toFixed(2)).join(',')}`).join('');
      svgEl('path', { d, class: `curve ${cls}`, 'data-testid': `curve-${c.kind}` }, g);
    }
    knots.replaceChildren(h('table', { class: 'data' },
      h('tr', {}, h('th', {}, 'variant'), points.map((_, i) => h('th', {}, `t${i}`))),
      r.curves.map((c) => h('tr', {}, h('td', {}, c.kind), c.parameters.map((t) => h('td', {}, fmt(t)))))),
    h('p', { class: 'muted' }, 'Knot parameters t_i of the points (t₀ = 0, t_{i+1} = t_i + ‖P_{i+1} − P_i‖^α), from trajkit::spline::CatmullRom.'));
  }

  // The curves sit below the handles.
  area.svg.insertBefore(area.layer('curves'), area.layer('handles'));
  const update = coalesce(run, (e) => showError(err, e));
  await update({});
}
