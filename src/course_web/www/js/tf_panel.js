// The TF tree (view_frames / rqt_tf_tree's job): every parent -> child link seen on /tf and
// /tf_static, as a tree, with each dynamic link's rate and age. Redrawn once a second while in sight.
const WINDOW_S = 5;

export function mount(bridge, root) {
  const tree = root.querySelector('#tf-tree');
  const summary = root.querySelector('#tf-summary');
  const links = new Map();  // child -> {parent, isStatic, stamps: [receipt times, s]}

  function take(message, isStatic) {
    const now = performance.now() / 1000;
    for (const transform of message.transforms || []) {
      const child = transform.child_frame_id.replace(/^\//, '');
      const parent = transform.header.frame_id.replace(/^\//, '');
      if (!child || !parent) continue;
      let link = links.get(child);
      if (!link || link.parent !== parent) links.set(child, link = {parent, isStatic, stamps: []});
      link.isStatic = isStatic;
      link.stamps.push(now);
      while (link.stamps.length && link.stamps[0] < now - WINDOW_S) link.stamps.shift();
    }
  }

  function label(child, link, now) {
    if (!link) return child;
    if (link.isStatic) return child + ' (static)';
    const recent = link.stamps.filter((t) => t >= now - WINDOW_S);
    const age = link.stamps.length ? now - link.stamps[link.stamps.length - 1] : Infinity;
    return child + ' (' + (recent.length / WINDOW_S).toFixed(1) + ' Hz' + (age > 1 ? ', last ' + age.toFixed(0) + ' s ago' : '') + ')';
  }

  function branch(frame, children, now, seen) {
    const item = document.createElement('li');
    item.dataset.frame = frame;
    item.textContent = label(frame, links.get(frame), now);
    const kids = (children.get(frame) || []).filter((k) => !seen.has(k)).sort();
    if (kids.length) {
      const list = document.createElement('ul');
      for (const kid of kids) { seen.add(kid); list.appendChild(branch(kid, children, now, seen)); }
      item.appendChild(list);
    }
    return item;
  }

  function render() {
    const now = performance.now() / 1000;
    const children = new Map();
    for (const [child, link] of links) (children.get(link.parent) || children.set(link.parent, []).get(link.parent)).push(child);
    const frames = new Set([...links.keys(), ...[...links.values()].map((l) => l.parent)]);
    const roots = [...frames].filter((f) => !links.has(f)).sort();
    const seen = new Set(roots);
    const list = document.createElement('ul');
    for (const frame of roots) list.appendChild(branch(frame, children, now, seen));
    for (const frame of [...frames].filter((f) => !seen.has(f)).sort()) {  // a loop has no root
      seen.add(frame);
      list.appendChild(branch(frame, children, now, seen));
    }
    tree.replaceChildren(list);
    summary.textContent = frames.size ? frames.size + ' frames, ' + roots.length + ' tree' + (roots.length === 1 ? '' : 's')
      : 'no transforms yet on /tf or /tf_static';
    root.dataset.frames = String(frames.size);
  }

  bridge.subscribe('/tf', 'tf2_msgs/TFMessage', (message) => take(message, false), {queue_length: 50});
  bridge.subscribe('/tf_static', 'tf2_msgs/TFMessage', (message) => take(message, true), {queue_length: 50});
  // Once a second (the rates and ages change) while there is something to show and the page is in sight.
  setInterval(() => { if (!document.hidden && links.size) render(); }, 1000);
  render();
}
