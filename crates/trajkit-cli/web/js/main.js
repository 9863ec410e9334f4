// The page shell: navigation between lessons (one module per lesson, loaded on demand).

import { h } from './ui.js';

const LESSONS = [
  ['polynomials', '1 · Polynomials'],
  ['catmull_rom', '2 · Catmull-Rom'],
  ['bspline', '3 · B-spline / NURBS'],
  ['profiles', '4 · Trapezoid vs S-curve'],
  ['plan', '5 · Plan'],
  ['primitives', '6 · Primitives'],
];

const nav = document.getElementById('nav');
const main = document.getElementById('lesson');

for (const [id, title] of LESSONS) {
  nav.appendChild(h('a', { href: `#/${id}`, 'data-lesson': id }, title));
}

async function show() {
  const id = (location.hash.replace(/^#\/?/, '') || LESSONS[0][0]).split('?')[0];
  const known = LESSONS.find(([l]) => l === id) ? id : LESSONS[0][0];
  for (const a of nav.querySelectorAll('a')) a.classList.toggle('active', a.dataset.lesson === known);
  const root = h('section', { class: 'lesson', 'data-lesson': known });
  main.replaceChildren(root);
  document.body.dataset.ready = '';
  const mod = await import(`../lessons/${known}.js`);
  await mod.mount(root);
  if (main.contains(root)) {
    root.dataset.ready = '1';
    document.body.dataset.ready = known;
  }
}

window.addEventListener('hashchange', show);
show();
