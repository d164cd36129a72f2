// The header's words about the ROS side, told by the server (the lab_status op's "health", sent
// when it changes, never polled): the master does not answer (the student stopped roscore), or
// nothing publishes the canvas's topic (turtlesim's ~scene: turtlesim is not running); empty again
// when they are back. root.dataset.state: ok, no-master, no-publisher, or unknown while the page's
// server does not answer (it restarts when the page moves to another master).
export function mount(bridge, root) {
  const nodeInput = document.getElementById('canvas-node');
  function show(state, says) {
    root.dataset.state = state;
    root.textContent = says;
  }
  function topic() {
    return nodeInput ? nodeInput.value.trim().replace(/\/+$/, '') + '/scene' : '';
  }
  const watch = bridge.watchLab('health', (answer) => {
    if (answer.error) show('unknown', 'The page cannot ask its server about ROS: ' + answer.error);
    else show(answer.state, answer.says);
  }, topic());
  if (nodeInput) nodeInput.addEventListener('change', () => watch.set(topic()));
  bridge.onState((state, detail) => {
    if (state !== 'open') show('unknown', 'The page cannot ask its server about ROS: the connection closed (' + detail + ')');
  });
}
