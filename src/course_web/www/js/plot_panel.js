// A live plot of numeric topic fields, typed as for rqt_plot (`/turtle1/pose/x:y`, several
// paths separated by spaces or commas). The server resolves the paths (/api/plot); the page
// subscribes to each topic and plots the last 20 s against the time each message arrived.
import {ask, whenHidden} from './api.js';

const SPAN_S = 20;
// At most 20 samples a second per topic, the newest (the server drops the rest): a 20 s plot shows no more,
// and a 62.5 Hz pose sent whole would cost the server and the page three times as much.
const THROTTLE_MS = 50;
const COLOURS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2', '#7f7f7f', '#bcbd22', '#17becf'];
const MARGIN = {left: 56, right: 10, top: 10, bottom: 24};

// The number at `steps` ([[name, index|null], ...]) of a message as the bridge sends it.
export function valueAt(message, steps) {
  let value = message;
  for (const [name, index] of steps) {
    if (value === null || typeof value !== 'object') return null;
    value = value[name];
    if (index !== null && index !== undefined) {
      if (typeof value === 'string') {  // uint8[] and char[] travel as base64
        const bytes = atob(value);
        value = index < bytes.length ? bytes.charCodeAt(index) : null;
      } else {
        value = Array.isArray(value) && index < value.length ? value[index] : null;
      }
    }
  }
  if (value && typeof value === 'object' && 'secs' in value) return value.secs + value.nsecs / 1e9;
  if (typeof value === 'boolean') return value ? 1 : 0;
  return typeof value === 'number' && Number.isFinite(value) ? value : null;
}

function niceStep(range) {
  const raw = range / 5;
  const power = Math.pow(10, Math.floor(Math.log10(raw)));
  return [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw);
}

export function mount(bridge, root) {
  const form = root.querySelector('#plot-form');
  const input = root.querySelector('#plot-path');
  const message = root.querySelector('#plot-message');
  const canvas = root.querySelector('#plot-canvas');
  const legend = root.querySelector('#plot-legend');
  const context = canvas.getContext('2d');
  let series = [];        // {label, colour, points: [[t, v]]}
  let subscriptions = []; // [id, topic]
  let samples = 0;
  let latest = 0;         // the last plot asked for: an older answer that arrives later is dropped
  let answers = 0;        // answers come back (used or dropped), as data-answers for tests

  function stop() {
    for (const [id, topic] of subscriptions) bridge.unsubscribe(id, topic);
    subscriptions = [];
  }

  async function start(spec) {
    const asked = ++latest;
    let answer;
    let failure = null;
    try {
      answer = await ask('plot', {path: spec});
    } catch (error) {
      failure = error;
    }
    root.dataset.answers = String(++answers);
    if (asked !== latest) return;
    if (failure) {
      message.textContent = failure.message;
      root.dataset.error = failure.message;
      // A topic nobody publishes yet (the page was opened first): try again while it is asked for.
      if (/does not exist/.test(failure.message)) {
        setTimeout(() => { if (asked === latest) start(spec); }, 3000);
      }
      return;
    }
    stop();
    delete root.dataset.error;
    message.textContent = '';
    series = answer.fields.map((field, i) => ({...field, colour: COLOURS[i % COLOURS.length], points: []}));
    legend.replaceChildren(...series.map((s) => {
      const item = document.createElement('span');
      item.style.color = s.colour;
      item.textContent = '— ' + s.label;
      return item;
    }));
    const byTopic = new Map();
    for (const s of series) (byTopic.get(s.topic) || byTopic.set(s.topic, []).get(s.topic)).push(s);
    for (const [topic, list] of byTopic) {
      const id = bridge.subscribe(topic, list[0].type, (msg) => {
        const now = performance.now() / 1000;
        for (const s of list) {
          const value = valueAt(msg, s.steps);
          if (value !== null) { s.points.push([now, value]); samples += 1; }
        }
      }, {queue_length: 1, throttle_rate: THROTTLE_MS});
      subscriptions.push([id, topic]);
    }
  }

  function render() {
    const now = performance.now() / 1000;
    const width = canvas.width;
    const height = canvas.height;
    context.fillStyle = '#fff';
    context.fillRect(0, 0, width, height);
    let low = Infinity;
    let high = -Infinity;
    for (const s of series) {
      while (s.points.length && s.points[0][0] < now - SPAN_S) s.points.shift();
      for (const [, v] of s.points) { low = Math.min(low, v); high = Math.max(high, v); }
    }
    if (!Number.isFinite(low)) { low = -1; high = 1; }
    if (high - low < 1e-9) { low -= 1; high += 1; }
    const pad = (high - low) * 0.05;
    low -= pad; high += pad;
    const plotW = width - MARGIN.left - MARGIN.right;
    const plotH = height - MARGIN.top - MARGIN.bottom;
    const px = (t) => MARGIN.left + (t - (now - SPAN_S)) / SPAN_S * plotW;
    const py = (v) => MARGIN.top + (high - v) / (high - low) * plotH;
    context.strokeStyle = '#ddd';
    context.fillStyle = '#555';
    context.font = '11px sans-serif';
    context.lineWidth = 1;
    const step = niceStep(high - low);
    for (let v = Math.ceil(low / step) * step; v <= high; v += step) {
      context.beginPath(); context.moveTo(MARGIN.left, py(v)); context.lineTo(width - MARGIN.right, py(v)); context.stroke();
      context.fillText(Number(v.toPrecision(6)).toString(), 4, py(v) + 4);
    }
    for (let s = 0; s <= SPAN_S; s += 5) context.fillText('-' + (SPAN_S - s) + ' s', px(now - SPAN_S + s) - 12, height - 6);
    context.strokeStyle = '#888';
    context.strokeRect(MARGIN.left, MARGIN.top, plotW, plotH);
    context.lineWidth = 2;
    for (const s of series) {
      context.strokeStyle = s.colour;
      context.beginPath();
      s.points.forEach(([t, v], i) => (i ? context.lineTo(px(t), py(v)) : context.moveTo(px(t), py(v))));
      context.stroke();
    }
    root.dataset.samples = String(samples);
  }

  // It plots what the student asks for (the form's `plot`), not the suggestion the field opens with:
  // a plot nobody asked for would stream /turtle1/pose to every page at 20 samples a second.
  let wanted = '';
  form.addEventListener('submit', (event) => { event.preventDefault(); wanted = input.value.trim(); start(wanted); });
  root.querySelector('#plot-clear').addEventListener('click', () => { for (const s of series) s.points = []; });
  // Redrawn 10 times a second while it has lines to draw and the page is in sight; an empty plot once.
  let blank = false;
  setInterval(() => {
    if (document.hidden || (blank && !series.length)) return;
    render();
    blank = !series.length;
  }, 100);
  // Out of sight, nothing is plotted (the server stops sending); back, the plot starts again.
  whenHidden(() => { latest += 1; stop(); }, () => { if (wanted) start(wanted); });
}
