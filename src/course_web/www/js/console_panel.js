// The /rosout console (rqt_console's job): every node's log messages, filtered by level.
const LEVELS = {1: 'DEBUG', 2: 'INFO', 4: 'WARN', 8: 'ERROR', 16: 'FATAL'};
const KEEP = 1000;

export function mount(bridge, root) {
  const body = root.querySelector('#console-table tbody');
  const levelSelect = root.querySelector('#console-level');
  const countLabel = root.querySelector('#console-count');
  const entries = [];

  function row(entry) {
    const tr = document.createElement('tr');
    tr.dataset.level = String(entry.level);
    const stamp = new Date(entry.header.stamp.secs * 1000 + entry.header.stamp.nsecs / 1e6);
    for (const text of [stamp.toLocaleTimeString(), LEVELS[entry.level] || entry.level, entry.name, entry.msg]) {
      const td = document.createElement('td');
      td.textContent = text;
      tr.appendChild(td);
    }
    tr.hidden = entry.level < Number(levelSelect.value);
    return tr;
  }

  function refresh() {
    const least = Number(levelSelect.value);
    for (const tr of body.children) tr.hidden = Number(tr.dataset.level) < least;
    countLabel.textContent = entries.length + ' messages';
  }

  const scroller = root.querySelector('.console-scroll');
  bridge.subscribe('/rosout', 'rosgraph_msgs/Log', (entry) => {
    const atBottom = scroller.scrollTop + scroller.clientHeight >= scroller.scrollHeight - 4;
    entries.push(entry);
    body.appendChild(row(entry));
    if (atBottom) scroller.scrollTop = scroller.scrollHeight;  // follow the newest unless scrolled up
    if (entries.length > KEEP) { entries.shift(); body.removeChild(body.firstChild); }
    countLabel.textContent = entries.length + ' messages';
  }, {queue_length: 100});
  levelSelect.addEventListener('change', refresh);
  root.querySelector('#console-clear').addEventListener('click', () => {
    entries.length = 0;
    body.replaceChildren();
    refresh();
  });
}
