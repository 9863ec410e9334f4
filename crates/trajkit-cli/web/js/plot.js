// SVG drawing: line plots with axes, and a 2-D editing area with draggable handles.
// Pure drawing: the numbers plotted come from the API.

const NS = 'http://www.w3.org/2000/svg';

/** An SVG element with attributes. */
export function svgEl(tag, attrs = {}, parent = null) {
  const e = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v !== undefined && v !== null) e.setAttribute(k, String(v));
  }
  if (parent) parent.appendChild(e);
  return e;
}

/** Round tick values covering [lo, hi], about `count` of them. */
export function ticks(lo, hi, count = 5) {
  if (!(hi > lo)) return [lo];
  const raw = (hi - lo) / count;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) || raw;
  const out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
    out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  }
  return out;
}

/** A short label for a number. */
export function fmt(v, digits = 4) {
  if (v === null || v === undefined || Number.isNaN(v)) return '—';
  if (!Number.isFinite(v)) return v > 0 ? '∞' : '−∞';
  const a = Math.abs(v);
  if (a !== 0 && (a >= 1e5 || a < 1e-3)) return v.toExponential(2);
  return String(Number(v.toPrecision(digits)));
}

function extent(values) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of values) {
    if (v === null || !Number.isFinite(v)) continue;
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  return [lo, hi];
}

/** The `d` of a polyline through (x[i], y[i]); gaps at null values. */
export function pathD(xs, ys, sx, sy) {
  let d = '';
  let pen = false;
  for (let i = 0; i < xs.length; i += 1) {
    const x = xs[i];
    const y = ys[i];
    if (x === null || y === null || !Number.isFinite(x) || !Number.isFinite(y)) {
      pen = false;
      continue;
    }
    d += `${pen ? 'L' : 'M'}${sx(x).toFixed(2)},${sy(y).toFixed(2)}`;
    pen = true;
  }
  return d;
}

/**
 * A line plot.
 * opts: {width, height, title, xlabel, series: [{x, y, cls, label}], hlines: [{y, cls}],
 *        vlines: [{x, cls}], bands: [{x, lo, hi, cls}], impulses: [{x, up, cls}],
 *        ydomain: [lo, hi] (widened to the data), ycap: top of the y axis at most, xdomain,
 *        alert: bool, testid}
 */
export function linePlot(opts) {
  const W = opts.width || 260;
  const H = opts.height || 150;
  const m = { l: 46, r: 8, t: opts.title ? 18 : 6, b: opts.xlabel ? 30 : 18 };
  const svg = svgEl('svg', {
    viewBox: `0 0 ${W} ${H}`,
    class: `plot${opts.alert ? ' alert' : ''}`,
    'data-testid': opts.testid,
    role: 'img',
  });
  const xs = [];
  const ys = [];
  for (const s of opts.series || []) {
    xs.push(...s.x);
    ys.push(...s.y);
  }
  for (const b of opts.bands || []) {
    xs.push(...b.x);
    ys.push(...b.lo, ...b.hi);
  }
  let [x0, x1] = opts.xdomain || extent(xs);
  let [y0, y1] = extent(ys);
  for (const h of opts.hlines || []) {
    if (Number.isFinite(h.y) && h.fit !== false) {
      y0 = Math.min(y0, h.y);
      y1 = Math.max(y1, h.y);
    }
  }
  if (opts.ydomain) {
    y0 = Math.min(y0, opts.ydomain[0]);
    y1 = Math.max(y1, opts.ydomain[1]);
  }
  if (opts.ycap !== undefined && Number.isFinite(opts.ycap) && y1 > opts.ycap) y1 = opts.ycap;
  if (!Number.isFinite(x0)) { x0 = 0; x1 = 1; }
  if (!Number.isFinite(y0)) { y0 = -1; y1 = 1; }
  if (x1 <= x0) x1 = x0 + 1;
  if (y1 - y0 < 1e-12 * Math.max(1, Math.abs(y0))) { y0 -= 1; y1 += 1; }
  const pad = 0.06 * (y1 - y0);
  y0 -= pad;
  y1 += pad;
  const sx = (x) => m.l + ((x - x0) / (x1 - x0)) * (W - m.l - m.r);
  const sy = (y) => H - m.b - ((y - y0) / (y1 - y0)) * (H - m.t - m.b);
  svgEl('rect', { x: m.l, y: m.t, width: W - m.l - m.r, height: H - m.t - m.b, class: 'frame' }, svg);
  const grid = svgEl('g', { class: 'grid' }, svg);
  for (const t of ticks(y0, y1, 4)) {
    svgEl('line', { x1: m.l, x2: W - m.r, y1: sy(t), y2: sy(t) }, grid);
    svgEl('text', { x: m.l - 4, y: sy(t) + 3, class: 'tick', 'text-anchor': 'end' }, grid).textContent = fmt(t, 3);
  }
  for (const t of ticks(x0, x1, 5)) {
    svgEl('line', { x1: sx(t), x2: sx(t), y1: m.t, y2: H - m.b }, grid);
    svgEl('text', { x: sx(t), y: H - m.b + 11, class: 'tick', 'text-anchor': 'middle' }, grid).textContent = fmt(t, 3);
  }
  if (opts.title) {
    svgEl('text', { x: m.l, y: 12, class: 'title' }, svg).textContent = opts.title;
  }
  if (opts.xlabel) {
    svgEl('text', { x: (m.l + W - m.r) / 2, y: H - 4, class: 'label', 'text-anchor': 'middle' }, svg).textContent = opts.xlabel;
  }
  const clipId = `c${Math.random().toString(36).slice(2)}`;
  const clip = svgEl('clipPath', { id: clipId }, svgEl('defs', {}, svg));
  svgEl('rect', { x: m.l, y: m.t, width: W - m.l - m.r, height: H - m.t - m.b }, clip);
  const body = svgEl('g', { 'clip-path': `url(#${clipId})` }, svg);
  for (const b of opts.bands || []) {
    const top = pathD(b.x, b.hi, sx, sy);
    const rx = [...b.x].reverse();
    const rlo = [...b.lo].reverse();
    const bottom = pathD(rx, rlo, sx, sy).replace(/^M/, 'L');
    svgEl('path', { d: `${top}${bottom}Z`, class: b.cls || 'band' }, body);
  }
  for (const h of opts.hlines || []) {
    if (!Number.isFinite(h.y)) continue;
    svgEl('line', { x1: m.l, x2: W - m.r, y1: sy(h.y), y2: sy(h.y), class: h.cls || 'limit' }, body);
  }
  for (const v of opts.vlines || []) {
    svgEl('line', { x1: sx(v.x), x2: sx(v.x), y1: m.t, y2: H - m.b, class: v.cls || 'vline' }, body);
  }
  for (const s of opts.series || []) {
    svgEl('path', { d: pathD(s.x, s.y, sx, sy), class: `series ${s.cls || ''}`, 'data-label': s.label }, body);
  }
  for (const imp of opts.impulses || []) {
    const x = sx(imp.x);
    const yb = sy(0);
    const yt = imp.up ? m.t + 4 : H - m.b - 4;
    svgEl('line', { x1: x, x2: x, y1: yb, y2: yt, class: `impulse ${imp.cls || ''}` }, body);
    svgEl('path', { d: `M${x - 3},${yt + (imp.up ? 5 : -5)}L${x},${yt}L${x + 3},${yt + (imp.up ? 5 : -5)}`, class: `impulse ${imp.cls || ''}` }, body);
  }
  svg.scales = { sx, sy };
  return svg;
}

