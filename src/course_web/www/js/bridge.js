// A small rosbridge v2 client: one websocket, subscriptions by id, service calls as promises,
// and our binary image frames (4-byte header length, JSON header, JPEG/PNG bytes).
// When the socket closes (the server restarted, as behind JupyterLab when the page moves to
// another master), it opens a new one after a pause and subscribes and advertises again; a
// refused token (1008) is final.
// The page's own op, lab_status: the panels say what they want to be told about the ROS side
// (watchLab: the health of a topic, the node graph, the topic list) and the server sends each
// part when it is known and again only when it changes; nothing is polled. While the page is out
// of sight (setLabPaused), it asks for nothing; back in sight, the server answers at once.
const RETRY_FIRST_MS = 500;
const RETRY_MAX_MS = 5000;
const POLICY_VIOLATION = 1008;

export class Bridge {
  constructor(url) {
    this.url = url;
    this.nextId = 1;
    this.topicHandlers = new Map();   // id -> {topic, onMessage}
    this.imageHandlers = new Map();   // topic -> Map(id -> onImage(blob, header))
    this.calls = new Map();           // id -> {resolve, reject}
    this.standing = new Map();        // subscriptions and advertisements: key -> text, sent on each new socket
    this.statusListeners = [];
    this.stateListeners = [];
    this.pending = [];
    this.retryMs = RETRY_FIRST_MS;
    this.labWatches = new Set();      // {part, option, onValue}
    this.labPaused = false;
    this.labAsked = '{}';             // the wants last sent, as text
    this.open();
  }

  open() {
    this.socket = new WebSocket(this.url);
    this.socket.binaryType = 'arraybuffer';
    this.socket.onopen = () => {
      this.setState('open');
      this.retryMs = RETRY_FIRST_MS;
      for (const text of this.standing.values()) this.socket.send(text);
      for (const text of this.pending) this.socket.send(text);
      this.pending = [];
    };
    this.socket.onclose = (event) => {
      const reason = event.reason || ('code ' + event.code);
      for (const call of this.calls.values()) call.reject(new Error('the connection closed: ' + reason));
      this.calls.clear();
      if (event.code === POLICY_VIOLATION) {
        this.setState('closed', reason);
        return;
      }
      this.setState('closed', reason + '; connecting again');
      setTimeout(() => this.open(), this.retryMs);
      this.retryMs = Math.min(2 * this.retryMs, RETRY_MAX_MS);
    };
    this.socket.onmessage = (event) => this.receive(event.data);
  }

  setState(state, detail) { for (const listener of this.stateListeners) listener(state, detail); }
  onState(listener) { this.stateListeners.push(listener); }
  onStatus(listener) { this.statusListeners.push(listener); }

  send(message) {
    const text = JSON.stringify(message);
    if (this.socket.readyState === WebSocket.OPEN) this.socket.send(text);
    else this.pending.push(text);
  }

  // A message that holds for the whole session: sent now if the socket is open, and on each new one.
  sendStanding(key, message) {
    const text = JSON.stringify(message);
    this.standing.set(key, text);
    if (this.socket.readyState === WebSocket.OPEN) this.socket.send(text);
  }

  newId(op) { return op + ':' + (this.nextId++); }

  receive(data) {
    if (data instanceof ArrayBuffer) { this.receiveImage(data); return; }
    const message = JSON.parse(data);
    if (message.op === 'publish') {
      for (const handler of this.topicHandlers.values()) {
        if (handler.topic === message.topic) handler.onMessage(message.msg);
      }
    } else if (message.op === 'service_response') {
      const call = this.calls.get(message.id);
      if (call) {
        this.calls.delete(message.id);
        if (message.result) call.resolve(message.values); else call.reject(new Error(message.values));
      }
    } else if (message.op === 'status') {
      for (const listener of this.statusListeners) listener(message);
    } else if (message.op === 'lab_status') {
      for (const watch of this.labWatches) if (watch.part in message) watch.onValue(message[watch.part]);
    }
  }

  receiveImage(buffer) {
    const length = new DataView(buffer).getUint32(0);
    const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 4, length)));
    const handlers = this.imageHandlers.get(header.topic);
    if (!handlers || handlers.size === 0) return;
    const blob = new Blob([new Uint8Array(buffer, 4 + length)], {type: 'image/' + header.format});
    for (const handler of handlers.values()) handler(blob, header);
  }

  subscribe(topic, type, onMessage, options = {}) {
    const id = this.newId('subscribe:' + topic);
    this.topicHandlers.set(id, {topic, onMessage});
    this.sendStanding(id, Object.assign({op: 'subscribe', id, topic, type}, options));
    return id;
  }

  subscribeImage(topic, format, onImage) {
    const id = this.newId('subscribe:' + topic);
    if (!this.imageHandlers.has(topic)) this.imageHandlers.set(topic, new Map());
    this.imageHandlers.get(topic).set(id, onImage);
    this.sendStanding(id, {op: 'subscribe', id, topic, type: 'sensor_msgs/Image', compression: format, queue_length: 1});
    return id;
  }

  unsubscribe(id, topic) {
    this.topicHandlers.delete(id);
    const handlers = this.imageHandlers.get(topic);
    if (handlers) handlers.delete(id);
    if (this.standing.delete(id)) this.send({op: 'unsubscribe', id, topic});
  }

  advertise(topic, type) {
    this.sendStanding('advertise:' + topic, {op: 'advertise', id: this.newId('advertise:' + topic), topic, type});
  }

  unadvertise(topic) {
    if (this.standing.delete('advertise:' + topic)) this.send({op: 'unadvertise', topic});
  }
  publish(topic, msg) { this.send({op: 'publish', topic, msg}); }

  // Be told `part` ('health': option is the topic; 'graph': option {debug}; 'topics') by
  // onValue(answer), now and on each change; stop() ends it.
  watchLab(part, onValue, option = true) {
    const watch = {part, onValue, option};
    this.labWatches.add(watch);
    this.askLab();
    return {
      set: (newOption) => { watch.option = newOption; this.askLab(); },
      stop: () => { if (this.labWatches.delete(watch)) this.askLab(); },
    };
  }

  setLabPaused(paused) {
    this.labPaused = paused;
    this.askLab();
  }

  // The wants of every watch as one lab_status request, sent when it differs from the last one
  // (and on each new socket, as a standing message; asking nothing ends the server's watch).
  askLab() {
    const wants = {};
    for (const watch of this.labPaused ? [] : this.labWatches) {
      if (watch.part === 'health') wants.health = watch.option;
      if (watch.part === 'graph') { wants.graph = true; wants.debug = wants.debug || Boolean(watch.option.debug); }
      if (watch.part === 'topics') wants.topics = true;
    }
    const text = JSON.stringify(wants);
    if (text === this.labAsked) return;
    this.labAsked = text;
    this.sendStanding('lab_status', Object.assign({op: 'lab_status'}, wants));
  }

  callService(service, args) {
    const id = this.newId('call_service:' + service);
    return new Promise((resolve, reject) => {
      this.calls.set(id, {resolve, reject});
      this.send({op: 'call_service', id, service, args});
    });
  }
}

// The websocket URL of the server that served this page, with the page's token if it has one;
// relative to the page's path, so that it also works behind a proxy's prefix (JupyterLab's /roslab/).
export function bridgeUrl(location) {
  const url = new URL('websocket', location.href);
  url.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
  const token = new URLSearchParams(location.search).get('token');
  url.search = token ? '?token=' + encodeURIComponent(token) : '';
  url.hash = '';
  return url.href;
}
