// The 3-D view (gzclient's job): the simulator's free camera, rendered offscreen by MuJoCo and
// streamed like any camera. Drag to orbit, shift-drag (or the right button) to pan, the wheel
// to zoom: each move publishes a gazebo_msgs/OrbitView on /gazebo/free_camera/set_view, and
// the simulator's latched /gazebo/free_camera/view says what it applied.
import {imageView} from './image_view.js';

const IMAGE = '/gazebo/free_camera/image_raw';
const VIEW = '/gazebo/free_camera/view';
const SET_VIEW = '/gazebo/free_camera/set_view';
const VIEW_TYPE = 'gazebo_msgs/OrbitView';
const ORBIT_PER_PIXEL = 0.01;
const ZOOM_PER_NOTCH = 1.15;
const SEND_PERIOD_MS = 33;

// The view after a drag of (dx, dy) pixels: orbit, or pan the target in the ground plane.
export function dragged(view, dx, dy, pan) {
  const next = {...view, target: {...view.target}};
  if (pan) {
    const scale = view.distance * 0.002;
    const a = view.azimuth;
    // The ground follows the pointer: screen right is (-sin a, cos a) on the ground, screen up
    // is the way the eye looks, (-cos a, -sin a).
    next.target.x += scale * (dx * Math.sin(a) - dy * Math.cos(a));
    next.target.y += scale * (-dx * Math.cos(a) - dy * Math.sin(a));
  } else {
    next.azimuth = view.azimuth - dx * ORBIT_PER_PIXEL;
    next.elevation = Math.max(-1.5, Math.min(1.5, view.elevation + dy * ORBIT_PER_PIXEL));
  }
  return next;
}

export function zoomed(view, notches) {
  return {...view, target: {...view.target}, distance: view.distance * Math.pow(ZOOM_PER_NOTCH, notches)};
}

export function mount(bridge, root) {
  const canvas = root.querySelector('#view3d-canvas');
  const note = root.querySelector('#view3d-note');
  const readout = root.querySelector('#view3d-readout');
  const draw = imageView(canvas, root.querySelector('#view3d-fps'));
  let view = null;       // the simulator's view, then ours while dragging
  let started = false;
  let drag = null;
  let sendTimer = null;
  let lastLocal = -Infinity;  // when the user last moved the view here (ms)
  const ECHO_QUIET_MS = 500;  // until then, the simulator's echoes of older views are not taken

  function show(v) {
    readout.textContent = 'azimuth ' + v.azimuth.toFixed(2) + ', elevation ' + v.elevation.toFixed(2) +
      ', distance ' + v.distance.toFixed(2) + ' m';
    root.dataset.azimuth = String(v.azimuth);
  }

  function send() {
    lastLocal = performance.now();
    if (sendTimer) return;  // at most one OrbitView per SEND_PERIOD_MS
    sendTimer = setTimeout(() => {
      sendTimer = null;
      bridge.publish(SET_VIEW, view);
      root.dataset.sent = String(Number(root.dataset.sent || 0) + 1);
    }, SEND_PERIOD_MS);
  }

  function start() {
    started = true;
    note.textContent = 'drag to orbit, shift-drag to pan, wheel to zoom';
    bridge.subscribeImage(IMAGE, 'jpeg', draw);
    bridge.subscribe(VIEW, VIEW_TYPE, (applied) => {
      if (!drag && performance.now() - lastLocal > ECHO_QUIET_MS) { view = applied; show(view); }
    }, {queue_length: 1});
    bridge.advertise(SET_VIEW, VIEW_TYPE);
  }

  canvas.addEventListener('contextmenu', (event) => event.preventDefault());
  canvas.addEventListener('pointerdown', (event) => {
    if (!view) return;
    drag = {x: event.clientX, y: event.clientY, pan: event.shiftKey || event.button === 2};
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!drag) return;
    view = dragged(view, event.clientX - drag.x, event.clientY - drag.y, drag.pan);
    drag.x = event.clientX;
    drag.y = event.clientY;
    show(view);
    send();
  });
  const release = () => { drag = null; };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
  canvas.addEventListener('wheel', (event) => {
    if (!view) return;
    event.preventDefault();
    view = zoomed(view, Math.sign(event.deltaY));
    show(view);
    send();
  }, {passive: false});

  // Until the simulator's camera shows in the topic list (the server sends it when it changes).
  const watch = bridge.watchLab('topics', (answer) => {
    if (answer.error) { note.textContent = answer.error; return; }
    if (!started && answer.topics.some((t) => t.name === IMAGE)) { start(); watch.stop(); }
  });
  note.textContent = 'no simulator yet: start a Gazebo world (roslaunch rrbot_gazebo rrbot_world.launch)';
}
