// Lesson 3: the B-spline / NURBS editor (POST /api/bspline).

import { post, coalesce } from '../js/api.js';
import { editArea, linePlot, svgEl, fmt } from '../js/plot.js';
import { h, checkbox, select, errorBox, showError } from '../js/ui.js';

export async function mount(root) {
  const points = [[0.8, 1.0], [1.8, 4.8], [3.4, 5.2], [4.6, 1.4], [6.2, 1.2], [7.6, 4.8], [9.2, 3.2]];
  const s = {
    degree: 3,
    compare: true,
    polygon: true,
    nurbs: false,
    basis: true,
    weights: points.map(() => 1),
    selected: 3,
  };
  const err = errorBox();
  const area = editArea({ testid: 'bspline-area' });
  const basisBox = h('div', { 'data-testid': 'basis-plot' });
  const info = h('div', { class: 'muted' });
  const weightValue = h('span', { class: 'big', 'data-testid': 'weight-value' });
  const weightSlider = h('input', {
    type: 'range', min: 0.1, max: 10, step: 0.1, value: 1, 'data-testid': 'slider-weight', disabled: true,
  });
  weightSlider.addEventListener('input', () => {
    s.weights[s.selected] = Number(weightSlider.value);
    update({});
  });
  const setWeight5 = h('button', {
    class: 'secondary', 'data-testid': 'weight-5', disabled: true,
    onclick: () => { s.weights[s.selected] = 5; weightSlider.value = 5; update({}); },
  }, 'w = 5');
  const degrees = [1, 2, 3, 4, 5, 6].map((d) => [String(d), `degree ${d}`]);

  root.append(
    h('h2', {}, 'B-spline / NURBS: an interactive control-point editor'),
    h('p', { class: 'lead' },
      'C(u) = Σ P_i B_{i,k}(u) on a clamped uniform knot vector. Experiments: (1) drag a control point: ',
      'only the highlighted part of the curve moves (local control, the support of B_{i,k}); ',
      '(2) raise the degree: smoother, but the curve follows the points less closely; ',
      '(3) turn on NURBS and raise one weight to 5: the curve is pulled towards that point; ',
      '(4) the basis functions sum to 1 everywhere (partition of unity).'),
    h('div', { class: 'card' },
      h('div', { class: 'controls' },
        select({ id: 'degree', label: 'B-spline', options: degrees, value: '3', onChange: (v) => { s.degree = Number(v); update({}); } }),
        checkbox({ id: 'compare', label: 'compare degree 2', checked: true, onChange: (c) => { s.compare = c; update({}); } }),
        checkbox({ id: 'polygon', label: 'control polygon', checked: true, onChange: (c) => { s.polygon = c; drawPolygon(); } }),
        checkbox({ id: 'basis', label: 'basis functions', checked: true, onChange: (c) => { s.basis = c; update({}); } }),
        checkbox({
          id: 'nurbs', label: 'NURBS (weights)', checked: false,
          onChange: (c) => { s.nurbs = c; weightSlider.disabled = !c; setWeight5.disabled = !c; update({}); },
        }),
        h('label', { class: 'slider' }, h('span', { class: 'name', 'data-testid': 'weight-label' }, `weight of P${s.selected}`), weightSlider, weightValue),
        setWeight5),
      h('div', { class: 'legend' },
        h('span', {}, h('i', { class: 'c1' }), 'B-spline of the chosen degree'),
        h('span', {}, h('i', { class: 'c2' }), 'degree 2 on the same points'),
        h('span', {}, h('i', { class: 'gold' }), 'where the selected point acts (its support)'),
        h('span', {}, h('i', { class: 'grey' }), 'control polygon')),
      err,
      h('div', { class: 'split' }, h('div', {}, area.svg, info), basisBox)));

  const handles = points.map((p, i) => area.handle(`P${i}`, p, `P${i}`, {
    onGrab: () => select_(i),
    onMove: (q) => { points[i] = q; drawPolygon(); update({}); },
  }));
  area.svg.insertBefore(area.layer('polygon'), area.layer('handles'));
  area.svg.insertBefore(area.layer('support'), area.layer('handles'));
  area.svg.insertBefore(area.layer('curves'), area.layer('handles'));

  function select_(i) {
    s.selected = i;
    handles.forEach((hd, k) => hd.g.classList.toggle('selected', k === i));
    root.querySelector('[data-testid=weight-label]').textContent = `weight of P${i}`;
    weightSlider.value = s.weights[i];
    if (last) render(last);
  }

  function drawPolygon() {
    area.polyline('polygon', s.polygon ? points : [], 'polygon');
  }

  let last = null;
  async function run() {
    const r = await post('/api/bspline', {
      control_points: points,
      degree: s.degree,
      weights: s.nurbs ? s.weights : null,
      compare_degree: s.compare ? 2 : null,
      samples: 301,
      basis: s.basis,
    });
    last = r;
    render(r);
  }

  function render(r) {
    const i = s.selected;
    const [lo, hi] = r.support[i];
    const inSupport = r.curve.filter((_, m) => r.u[m] >= lo && r.u[m] <= hi);
    area.polyline('support', inSupport, 'curve support', { 'data-testid': 'support-curve' });
    const g = area.layer('curves');
    g.replaceChildren();
    const draw = (pts, cls, testid) => {
      const d = pts.map((p, m) => `${m ? 'L' : 'M'}${area.toPx(p).map((v) => v.toFixed(2)).join(',')}`).join('');
      svgEl('path', { d, class: cls, 'data-testid': testid }, g);
    };
    if (r.comparison) draw(r.comparison.curve, 'curve c2 dashed', 'bspline-compare');
    draw(r.curve, 'curve c1', 'bspline-curve');
    weightValue.textContent = s.nurbs ? `w = ${fmt(s.weights[i])}` : 'w = 1 (B-spline)';
    info.replaceChildren(
      `degree ${r.degree}${r.rational ? ' NURBS' : ''}, knots [${r.knots.map((k) => fmt(k, 3)).join(', ')}]; `,
      `P${i} acts on u ∈ [${fmt(lo, 3)}, ${fmt(hi, 3)}] (k + 2 = ${r.degree + 2} knots).`);
    basisBox.replaceChildren();
    if (r.basis) {
      const series = r.basis.values.map((v, k) => ({
        x: r.u, y: v, cls: k === i ? 'c2 hi' : 'thin', label: `B${k}`,
      }));
      series.push({ x: r.u, y: r.basis.sum, cls: 'c3 dashed', label: 'sum' });
      basisBox.append(
        h('h3', {}, r.rational ? 'Rational basis functions R_i(u) and their sum' : `Basis functions B_{i,${r.degree}}(u) and their sum`),
        linePlot({
          width: 420, height: 260, xlabel: 'u', xdomain: [0, 1], ydomain: [0, 1],
          bands: [{ x: [lo, hi], lo: [0, 0], hi: [1.05, 1.05], cls: 'band support' }],
          series,
          testid: 'basis-svg',
        }),
        h('div', { class: 'legend' },
          h('span', {}, h('i', { class: 'c2' }), `B${i} (selected point)`),
          h('span', {}, h('i', { class: 'c3' }), `Σ = ${fmt(Math.min(...r.basis.sum), 6)} … ${fmt(Math.max(...r.basis.sum), 6)}`)));
    }
  }

  drawPolygon();
  select_(s.selected);
  const update = coalesce(run, (e) => showError(err, e));
  await update({});
}
