// The turtlesim panel: turtlesim's ~image topic drawn on a canvas, frames counted per second.
export function mount(bridge, root) {
  const canvas = root.querySelector('#turtle-canvas');
  const context = canvas.getContext('2d');
  const topicInput = root.querySelector('#canvas-topic');
  const fpsLabel = root.querySelector('#canvas-fps');
  let subscription = null;
  let frames = 0;
  let drawing = false;

  function draw(blob, header) {
    if (drawing) return;  // the previous frame is still decoding: skip, a newer one follows
    drawing = true;
    createImageBitmap(blob).then((bitmap) => {
      if (canvas.width !== header.width || canvas.height !== header.height) {
        canvas.width = header.width;
        canvas.height = header.height;
      }
      context.drawImage(bitmap, 0, 0);
      bitmap.close();
      frames += 1;
      canvas.dataset.frames = String(Number(canvas.dataset.frames || 0) + 1);
    }).finally(() => { drawing = false; });
  }

  function follow(topic) {
    if (subscription) bridge.unsubscribe(subscription.id, subscription.topic);
    subscription = {topic, id: bridge.subscribeImage(topic, 'jpeg', draw)};
  }

  topicInput.addEventListener('change', () => follow(topicInput.value.trim()));
  setInterval(() => {
    fpsLabel.textContent = frames + ' fps';
    canvas.dataset.fps = String(frames);
    frames = 0;
  }, 1000);
  follow(topicInput.value.trim());
}
