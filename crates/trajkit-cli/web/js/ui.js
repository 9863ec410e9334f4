// Small DOM helpers shared by the lessons: elements, labelled sliders, checkboxes, errors.

/** An element with attributes and children (strings become text). */
export function h(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === null || v === false) continue;
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else if (v === true) e.setAttribute(k, '');
    else e.setAttribute(k, String(v));
  }
  for (const c of children.flat()) {
    if (c === null || c === undefined || c === false) continue;
    e.appendChild(typeof c === 'string' || typeof c === 'number' ? document.createTextNode(String(c)) : c);
  }
  return e;
}

/** A labelled range slider showing its value; `onInput(value)` on every change. */
export function slider({ id, label, min, max, step, value, unit = '', onInput }) {
  const out = h('output', { for: id }, String(value));
  const input = h('input', {
    type: 'range', id, min, max, step, value, 'data-testid': `slider-${id}`,
  });
  input.addEventListener('input', () => {
    out.textContent = input.value;
    onInput(Number(input.value));
  });
  return h('label', { class: 'slider' }, h('span', { class: 'name' }, label), input, h('span', { class: 'value' }, out, unit));
}

/** A labelled number field; `onChange(value)` when it changes to a number. */
export function numberField({ id, label, value, step = 'any', min, onChange }) {
  const input = h('input', { type: 'number', id, value, step, min, 'data-testid': `input-${id}` });
  input.addEventListener('change', () => {
    const v = Number(input.value);
    if (input.value !== '' && Number.isFinite(v)) onChange(v);
  });
  return h('label', { class: 'field' }, h('span', { class: 'name' }, label), input);
}

/** A labelled checkbox; `onChange(checked)`. */
export function checkbox({ id, label, checked = false, onChange }) {
  const input = h('input', { type: 'checkbox', id, checked, 'data-testid': `check-${id}` });
  input.addEventListener('change', () => onChange(input.checked));
  return h('label', { class: 'check' }, input, label);
}

/** A labelled select of [value, text] pairs; `onChange(value)`. */
export function select({ id, label, options, value, onChange }) {
  const s = h('select', { id, 'data-testid': `select-${id}` },
    options.map(([v, t]) => h('option', { value: v, selected: v === value }, t)));
  s.addEventListener('change', () => onChange(s.value));
  return h('label', { class: 'field' }, h('span', { class: 'name' }, label), s);
}

/** Shows an API error (or clears it when `err` is null) in `box`. */
export function showError(box, err) {
  box.replaceChildren();
  box.hidden = !err;
  if (!err) return;
  box.appendChild(h('strong', {}, err.status ? `Refused (${err.status}): ` : 'Error: '));
  box.appendChild(document.createTextNode(err.message));
  if (err.field) box.appendChild(h('span', { class: 'field-name' }, ` [field: ${err.field}]`));
}

/** An error box (hidden until used). */
export function errorBox() {
  return h('div', { class: 'error', role: 'alert', hidden: true, 'data-testid': 'error' });
}
