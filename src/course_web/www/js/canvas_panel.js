// The turtlesim panel: the canvas drawn here, in the page, from what turtlesim says changed.
// turtlesim's ~canvas service gives the whole canvas once (its lines as a PNG, the turtle icons,
// the turtles, and the number of the last update the PNG holds); its ~scene topic then gives each
// update (std_msgs/String, JSON: a clear colour, the lines drawn with their pen's colour and width,
// where each turtle is), about 30 a second while something moves and none while nothing does.
// An update that skips a number (one was lost) or comes from another turtlesim process (`run`:
// it restarted) makes the panel ask ~canvas again. While the page is hidden it takes no updates.
// canvas.dataset.frames counts the pictures drawn (the tests and the benchmark read it).
import {whenHidden} from './api.js';
import {frameCounter} from './image_view.js';

const SCENE_TYPE = 'std_msgs/String';
const RETRY_FIRST_MS = 1000;  // turtlesim not up: ask ~canvas again after 1 s, 2 s, then every 4 s,
const RETRY_MAX_MS = 4000;    // and at once when an update shows it is back

function pngImage(base64) {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  return createImageBitmap(new Blob([bytes], {type: 'image/png'}));
}

export function mount(bridge, root) {
  const nodeInput = root.querySelector('#canvas-node');
  const canvas = root.querySelector('#turtle-canvas');
  const drawn = frameCounter(canvas, root.querySelector('#canvas-fps'));
  const context = canvas.getContext('2d');
  const paths = document.createElement('canvas');
  const pathsContext = paths.getContext('2d');
  let icons = [];
  let turtles = [];
  let seq = null;         // the last update drawn; null until a snapshot arrived
  let run = null;         // which turtlesim process the numbers count for
  let waiting = [];       // updates that came before the snapshot
  let asking = false;
  let subscription = null;
  let node = '';
  let queued = false;
  let retryMs = RETRY_FIRST_MS;
  let retryTimer = null;

  function compose() {
    queued = false;
    context.drawImage(paths, 0, 0);
    for (const [, x, y, theta, icon] of turtles) {
      const image = icons.length ? icons[icon % icons.length] : null;
      if (!image) continue;
      context.save();
      context.translate(x, y);
      context.rotate(-theta);
      context.drawImage(image, -image.width / 2, -image.height / 2);
      context.restore();
    }
    drawn();
  }

  function show() {
    if (!queued) { queued = true; requestAnimationFrame(compose); }
  }

  function apply(update) {
    if (update.clear) {
      pathsContext.fillStyle = 'rgb(' + update.clear.join(',') + ')';
      pathsContext.fillRect(0, 0, paths.width, paths.height);
    }
    pathsContext.lineCap = 'square';
    for (const [r, g, b, width, x0, y0, x1, y1] of update.strokes) {
      pathsContext.strokeStyle = 'rgb(' + r + ',' + g + ',' + b + ')';
      pathsContext.lineWidth = width;
      pathsContext.beginPath();
      pathsContext.moveTo(x0, y0);
      pathsContext.lineTo(x1, y1);
      pathsContext.stroke();
    }
    turtles = update.turtles;
    seq = update.seq;
  }

  function onUpdate(msg) {
    const update = JSON.parse(msg.data);
    if (seq === null) {
      waiting.push(update);
      if (retryTimer) { clearTimeout(retryTimer); retryTimer = null; askCanvas(); }  // it is back
      return;
    }
    if (update.run !== run) { askCanvas(); return; }  // another turtlesim (restarted)
    if (update.seq <= seq) return;  // already in the snapshot
    if (update.seq !== seq + 1) { askCanvas(); return; }  // one was lost: start again from a snapshot
    apply(update);
    show();
  }

  async function askCanvas() {
    if (asking) return;
    asking = true;
    seq = null;
    const asked = node;
    try {
      const reply = await bridge.callService(asked + '/canvas', {});
      const snapshot = JSON.parse(reply.message);
      const [picture, ...images] = await Promise.all([pngImage(snapshot.paths), ...snapshot.icons.map(pngImage)]);
      if (asked !== node || !subscription) return;
      for (const canvasElement of [canvas, paths]) {
        canvasElement.width = snapshot.width;
        canvasElement.height = snapshot.height;
      }
      pathsContext.drawImage(picture, 0, 0);
      picture.close();
      icons = images;
      turtles = snapshot.turtles;
      seq = snapshot.seq;
      run = snapshot.run;
      const later = waiting.filter((u) => u.run === run && u.seq > seq).sort((a, b) => a.seq - b.seq);
      waiting = [];
      for (const update of later) {
        if (update.seq !== seq + 1) { seq = null; setTimeout(askCanvas, 0); return; }
        apply(update);
      }
      show();
      retryMs = RETRY_FIRST_MS;
    } catch (error) {
      clearTimeout(retryTimer);
      retryTimer = setTimeout(() => {  // turtlesim not up yet
        retryTimer = null;
        if (subscription && asked === node && seq === null) askCanvas();
      }, retryMs);
      retryMs = Math.min(2 * retryMs, RETRY_MAX_MS);
    } finally {
      asking = false;
    }
  }

  function unfollow() {
    if (subscription) bridge.unsubscribe(subscription.id, subscription.topic);
    subscription = null;
    seq = null;
    waiting = [];
  }

  function follow(name) {
    unfollow();
    node = name.replace(/\/+$/, '');
    clearTimeout(retryTimer);
    retryTimer = null;
    retryMs = RETRY_FIRST_MS;
    seq = null;
    waiting = [];
    const topic = node + '/scene';
    subscription = {topic, id: bridge.subscribe(topic, SCENE_TYPE, onUpdate, {queue_length: 100})};
    askCanvas();
  }

  nodeInput.addEventListener('change', () => follow(nodeInput.value.trim()));
  bridge.onState((state) => { if (state === 'open' && subscription) askCanvas(); });  // a new server may follow another master
  whenHidden(unfollow, () => follow(nodeInput.value.trim()));  // out of sight: no updates; back: a snapshot
  follow(nodeInput.value.trim());
}
