// Requests to the studio's JSON API. The page computes nothing itself: every number it shows
// comes back from one of these calls.

let inFlight = 0;
let completed = 0;

function mark() {
  document.body.dataset.busy = String(inFlight);
  document.body.dataset.completed = String(completed);
}

/** An error answered by the API: {message, field, value}. */
export class ApiError extends Error {
  constructor(status, body) {
    const e = (body && body.error) || { message: `HTTP ${status}` };
    super(e.message);
    this.status = status;
    this.field = e.field;
    this.value = e.value;
  }
}

/** POST `body` as JSON to `path`; resolves to the parsed JSON answer (or the raw Response
 * when `raw` is set), rejects with ApiError. */
export async function post(path, body, { raw = false } = {}) {
  inFlight += 1;
  mark();
  try {
    const r = await fetch(path, {
      method: 'POST',
      headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify(body),
    });
    if (!r.ok) {
      let j = null;
      try { j = await r.json(); } catch (_) { /* not JSON */ }
      throw new ApiError(r.status, j);
    }
    return raw ? r : await r.json();
  } finally {
    inFlight -= 1;
    completed += 1;
    mark();
  }
}

/** GET `path` as JSON. */
export async function get(path) {
  const r = await fetch(path);
  if (!r.ok) throw new ApiError(r.status, null);
  return r.json();
}

/**
 * Coalesces requests while the user drags: `run(state)` is called with the newest state only,
 * one call at a time; states that arrive meanwhile replace each other. `onError` gets failures.
 */
export function coalesce(run, onError) {
  let busy = false;
  let pending = null;
  async function pump() {
    while (pending !== null) {
      const s = pending;
      pending = null;
      busy = true;
      try {
        await run(s);
        onError(null);
      } catch (e) {
        onError(e);
      } finally {
        busy = false;
      }
    }
  }
  return (state) => {
    pending = state;
    if (!busy) return pump();
    return Promise.resolve();
  };
}
