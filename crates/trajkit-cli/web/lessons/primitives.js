// Lesson 6: movement primitives. DMP replay with a dragged goal (POST /api/dmp); ProMP mean
// and band with a draggable via point (POST /api/promp).

import { post, get, coalesce } from '../js/api.js';
import { editArea, linePlot, svgEl, fmt } from '../js/plot.js';
import { h, checkbox, errorBox, showError } from '../js/ui.js';

export async function mount(root) {
  const demos = await get('/assets/lessons/demos.json');
  const dmpErr = errorBox();
  const prompErr = errorBox();
  const area = editArea({ testid: 'dmp-area', width: 560, height: 340 });
  const dmpInfo = h('div', { class: 'muted', 'data-testid': 'dmp-info' });
  const prompBox = h('div', { class: 'overlay-wrap', 'data-testid': 'promp-plot' });
  const prompInfo = h('div', { class: 'muted' });
  let demo = demos.dmp;
  let goal = demo.q[demo.q.length - 1].slice();
  let drawing = false;
  let rollout = null;

  const drawButton = h('button', { class: 'secondary', 'data-testid': 'draw-demo', onclick: () => startDrawing() }, 'Draw a demonstration');
  const resetButton = h('button', { class: 'secondary', onclick: () => { demo = demos.dmp; goal = demo.q[demo.q.length - 1].slice(); goalHandle.place(goal); updateDmp({}); } }, 'Load the example');
  const replayButton = h('button', { 'data-testid': 'replay', onclick: () => replay() }, 'Replay');

  const via = { on: true, t: 1.0, y: 1.6 };
  root.append(
    h('h2', {}, 'Movement primitives: DMP and ProMP'),
    h('p', { class: 'lead' },
      'A DMP learns one demonstration as a damped spring towards the goal plus a learned forcing term ',
      '(α_z = 25, β_z = 6.25). Drag the goal: the motion keeps the demonstrated style and converges to the new goal. ',
      'A ProMP learns a distribution over several demonstrations: its mean and a ±2σ band; conditioning on a ',
      'via point (drag it) gives the posterior that passes through it.'),
    h('div', { class: 'split' },
      h('div', { class: 'card' },
        h('h3', {}, 'DMP: drag the goal (orange), then replay'),
        h('div', { class: 'controls' }, drawButton, resetButton, replayButton),
        h('div', { class: 'legend' },
          h('span', {}, h('i', { class: 'grey' }), 'demonstration'),
          h('span', {}, h('i', { class: 'c1' }), 'reproduction (demo goal)'),
          h('span', {}, h('i', { class: 'c2' }), 'rollout to the new goal')),
        dmpErr, area.svg, dmpInfo),
      h('div', { class: 'card' },
        h('h3', {}, 'ProMP: mean and ±2σ band; drag the via point'),
        h('div', { class: 'controls' },
          checkbox({ id: 'via', label: 'condition on the via point', checked: true, onChange: (c) => { via.on = c; updatePromp({}); } })),
        h('div', { class: 'legend' },
          h('span', {}, h('i', { class: 'grey' }), 'demonstrations'),
          h('span', {}, h('i', { class: 'c1' }), 'prior mean ± 2σ'),
          h('span', {}, h('i', { class: 'c2' }), 'conditioned mean ± 2σ')),
        prompErr, prompBox, prompInfo)));

  area.svg.insertBefore(area.layer('demo'), area.layer('handles'));
  area.svg.insertBefore(area.layer('repro'), area.layer('handles'));
  area.svg.insertBefore(area.layer('rollout'), area.layer('handles'));
  area.svg.insertBefore(area.layer('dot'), area.layer('handles'));
  const goalHandle = area.handle('goal', goal, 'goal', {
    cls: 'handle goal',
    onMove: (p) => { goal = p; updateDmp({}); },
  });

  async function runDmp() {
    area.polyline('demo', demo.q, 'curve demo');
    const r = await post('/api/dmp', { demo, goal, samples: 301 });
    rollout = r.rollout;
    area.polyline('repro', r.reproduction.q, 'curve c1 dashed');
    area.polyline('rollout', r.rollout.q, 'curve c2', { 'data-testid': 'dmp-rollout' });
    const end = r.rollout.q[r.rollout.q.length - 1];
    dmpInfo.textContent = `goal (${fmt(r.goal[0], 3)}, ${fmt(r.goal[1], 3)}); rollout ends at (${fmt(end[0], 3)}, ${fmt(end[1], 3)}) after ${fmt(r.rollout.duration)} s; demonstration: ${demo.t.length} samples.`;
  }

  function replay() {
    if (!rollout) return;
    const dot = area.layer('dot');
    dot.replaceChildren();
    const c = svgEl('circle', { r: 7, class: 'dot' }, dot);
    const r = rollout;
    const t0 = performance.now();
    const step = (now) => {
      const t = (now - t0) / 1000;
      // Show the sample at or before t (the samples are the rollout's own).
      let k = 0;
      while (k + 1 < r.t.length && r.t[k + 1] <= t) k += 1;
      const [px, py] = area.toPx(r.q[k]);
      c.setAttribute('cx', px);
      c.setAttribute('cy', py);
      if (t < r.duration) requestAnimationFrame(step);
    };
    requestAnimationFrame(step);
  }

  function startDrawing() {
    if (drawing) return;
    drawing = true;
    drawButton.textContent = 'Draw with the mouse…';
    const pts = [];
    const ts = [];
    let t0 = 0;
    const down = (ev) => {
      ev.preventDefault();
      area.svg.setPointerCapture(ev.pointerId);
      t0 = ev.timeStamp;
      pts.length = 0;
      ts.length = 0;
      pts.push(area.eventData(ev));
      ts.push(0);
      area.svg.addEventListener('pointermove', move);
    };
    const move = (ev) => {
      const t = (ev.timeStamp - t0) / 1000;
      if (t <= ts[ts.length - 1] + 0.004) return;
      pts.push(area.eventData(ev));
      ts.push(t);
      area.polyline('demo', pts, 'curve demo');
    };
    const up = () => {
      area.svg.removeEventListener('pointerdown', down);
      area.svg.removeEventListener('pointermove', move);
      area.svg.removeEventListener('pointerup', up);
      drawing = false;
      drawButton.textContent = 'Draw a demonstration';
      if (pts.length >= 3) {
        demo = { t: ts.slice(), q: pts.map((p) => p.slice()) };
        goal = pts[pts.length - 1].slice();
        goalHandle.place(goal);
      }
      updateDmp({});
    };
    area.svg.addEventListener('pointerdown', down);
    area.svg.addEventListener('pointerup', up);
  }

  // The via point lives on an overlay with the plot's view box, so that re-drawing the plot
  // while it is dragged does not interrupt the drag.
  const W = 520;
  const H = 320;
  const overlay = svgEl('svg', { viewBox: `0 0 ${W} ${H}`, class: 'overlay' });
  const viaDot = svgEl('circle', { r: 8, class: 'via-handle', 'data-testid': 'via-handle' }, overlay);
  let scales = null;
  let duration = 2;
  const placeVia = () => {
    viaDot.style.display = via.on && scales ? '' : 'none';
    if (!scales) return;
    viaDot.setAttribute('cx', scales.sx(via.t));
    viaDot.setAttribute('cy', scales.sy(via.y));
  };
  viaDot.addEventListener('pointerdown', (ev) => {
    ev.preventDefault();
    viaDot.setPointerCapture(ev.pointerId);
    const move = (e) => {
      const p = overlay.createSVGPoint();
      p.x = e.clientX;
      p.y = e.clientY;
      const q = p.matrixTransform(overlay.getScreenCTM().inverse());
      // The plot's scales are affine: invert them from two points.
      const { sx, sy } = scales;
      via.t = Math.min(duration, Math.max(0, (q.x - sx(0)) / (sx(1) - sx(0))));
      via.y = (q.y - sy(0)) / (sy(1) - sy(0));
      placeVia();
      updatePromp({});
    };
    const up = () => {
      viaDot.removeEventListener('pointermove', move);
      viaDot.removeEventListener('pointerup', up);
    };
    viaDot.addEventListener('pointermove', move);
    viaDot.addEventListener('pointerup', up);
  });

  async function runPromp() {
    const body = { demos: demos.promp, samples: 201 };
    if (via.on) body.via = [{ t: via.t, q: [via.y], variance: 1e-4 }];
    const r = await post('/api/promp', body);
    const series = demos.promp.map((d) => ({ x: d.t, y: d.q.map((q) => q[0]), cls: 'thin' }));
    const bands = [{ x: r.t, lo: r.prior.lower[0], hi: r.prior.upper[0], cls: 'band' }];
    series.push({ x: r.t, y: r.prior.mean[0], cls: 'c1' });
    if (r.posterior) {
      bands.push({ x: r.t, lo: r.posterior.lower[0], hi: r.posterior.upper[0], cls: 'band c2' });
      series.push({ x: r.t, y: r.posterior.mean[0], cls: 'c2', label: 'posterior' });
    }
    const svg = linePlot({
      width: W, height: H, xlabel: 't [s]', series, bands, xdomain: [0, r.duration], ydomain: [-0.6, 2.6], testid: 'promp-svg',
    });
    scales = svg.scales;
    duration = r.duration;
    prompBox.replaceChildren(svg, overlay);
    placeVia();
    prompInfo.textContent = `duration ${fmt(r.duration)} s (mean of ${demos.promp.length} demonstrations); `
      + (r.posterior ? `via point y(${fmt(via.t, 3)}) = ${fmt(via.y, 3)}, variance 1e-4` : 'no via point');
  }

  const updateDmp = coalesce(runDmp, (e) => showError(dmpErr, e));
  const updatePromp = coalesce(runPromp, (e) => showError(prompErr, e));
  await Promise.all([updateDmp({}), updatePromp({})]);
}
