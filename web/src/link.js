// The WebSocket to the rover's link server (docs/operator-protocol.md). One connection, JSON text
// frames; reconnects after a pause when the connection ends. The state the operator sees:
//   connecting    no WebSocket open yet
//   read-only     connected, another console (or nobody) holds control
//   in-control    connected, this console drives
//   disconnected  the connection ended or could not be opened; a retry is scheduled
// Events (EventTarget, `event.detail`): "state" {state}, "status" {status}, "error" {text},
// "control" {message}, "stopped" {by, reason}, "pong" {rtt_ms}.
//
// The page's address carries the token once (?token=… as the server printed it): exchangeToken
// trades it for an HttpOnly session cookie (POST /session) and takes it out of the address bar,
// so it stays out of the history, bookmarks and screenshots; the WebSocket then goes with the
// cookie. Gamepad and targets messages carry `seq` (from 1 on each connection) and `sent_ms`, so
// that the server can drop readings held up in a network stall.

/** @typedef {import('./protocol').ConsoleMessage} ConsoleMessage */
/** @typedef {import('./protocol').OperatorInput} OperatorInput */
/** @typedef {import('./protocol').ServerMessage} ServerMessage */
/** @typedef {import('./protocol').HelloMessage} HelloMessage */
/** @typedef {import('./protocol').ControlMessage} ControlMessage */
/** @typedef {import('./protocol').CalibrationInfo} CalibrationInfo */
/** @typedef {import('./protocol').Status} Status */

/** @typedef {'connecting' | 'read-only' | 'in-control' | 'disconnected'} LinkState */

/**
 * Each event's `detail`.
 * @typedef {{ state: { state: LinkState },
 *   hello: { calibration: CalibrationInfo | null, velocityLimits: unknown },
 *   control: { message: ControlMessage }, stopped: { by: number, reason: string },
 *   status: { status: Status }, error: { text: string }, pong: { rtt_ms: number } }} LinkEvents
 */

const RETRY_FIRST_MS = 500;
const RETRY_MAX_MS = 5000;
const PING_PERIOD_MS = 2000;
// Readings sent in the moment control passed to another console are answered "read-only" after
// the `control` message; those answers only hide the "lost control" the operator needs to see.
const LATE_READ_ONLY_MS = 1000;
const READ_ONLY_ERROR = 'read-only: take control first';

// ws(s)://host/ws next to the page, so that a console served under a path prefix (a reverse
// proxy) still finds its server.
/** @param {Location | URL} location */
export function websocketUrl(location) {
  const url = new URL('ws', location.href);
  url.protocol = location.protocol === 'https:' ? 'wss:' : 'ws:';
  url.search = '';
  url.hash = '';
  return url.href;
}

// The page's address without its token (other query parameters and the fragment stay).
/** @param {string} href */
export function addressWithoutToken(href) {
  const url = new URL(href);
  url.searchParams.delete('token');
  return url.pathname + url.search + url.hash;
}

// POST /session next to the page with the token: the server answers with the session cookie.
// Resolves to null on success, else to what went wrong.
/**
 * @param {Location | URL} location
 * @param {string} token
 * @returns {Promise<string | null>}
 */
export async function exchangeToken(location, token) {
  let response;
  try {
    response = await fetch(new URL('session', location.href), {
      method: 'POST', headers: { Authorization: `Bearer ${token}` }, credentials: 'same-origin',
    });
  } catch (err) {
    return `cannot reach the server: ${errorText(err)}`;
  }
  if (response.ok) return null;
  const text = (await response.text()).trim();
  return `the server refused the token (HTTP ${response.status}): ${text}`;
}

/** @param {unknown} err */
function errorText(err) {
  return err instanceof Error ? err.message : String(err);
}

export class Link extends EventTarget {
  /** @param {string} url */
  constructor(url) {
    super();
    this.url = url;
    /** @type {LinkState} */
    this.state = 'connecting';
    /** @type {number | null} */
    this.clientId = null;
    /** @type {number | null} */
    this.controller = null;
    /** @type {WebSocket | null} */
    this.socket = null;
    this.retryMs = RETRY_FIRST_MS;
    /** @type {ReturnType<typeof setTimeout> | undefined} */
    this.retryTimer = undefined;
    /** @type {ReturnType<typeof setInterval> | undefined} */
    this.pingTimer = undefined;
    /** @type {number | null} */
    this.pingSentAt = null;
    /** @type {string | null} */
    this.lastError = null;
    this.everOpened = false;
    this.closedByUser = false;
    this.lostControlAt = -Infinity;
    this.seq = 0;
  }

  connect() {
    this.closedByUser = false;
    this.setState('connecting');
    let socket;
    try {
      socket = new WebSocket(this.url);
    } catch (err) {
      this.reportError(`cannot open the WebSocket ${this.url}: ${errorText(err)}`);
      this.scheduleRetry();
      return;
    }
    this.socket = socket;
    this.seq = 0;  // the server counts each connection's sequence afresh
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
        this.reportError('the server refused the connection or cannot be reached: open the ' +
          'address the server printed (http://…/?token=…) and check that the server runs');
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
  /** @param {ConsoleMessage} message */
  send(message) {
    if (!this.socket || this.socket.readyState !== WebSocket.OPEN) return false;
    this.socket.send(JSON.stringify(message));
    return true;
  }

  // A gamepad or targets message, stamped with its place in the stream and the time it left.
  /** @param {OperatorInput} message */
  sendInput(message) {
    const sentMs = performance.timeOrigin + performance.now();  // monotonic, unlike Date.now()
    if (!this.send({ ...message, seq: this.seq + 1, sent_ms: sentMs })) return false;
    this.seq += 1;
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

  // The server's JSON is taken to be the protocol's shapes; fields shown to people still go
  // through String(), and unknown types are ignored.
  /** @param {string} text */
  receive(text) {
    /** @type {ServerMessage} */
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
        this.emit('hello', { calibration: message.calibration ?? null, velocityLimits: message.velocity_limits });
        break;
      case 'control':
        this.applyControl(message);
        this.emit('control', { message });
        break;
      case 'stopped':
        this.emit('stopped', { by: message.by, reason: String(message.reason) });
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

  /** @param {HelloMessage | ControlMessage} message */
  applyControl(message) {
    this.controller = message.controller ?? null;
    if ('lost_control' in message && message.lost_control) {
      this.lostControlAt = performance.now();
      this.reportError(message.reason ? `lost control: ${message.reason}` : 'lost control');
    }
    this.setState(message.read_only ? 'read-only' : 'in-control');
  }

  /** @param {LinkState} state */
  setState(state) {
    if (state === this.state) return;
    this.state = state;
    this.emit('state', { state });
  }

  /** @param {string} text */
  reportError(text) {
    this.lastError = text;
    this.emit('error', { text });
  }

  /**
   * @template {keyof LinkEvents} K
   * @param {K} type
   * @param {LinkEvents[K]} detail
   */
  emit(type, detail) {
    this.dispatchEvent(new CustomEvent(type, { detail }));
  }

  /**
   * Calls `handler` with the detail of every `type` event.
   * @template {keyof LinkEvents} K
   * @param {K} type
   * @param {(detail: LinkEvents[K]) => void} handler
   */
  on(type, handler) {
    // Every event of these types comes from emit(): a CustomEvent with that detail.
    this.addEventListener(type, (event) => handler(/** @type {CustomEvent<LinkEvents[K]>} */ (event).detail));
  }
}
