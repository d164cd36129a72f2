// The turtlesim panel: the canvas drawn here, in the page, from what turtlesim says changed.
// turtlesim's ~canvas service gives the whole canvas once (its lines as a PNG, the turtle icons,
// the turtles, and the number of the last update the PNG holds); its ~scene topic then gives each
// update (std_msgs/String, JSON: a clear colour, the lines drawn with their pen's colour and width,
// where each turtle is, with its velocity), none while nothing moves. Between updates the panel
// moves each turtle on as turtlesim does (its velocity, along the arc it drives, for at most
// AHEAD_MAX_S): turtlesim sends a turtle that goes on as foreseen only 7.8 times a second, and
// what it could not foresee (a key, a teleport, the wall) within 3 ticks (turtlesim.scene).
// An update that skips a number (one was lost) or comes from another turtlesim process (`run`:
// it restarted) makes the panel ask ~canvas again. While the page is hidden it takes no updates.
// canvas.dataset.frames counts the pictures drawn (the tests and the benchmark read it).
import {whenHidden} from './api.js';
import {frameCounter} from './image_view.js';

const SCENE_TYPE = 'std_msgs/String';
const RETRY_FIRST_MS = 1000;  // turtlesim not up: ask ~canvas again after 1 s, 2 s, then every 4 s,
const RETRY_MAX_MS = 4000;    // and at once when an update shows it is back
const AHEAD_MAX_S = 0.25;     // how far past its last update a turtle is moved on (2 steady updates)
const MOVED_ON_MS = 33;       // pictures of turtles moved on: at most 30 a second (the browser's CPU)

// Where a turtle at canvas (x, y, theta) with velocity (vx forward, vy to its left, in pixels a
// second; w in radians a second, counter-clockwise) is `t` seconds on, driving the arc it drives.
export function movedOn([name, x, y, theta, icon, vx = 0, vy = 0, w = 0], t) {
  const heading = theta + w * t;
  const along = Math.abs(w) < 1e-9 ? t * Math.cos(theta) : (Math.sin(heading) - Math.sin(theta)) / w;
  const across = Math.abs(w) < 1e-9 ? t * Math.sin(theta) : (Math.cos(theta) - Math.cos(heading)) / w;
  return [name, x + vx * along - vy * across, y - (vx * across + vy * along), heading, icon];  // canvas y is down
}

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
  let turtlesAt = 0;      // when `turtles` were said (performance.now())
  let composedAt = 0;     // when the last picture was drawn
  let fresh = false;      // something new to draw (not only turtles moved on)
  let seq = null;         // the last update drawn; null until a snapshot arrived
  let run = null;         // which turtlesim process the numbers count for
  let waiting = [];       // updates that came before the snapshot
  let asking = false;
  let subscription = null;
  let node = '';
  let queued = false;
  let retryMs = RETRY_FIRST_MS;
  let retryTimer = null;

  function compose(now) {
    queued = false;
    if (!fresh && now - composedAt < MOVED_ON_MS) { show(); return; }  // only moving on: not yet
    fresh = false;
    composedAt = now;
    const ahead = Math.min(Math.max((now - turtlesAt) / 1000, 0), AHEAD_MAX_S);
    context.drawImage(paths, 0, 0);
    let moving = false;
    for (const turtle of turtles) {
      const [, x, y, theta, icon] = movedOn(turtle, ahead);
      moving = moving || turtle[5] || turtle[6] || turtle[7];
      const image = icons.length ? icons[icon % icons.length] : null;
      if (!image) continue;
      context.save();
      context.translate(Math.min(Math.max(x, 0), canvas.width), Math.min(Math.max(y, 0), canvas.height));
      context.rotate(-theta);
      context.drawImage(image, -image.width / 2, -image.height / 2);
      context.restore();
    }
    drawn();
    if (moving && ahead < AHEAD_MAX_S && subscription) show();  // on to the next frame
  }

  function placed(list) {  // the turtles as turtlesim said, now
    turtles = list;
    turtlesAt = performance.now();
    fresh = true;
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
    placed(update.turtles);
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
      placed(snapshot.turtles);
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