/**
 * A 2-D editing area with a fixed data domain. Returns {svg, layer(name), toPx, toData,
 * handle(...)}. Handles call onMove(x, y) while dragged and onDrop() on release.
 */
export function editArea({ width = 640, height = 380, domain = [[0, 10], [0, 6]], testid }) {
  const svg = svgEl('svg', { viewBox: `0 0 ${width} ${height}`, class: 'edit-area', 'data-testid': testid });
  const [[xa, xb], [ya, yb]] = domain;
  const m = 16;
  const toPx = ([x, y]) => [m + ((x - xa) / (xb - xa)) * (width - 2 * m), height - m - ((y - ya) / (yb - ya)) * (height - 2 * m)];
  const toData = (px, py) => [xa + ((px - m) / (width - 2 * m)) * (xb - xa), ya + ((height - m - py) / (height - 2 * m)) * (yb - ya)];
  svgEl('rect', { x: 0, y: 0, width, height, class: 'edit-bg' }, svg);
  const grid = svgEl('g', { class: 'grid' }, svg);
  for (let x = Math.ceil(xa); x <= xb; x += 1) {
    const [px] = toPx([x, ya]);
    svgEl('line', { x1: px, x2: px, y1: m, y2: height - m }, grid);
  }
  for (let y = Math.ceil(ya); y <= yb; y += 1) {
    const [, py] = toPx([xa, y]);
    svgEl('line', { x1: m, x2: width - m, y1: py, y2: py }, grid);
  }
  const layers = {};
  const layer = (name) => {
    if (!layers[name]) layers[name] = svgEl('g', { class: `layer-${name}` }, svg);
    return layers[name];
  };
  const clampData = ([x, y]) => [Math.min(xb, Math.max(xa, x)), Math.min(yb, Math.max(ya, y))];
  const eventData = (ev) => {
    const p = svg.createSVGPoint();
    p.x = ev.clientX;
    p.y = ev.clientY;
    const q = p.matrixTransform(svg.getScreenCTM().inverse());
    return clampData(toData(q.x, q.y));
  };
  function polyline(name, points, cls, attrs = {}) {
    const g = layer(name);
    g.replaceChildren();
    if (!points || points.length === 0) return null;
    const d = points.map((p, i) => `${i ? 'L' : 'M'}${toPx(p).map((v) => v.toFixed(2)).join(',')}`).join('');
    return svgEl('path', { d, class: cls, ...attrs }, g);
  }
  function handle(name, at, label, { onMove, onDrop, onGrab, cls = 'handle' } = {}) {
    const g = svgEl('g', { class: cls, 'data-handle': name }, layer('handles'));
    const c = svgEl('circle', { r: 8 }, g);
    const t = svgEl('text', { dx: 10, dy: -10 }, g);
    t.textContent = label;
    const place = ([x, y]) => {
      const [px, py] = toPx([x, y]);
      c.setAttribute('cx', px);
      c.setAttribute('cy', py);
      t.setAttribute('x', px);
      t.setAttribute('y', py);
    };
    place(at);
    c.addEventListener('pointerdown', (ev) => {
      ev.preventDefault();
      c.setPointerCapture(ev.pointerId);
      g.classList.add('dragging');
      if (onGrab) onGrab();
      const move = (e) => {
        const p = eventData(e);
        place(p);
        if (onMove) onMove(p);
      };
      const up = () => {
        g.classList.remove('dragging');
        c.removeEventListener('pointermove', move);
        c.removeEventListener('pointerup', up);
        c.removeEventListener('pointercancel', up);
        if (onDrop) onDrop();
      };
      c.addEventListener('pointermove', move);
      c.addEventListener('pointerup', up);
      c.addEventListener('pointercancel', up);
    });
    return { g, place, circle: c };
  }
  return { svg, layer, toPx, toData, eventData, polyline, handle, domain };
}
