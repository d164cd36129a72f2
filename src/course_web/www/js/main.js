// The page: one Bridge, one module per panel.
import {whenHidden} from './api.js';
import {Bridge, bridgeUrl} from './bridge.js';
import * as canvasPanel from './canvas_panel.js';
import * as teleopPanel from './teleop_panel.js';
import * as consolePanel from './console_panel.js';
import * as view3dPanel from './view3d_panel.js';
import * as cameraPanel from './camera_panel.js';
import * as plotPanel from './plot_panel.js';
import * as tfPanel from './tf_panel.js';
import * as graphPanel from './graph_panel.js';
import * as healthPanel from './health_panel.js';

const PANELS = {
  canvas: canvasPanel, teleop: teleopPanel, console: consolePanel, view3d: view3dPanel, camera: cameraPanel,
  plot: plotPanel, tf: tfPanel, graph: graphPanel, health: healthPanel,
};

const bridge = new Bridge(bridgeUrl(window.location));
const connection = document.getElementById('connection');
const serverStatus = document.getElementById('server-status');
bridge.onState((state, detail) => {
  connection.dataset.state = state;
  connection.textContent = state === 'open' ? 'connected' : state + (detail ? ': ' + detail : '');
});
bridge.onStatus((status) => { serverStatus.textContent = status.level + ': ' + status.msg; });
for (const [name, panel] of Object.entries(PANELS)) {
  panel.mount(bridge, document.querySelector('[data-panel="' + name + '"]'));
}
// Out of sight, the page asks the server to tell it nothing about the ROS side; back, it is told at once.
whenHidden(() => bridge.setLabPaused(true), () => bridge.setLabPaused(false));
if (document.hidden) bridge.setLabPaused(true);
document.body.dataset.ready = 'true';
