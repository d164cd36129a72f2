// Any camera: a sensor_msgs/Image topic picked from those the master knows (the server sends the
// list, the lab_status op's "topics", when it changes), drawn like the turtlesim canvas. The free
// camera has its own panel (3-D view).
import {imageView} from './image_view.js';

const IMAGE_TYPE = 'sensor_msgs/Image';
const OWN_PANELS = ['/gazebo/free_camera/image_raw', '/turtlesim/image'];

export function mount(bridge, root) {
  const select = root.querySelector('#camera-topic');
  const note = root.querySelector('#camera-note');
  const draw = imageView(root.querySelector('#camera-canvas'), root.querySelector('#camera-fps'));
  let subscription = null;

  function follow(topic) {
    if (subscription) bridge.unsubscribe(subscription.id, subscription.topic);
    subscription = topic ? {topic, id: bridge.subscribeImage(topic, 'jpeg', draw)} : null;
    root.dataset.topic = topic || '';
  }

  function refresh(answer) {
    if (answer.error) { note.textContent = answer.error; return; }
    const {topics} = answer;
    const cameras = topics.filter((t) => t.type === IMAGE_TYPE).map((t) => t.name);
    const current = select.value;
    const listed = [...select.options].map((o) => o.value);
    if (cameras.join() !== listed.join()) {
      select.replaceChildren(...cameras.map((name) => new Option(name, name)));
      if (cameras.includes(current)) select.value = current;
    }
    note.textContent = cameras.some((name) => !OWN_PANELS.includes(name)) ? '' : 'no camera topic yet (pick one when it comes)';
    const robotCamera = cameras.find((name) => !OWN_PANELS.includes(name));
    if (!subscription && robotCamera) {  // on its own, the panel shows a robot's camera, never a view shown above
      select.value = robotCamera;
      follow(robotCamera);
    } else if (!subscription) {
      select.value = '';
    }
  }

  select.addEventListener('change', () => follow(select.value));
  bridge.watchLab('topics', refresh);
}
