// Keyboard teleop: the arrow keys publish geometry_msgs/Twist on the topic the user picks,
// with turtle_teleop_key's scales (2 m/s, 2 rad/s).
const LINEAR = 2.0;
const ANGULAR = 2.0;
const KEYS = {
  ArrowUp: [LINEAR, 0], ArrowDown: [-LINEAR, 0], ArrowLeft: [0, ANGULAR], ArrowRight: [0, -ANGULAR],
};

export function mount(bridge, root) {
  const topicInput = root.querySelector('#teleop-topic');
  const last = root.querySelector('#teleop-last');
  const count = root.querySelector('#teleop-count');
  let topic = null;
  let sent = 0;

  function use(newTopic) {
    if (topic) bridge.unadvertise(topic);
    topic = newTopic;
    bridge.advertise(topic, 'geometry_msgs/Twist');
  }

  document.addEventListener('keydown', (event) => {
    const command = KEYS[event.key];
    if (!command || event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement) return;
    event.preventDefault();
    const [linear, angular] = command;
    bridge.publish(topic, {linear: {x: linear, y: 0, z: 0}, angular: {x: 0, y: 0, z: angular}});
    sent += 1;
    last.textContent = event.key + ' → linear.x ' + linear + ', angular.z ' + angular;
    count.textContent = String(sent);
  });
  topicInput.addEventListener('change', () => use(topicInput.value.trim()));
  use(topicInput.value.trim());
}
