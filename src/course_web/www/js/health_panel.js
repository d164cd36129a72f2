// The header's words about the ROS side, from /api/health every second: the master does not
// answer (the student stopped roscore), or nothing publishes the canvas's topic (turtlesim's ~scene) (turtlesim is not
// running); empty again when they are back. root.dataset.state: ok, no-master, no-publisher,
// or unknown while the page's server does not answer (it restarts when the page moves to
// another master).
import {ask, every} from './api.js';

const PERIOD_MS = 1000;

export function mount(bridge, root) {
  const nodeInput = document.getElementById('canvas-node');
  function show(state, says) {
    root.dataset.state = state;
    root.textContent = says;
  }
  every(PERIOD_MS, async () => {
    const answer = await ask('health', {topic: nodeInput ? nodeInput.value.trim().replace(/\/+$/, '') + '/scene' : ''});
    show(answer.state, answer.says);
  }, (error) => show('unknown', 'The page cannot ask its server about ROS: ' + error.message));
}
