// The node graph (rqt_graph's default view): nodes as ellipses, topics as boxes, publisher ->
// topic -> subscriber, laid out left to right in layers; the server sends it (the lab_status op's
// "graph") while the panel is on screen, and again whenever it changes.

const SVG = 'http://www.w3.org/2000/svg';
const CHAR_W = 7.5;
const ROW_H = 34;
const COL_GAP = 60;
const PAD = 10;
const LOOP_DROP = 28;  // how far below the boxes an edge closing a cycle runs

// Layers: longest path from the sources, with the edges that close a cycle left out.
export function layers(names, edges) {
  const out = new Map(names.map((n) => [n, []]));
  for (const e of edges) if (out.has(e.from) && out.has(e.to)) out.get(e.from).push(e.to);
  const state = new Map();
  const forward = new Map(names.map((n) => [n, []]));
  function visit(name) {
    state.set(name, 'open');
    for (const next of out.get(name)) {
      if (state.get(next) === 'open') continue;  // a back edge: part of a cycle
      forward.get(name).push(next);
      if (!state.has(next)) visit(next);
    }
    state.set(name, 'done');
  }
  const indegree = new Map(names.map((n) => [n, 0]));
  for (const e of edges) if (indegree.has(e.to) && out.has(e.from)) indegree.set(e.to, indegree.get(e.to) + 1);
  for (const name of [...names].sort((a, b) => indegree.get(a) - indegree.get(b))) if (!state.has(name)) visit(name);
  const rank = new Map(names.map((n) => [n, 0]));
  const pending = new Map(names.map((n) => [n, 0]));
  for (const targets of forward.values()) for (const t of targets) pending.set(t, pending.get(t) + 1);
  const ready = names.filter((n) => pending.get(n) === 0);
  while (ready.length) {
    const name = ready.shift();
    for (const next of forward.get(name)) {
      rank.set(next, Math.max(rank.get(next), rank.get(name) + 1));
      pending.set(next, pending.get(next) - 1);
      if (pending.get(next) === 0) ready.push(next);
    }
  }
  return rank;
}

function element(tag, attributes, parent) {
  const node = document.createElementNS(SVG, tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  if (parent) parent.appendChild(node);
  return node;
}

function draw(svg, graph) {
  const kinds = new Map([...graph.nodes.map((n) => [n, 'node']), ...graph.topics.map((t) => [t.name, 'topic'])]);
  const names = [...kinds.keys()].sort();
  const rank = layers(names, graph.edges);
  const columns = [];
  for (const name of names) (columns[rank.get(name)] ||= []).push(name);
  const position = new Map();
  let x = PAD;
  let height = 0;
  columns.forEach((column = [], index) => {
    if (index > 0) {  // order by where the predecessors sit (one barycentre pass)
      const at = (name) => {
        const ys = graph.edges.filter((e) => e.to === name && position.has(e.from)).map((e) => position.get(e.from).y);
        return ys.length ? ys.reduce((a, b) => a + b, 0) / ys.length : Infinity;
      };
      column.sort((a, b) => at(a) - at(b) || a.localeCompare(b));
    }
    const width = Math.max(...column.map((n) => n.length * CHAR_W + 24));
    column.forEach((name, row) => position.set(name, {x, y: PAD + row * ROW_H + ROW_H / 2, w: name.length * CHAR_W + 24, col: width}));
    x += width + COL_GAP;
    height = Math.max(height, PAD * 2 + column.length * ROW_H);
  });
  svg.replaceChildren();
  svg.setAttribute('width', String(Math.max(x, 200)));
  svg.setAttribute('height', String(Math.max(height + LOOP_DROP, 60)));
  const defs = element('defs', {}, svg);
  const marker = element('marker', {id: 'arrow', viewBox: '0 0 10 10', refX: '10', refY: '5', markerWidth: '7',
    markerHeight: '7', orient: 'auto-start-reverse'}, defs);
  element('path', {d: 'M 0 0 L 10 5 L 0 10 z', fill: '#445'}, marker);
  for (const edge of graph.edges) {
    const a = position.get(edge.from);
    const b = position.get(edge.to);
    if (!a || !b) continue;
    let d;
    if (b.x > a.x) {  // left to right: from a's right side to b's left side
      const x1 = a.x + a.w;
      const x2 = b.x;
      const bend = Math.max(30, (x2 - x1) / 2);
      d = `M ${x1} ${a.y} C ${x1 + bend} ${a.y}, ${x2 - bend} ${b.y}, ${x2} ${b.y}`;
    } else {  // an edge that closes a cycle: under the boxes, from a's bottom to b's bottom
      const [x1, y1, x2, y2] = [a.x + a.w / 2, a.y + ROW_H / 2 - 5, b.x + b.w / 2, b.y + ROW_H / 2 - 5];
      const low = Math.max(y1, y2) + LOOP_DROP;
      d = `M ${x1} ${y1} C ${x1} ${low}, ${x2} ${low}, ${x2} ${y2}`;
    }
    element('path', {class: 'edge', d, 'marker-end': 'url(#arrow)', 'data-from': edge.from, 'data-to': edge.to}, svg);
  }
  for (const [name, at] of position) {
    const group = element('g', {class: 'vertex ' + kinds.get(name), 'data-name': name}, svg);
    if (kinds.get(name) === 'node') {
      element('ellipse', {cx: at.x + at.w / 2, cy: at.y, rx: at.w / 2, ry: ROW_H / 2 - 4}, group);
    } else {
      element('rect', {x: at.x, y: at.y - ROW_H / 2 + 5, width: at.w, height: ROW_H - 10}, group);
    }
    const label = element('text', {x: at.x + at.w / 2, y: at.y + 4, 'text-anchor': 'middle'}, group);
    label.textContent = name;
  }
}

export function mount(bridge, root) {
  const svg = root.querySelector('#graph-svg');
  const debug = root.querySelector('#graph-debug');
  const summary = root.querySelector('#graph-summary');
  let shown = '';
  let watch = null;
  function show(graph) {
    root.dataset.refreshed = String(Number(root.dataset.refreshed || 0) + 1);
    if (graph.error) { summary.textContent = graph.error; return; }
    summary.textContent = graph.nodes.length + ' nodes, ' + graph.topics.length + ' topics';
    const text = JSON.stringify(graph);
    if (text === shown) return;
    shown = text;
    draw(svg, graph);
  }
  // Told only while the panel is on screen: a graph nobody sees is not worth the server's work.
  function follow(visible) {
    root.dataset.watching = String(visible);
    if (visible && !watch) watch = bridge.watchLab('graph', show, {debug: debug.checked});
    if (!visible && watch) { watch.stop(); watch = null; }
  }
  new IntersectionObserver((entries) => follow(entries[entries.length - 1].isIntersecting)).observe(root);
  debug.addEventListener('change', () => { if (watch) watch.set({debug: debug.checked}); });
}
