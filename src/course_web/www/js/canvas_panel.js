// The turtlesim panel: turtlesim's ~image topic drawn on a canvas.
import {imageView} from './image_view.js';

export function mount(bridge, root) {
  const topicInput = root.querySelector('#canvas-topic');
  const draw = imageView(root.querySelector('#turtle-canvas'), root.querySelector('#canvas-fps'));
  let subscription = null;

  function follow(topic) {
    if (subscription) bridge.unsubscribe(subscription.id, subscription.topic);
    subscription = {topic, id: bridge.subscribeImage(topic, 'jpeg', draw)};
  }

  topicInput.addEventListener('change', () => follow(topicInput.value.trim()));
  follow(topicInput.value.trim());
}
