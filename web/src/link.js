// The WebSocket to the rover's link server (docs/operator-protocol.md). One connection, JSON text
// frames; reconnects after a pause when the connection ends. The state the operator sees:
//   connecting    no WebSocket open yet
//   read-only     connected, another console (or nobody) holds control
//   in-control    connected, this console drives
//   disconnected  the connection ended or could not be opened; a retry is scheduled
// Events (EventTarget, `event.detail`): "state" {state}, "status" {status}, "error" {text},
// "control" {message}, "pong" {rtt_ms}.

const RETRY_FIRST_MS = 500;
const RETRY_MAX_MS = 5000;
const PING_PERIOD_MS = 2000;
// Readings sent in the moment control passed to another console are answered "read-only" after
// the `control` message; those answers only hide the "lost control" the operator needs to see.
const LATE_READ_ONLY_MS = 1000;
const READ_ONLY_ERROR = 'read-only: take control first';

// ws(s)://host/ws?token=… next to the page, so that a console served under a path prefix (a
// reverse proxy) still finds its server.
export function websocketUrl(location, token) {
  const url = new URL('ws', location.href);
  url.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
  url.search = '?token=' + encodeURIComponent(token);
  url.hash = '';
  return url.href;
}

export class Link extends EventTarget {
  constructor(url) {
    super();
    this.url = url;
    this.state = 'connecting';
    this.clientId = null;
    this.controller = null;
    this.socket = null;
    this.retryMs = RETRY_FIRST_MS;
    this.retryTimer = null;
    this.pingTimer = null;
    this.pingSentAt = null;
    this.everOpened = false;
    this.closedByUser = false;
    this.lostControlAt = -Infinity;
  }

  connect() {
    this.closedByUser = false;
    this.setState('connecting');
    let socket;
    try {
      socket = new WebSocket(this.url);
    } catch (err) {
      this.reportError(`cannot open the WebSocket ${this.url}: ${err.message}`);
      this.scheduleRetry();
      return;
    }
    this.socket = socket;
    let opened = false;
    socket.addEventListener('open', () => {
      opened = true;
      this.everOpened = true;
      this.retryMs = RETRY_FIRST_MS;
      this.pingTimer = setInterval(() => this.ping(), PING_PERIOD_MS);
    });
    socket.addEventListener('message', (event) => this.receive(event.data));
    socket.addEventListener('close', (event) => {
      if (this.socket !== socket) return;
      this.socket = null;
      clearInterval(this.pingTimer);
      this.clientId = null;
      this.controller = null;
      this.setState('disconnected');
      if (!opened) {
        // The browser hides the HTTP answer of a refused upgrade (401 for a bad token, 503 when
        // full); say what the likely causes are.
        this.reportError('the server refused the connection or cannot be reached: check the ' +
          'token in the page address (?token=… as printed by the server) and that the server runs');
      } else if (!this.closedByUser) {
        const why = event.reason ? `: ${event.reason}` : '';
        this.reportError(`connection closed (code ${event.code}${why}); reconnecting`);
      }
      if (!this.closedByUser) this.scheduleRetry();
    });
  }

  close() {
    this.closedByUser = true;
    clearTimeout(this.retryTimer);
    if (this.socket) this.socket.close(1000, 'console closed');
  }

  scheduleRetry() {
    clearTimeout(this.retryTimer);
    this.retryTimer = setTimeout(() => this.connect(), this.retryMs);
    this.retryMs = Math.min(this.retryMs * 2, RETRY_MAX_MS);
  }

  // True when the message was handed to the socket.
  send(message) {
    if (!this.socket || this.socket.readyState !== WebSocket.OPEN) return false;
    this.socket.send(JSON.stringify(message));
    return true;
  }

  get inControl() {
    return this.state === 'in-control';
  }

  takeControl() { return this.send({ type: 'take_control' }); }
  releaseControl() { return this.send({ type: 'release_control' }); }
  stop() { return this.send({ type: 'stop' }); }

  ping() {
    if (this.send({ type: 'ping' })) this.pingSentAt = performance.now();
  }

  receive(text) {
    let message;
    try {
      message = JSON.parse(text);
    } catch {
      this.reportError('the server sent something that is not JSON; is this the rover\'s server?');
      return;
    }
    switch (message.type) {
      case 'hello':
        this.clientId = message.client_id;
        this.applyControl(message);
        this.emit('hello', { calibration: message.calibration ?? null });
        break;
      case 'control':
        this.applyControl(message);
        this.emit('control', { message });
        break;
      case 'status':
        this.emit('status', { status: message.status });
        break;
      case 'error':
        if (String(message.message).endsWith(READ_ONLY_ERROR) &&
            performance.now() - this.lostControlAt < LATE_READ_ONLY_MS) break;
        this.reportError(String(message.message));
        break;
      case 'pong':
        if (this.pingSentAt !== null) {
          this.emit('pong', { rtt_ms: performance.now() - this.pingSentAt });
          this.pingSentAt = null;
        }
        break;
      default:
        break;  // newer servers may add messages; ignoring them keeps old consoles working
    }
  }

  applyControl(message) {
    this.controller = message.controller ?? null;
    if (message.lost_control) {
      this.lostControlAt = performance.now();
      this.reportError(message.reason ? `lost control: ${message.reason}` : 'lost control');
    }
    this.setState(message.read_only ? 'read-only' : 'in-control');
  }

  setState(state) {
    if (state === this.state) return;
    this.state = state;
    this.emit('state', { state });
  }

  reportError(text) {
    this.lastError = text;
    this.emit('error', { text });
  }

  emit(type, detail) {
    this.dispatchEvent(new CustomEvent(type, { detail }));
  }
}
