// The top-down map: the dead-reckoned track (status.pose) in the odometry frame of the driver's
// start, the rover's estimated pose with its 1-σ circle, the simulator's true track beside it
// (status.truth.odometry, the truth carried into the same frame), the mission's waypoints and
// target (status.mission) and the waypoints typed or clicked into the mission form. A 2-D canvas;
// the view fits everything in, with a grid of 1-2-5 metre steps and a scale bar.
//
// The frame: x forward and y left of where the driver started; on the map x points right and y
// up, so a counter-clockwise heading turns counter-clockwise on the screen. A restarted driver
// (after a brown-out) starts a new frame: its pose and its distance start again from zero, and its
// mission time from zero; the tracks start afresh then (TrackLog).

/** @typedef {import('./protocol').Status} Status */
/** @typedef {import('./protocol').MissionStatus} MissionStatus */

/** @typedef {{ x: number, y: number }} Point */
/** @typedef {{ minX: number, maxX: number, minY: number, maxY: number }} Bounds */
/** @typedef {{ scale: number, ox: number, oy: number }} Transform  px per metre, and where x = y = 0 is */

export const MIN_STEP_M = 0.005;    // a track point only once the rover moved this far
export const MAX_TRACK_POINTS = 4000;
const MIN_SPAN_M = 2;               // the view never shows less than this across
const MARGIN_PX = 24;
const HEIGHT_PX = 360;

export const COLORS = {
  estimated: '#1f6feb',
  sigma: 'rgba(31, 111, 235, 0.15)',
  truth: '#e8590c',
  waypoint: '#2e7d32',
  target: '#d0021b',
  draft: '#8e44ad',
  grid: '#e6e3dd',
  axis: '#b8b4ac',
  text: '#6b6f73',
};

/**
 * @param {unknown} v
 * @returns {v is number}
 */
const finite = (v) => typeof v === 'number' && Number.isFinite(v);

// ---- Pure parts (tests/modules.test.mjs) ----

// A decimal number as people type it: 1, -0.5, .25, 2e-1; nothing else (Number() would take "",
// " ", "0x10" and "Infinity").
const NUMBER = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;

/**
 * The number in `text`, or null when it is not one.
 * @param {string} text
 * @returns {number | null}
 */
export function parseNumber(text) {
  const t = text.trim();
  if (!NUMBER.test(t)) return null;
  const v = Number(t);
  return Number.isFinite(v) ? v : null;
}

/**
 * Waypoints typed as "x,y; x,y" in metres (semicolons or new lines between them, a trailing
 * separator allowed), or what is wrong with the text.
 * @param {string} text
 * @param {{ max?: number, limitM?: number }} [limits]  at most `max` waypoints, each within limitM
 *   of the origin
 * @returns {{ waypoints: Point[], error?: undefined } | { error: string, waypoints?: undefined }}
 */
export function parseWaypoints(text, { max = 64, limitM = 1000 } = {}) {
  // Lines are separators too; a line may end in its semicolon, blank lines do not count.
  const lines = text.split('\n').map((l) => l.trim().replace(/;$/, '')).filter((l) => l !== '');
  const parts = lines.join(';').split(';').map((p) => p.trim());
  while (parts.length && parts[parts.length - 1] === '') parts.pop();
  if (parts.length === 0) return { error: 'no waypoints: type them as x,y; x,y (metres) or click the map' };
  if (parts.length > max) return { error: `${parts.length} waypoints; at most ${max}` };
  /** @type {Point[]} */
  const waypoints = [];
  for (const [i, part] of parts.entries()) {
    const n = i + 1;
    const xy = part.split(',');
    if (part === '' || xy.length !== 2) return { error: `waypoint ${n}: "${part}" is not x,y (two numbers in metres)` };
    const [x, y] = xy.map(parseNumber);
    if (x === null || y === null) return { error: `waypoint ${n}: "${part}" is not x,y (two numbers in metres)` };
    if (Math.hypot(x, y) > limitM) {
      return { error: `waypoint ${n}: ${x},${y} is ${Math.hypot(x, y).toFixed(1)} m from the origin; at most ${limitM} m` };
    }
    waypoints.push({ x, y });
  }
  return { waypoints };
}

// "x,y; x,y" for waypoints, to 2 decimals (centimetres).
/** @param {Point[]} points */
export function formatWaypoints(points) {
  const r = (/** @type {number} */ v) => String(Math.round(v * 100) / 100);
  return points.map((p) => `${r(p.x)},${r(p.y)}`).join('; ');
}

/**
 * The smallest box around the points (null for none).
 * @param {Iterable<Point>} points
 * @returns {Bounds | null}
 */
export function boundsOf(points) {
  /** @type {Bounds | null} */
  let b = null;
  for (const p of points) {
    if (!finite(p.x) || !finite(p.y)) continue;
    if (!b) b = { minX: p.x, maxX: p.x, minY: p.y, maxY: p.y };
    else {
      b.minX = Math.min(b.minX, p.x);
      b.maxX = Math.max(b.maxX, p.x);
      b.minY = Math.min(b.minY, p.y);
      b.maxY = Math.max(b.maxY, p.y);
    }
  }
  return b;
}

/**
 * The transform that shows `bounds` (at least `minSpan` metres across each way, centred on the
 * box) in a width × height canvas, `margin` pixels free on every side, the same scale on both
 * axes. No bounds: the origin in the middle.
 * @param {Bounds | null} bounds
 * @param {number} width
 * @param {number} height
 * @param {{ margin?: number, minSpan?: number }} [options]
 * @returns {Transform}
 */
export function fitView(bounds, width, height, { margin = MARGIN_PX, minSpan = MIN_SPAN_M } = {}) {
  const b = bounds ?? { minX: 0, maxX: 0, minY: 0, maxY: 0 };
  const cx = (b.minX + b.maxX) / 2;
  const cy = (b.minY + b.maxY) / 2;
  const spanX = Math.max(b.maxX - b.minX, minSpan);
  const spanY = Math.max(b.maxY - b.minY, minSpan);
  const scale = Math.max(1e-6, Math.min((width - 2 * margin) / spanX, (height - 2 * margin) / spanY));
  return { scale, ox: width / 2 - scale * cx, oy: height / 2 + scale * cy };
}

/**
 * Metres (odometry frame) to canvas pixels: x to the right, y up.
 * @param {Transform} t
 * @param {Point} p
 * @returns {Point}
 */
export function toScreen(t, p) {
  return { x: t.ox + t.scale * p.x, y: t.oy - t.scale * p.y };
}

/**
 * Canvas pixels to metres: the inverse of toScreen.
 * @param {Transform} t
 * @param {Point} px
 * @returns {Point}
 */
export function toWorld(t, px) {
  return { x: (px.x - t.ox) / t.scale, y: (t.oy - px.y) / t.scale };
}

/**
 * The grid's step: 1, 2 or 5 × 10ⁿ metres, the smallest at least `minPx` pixels apart.
 * @param {number} scale  px per metre
 * @param {number} [minPx]
 */
export function gridStep(scale, minPx = 40) {
  const raw = minPx / scale;
  const decade = 10 ** Math.floor(Math.log10(raw));
  for (const m of [1, 2, 5, 10]) if (m * decade >= raw * (1 - 1e-9)) return m * decade;
  return 10 * decade;
}

/** The length of a polyline [m]. @param {Point[]} points */
export function pathLength(points) {
  let sum = 0;
  for (let i = 1; i < points.length; i += 1) {
    sum += Math.hypot(points[i].x - points[i - 1].x, points[i].y - points[i - 1].y);
  }
  return sum;
}

// Every other point, the last kept: a long track keeps its shape in half the points.
/** @param {Point[]} points */
function thin(points) {
  const kept = points.filter((_, i) => i % 2 === 0);
  if ((points.length - 1) % 2 !== 0) kept.push(points[points.length - 1]);
  return kept;
}

/**
 * A point added to a track unless it lies within `minStep` of the track's last one.
 * @param {Point[]} track
 * @param {Point} p
 * @param {number} minStep
 * @param {number} maxPoints
 * @returns {Point[]}
 */
function extend(track, p, minStep, maxPoints) {
  const last = track[track.length - 1];
  if (last && Math.hypot(p.x - last.x, p.y - last.y) < minStep) return track;
  track.push(p);
  return track.length > maxPoints ? thin(track) : track;
}

// The estimated track (status.pose) and the true one (status.truth.odometry), point by point as
// the statuses arrive. A new driver frame — the pose's distance or the mission time going back —
// starts both again.
export class TrackLog {
  /** @param {{ minStep?: number, maxPoints?: number }} [options] */
  constructor({ minStep = MIN_STEP_M, maxPoints = MAX_TRACK_POINTS } = {}) {
    this.minStep = minStep;
    this.maxPoints = maxPoints;
    /** @type {Point[]} */
    this.estimated = [];
    /** @type {Point[]} */
    this.truth = [];
    /** @type {number | null} */
    this.lastDistance = null;
    /** @type {number | null} */
    this.lastTime = null;
    this.frames = 1;  // driver frames seen (restarts + 1)
  }

  clear() {
    this.estimated = [];
    this.truth = [];
  }

  /**
   * One status; true when it started a new frame (the tracks were cleared).
   * @param {Partial<Pick<Status, 'pose' | 'truth' | 'mission_time_s'>>} s
   */
  add(s) {
    const distance = s.pose?.distance_m;
    const time = s.mission_time_s;
    const restarted = (finite(distance) && this.lastDistance !== null && distance < this.lastDistance) ||
      (finite(time) && this.lastTime !== null && time < this.lastTime);
    if (restarted) {
      this.clear();
      this.frames += 1;
    }
    if (finite(distance)) this.lastDistance = distance;
    if (finite(time)) this.lastTime = time;
    const pose = s.pose;
    if (pose && finite(pose.x_m) && finite(pose.y_m)) {
      this.estimated = extend(this.estimated, { x: pose.x_m, y: pose.y_m }, this.minStep, this.maxPoints);
    }
    const odometry = s.truth?.odometry;
    if (odometry && finite(odometry.x_m) && finite(odometry.y_m)) {
      this.truth = extend(this.truth, { x: odometry.x_m, y: odometry.y_m }, this.minStep, this.maxPoints);
    }
    return restarted;
  }
}

/**
 * The mission's waypoints as points (status.mission.waypoints: [[x, y], …]); non-finite ones out.
 * @param {MissionStatus | undefined} mission
 * @returns {Point[]}
 */
export function missionWaypoints(mission) {
  const list = Array.isArray(mission?.waypoints) ? mission.waypoints : [];
  return list.flatMap((w) => {
    if (!Array.isArray(w)) return [];
    const [x, y] = w;
    return finite(x) && finite(y) ? [{ x, y }] : [];
  });
}

/**
 * Where the running mission is heading: goto's waypoint `leg`, move's end point; null otherwise
 * (turn has no point; a finished mission no target).
 * @param {MissionStatus | undefined} mission
 * @returns {Point | null}
 */
export function missionTarget(mission) {
  if (!mission || mission.state !== 'running') return null;
  const points = missionWaypoints(mission);
  if (mission.kind === 'goto') return points[Math.min(Math.max(0, mission.leg ?? 0), points.length - 1)] ?? null;
  if (mission.kind === 'move') return points[0] ?? null;
  return null;
}

// ---- The panel (browser only) ----

export class MapPanel {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {{ onClick?: (p: Point) => void }} [options]  a click on the map, in metres
   */
  constructor(canvas, { onClick } = {}) {
    this.canvas = canvas;
    this.tracks = new TrackLog();
    /** @type {Status | null} */
    this.status = null;
    /** @type {Point[]} */
    this.draft = [];
    this.dirty = true;
    /** @type {Transform} */
    this.transform = { scale: 1, ox: 0, oy: 0 };
    this.width = 0;
    this.height = HEIGHT_PX;
    canvas.addEventListener('click', (event) => {
      const rect = canvas.getBoundingClientRect();
      onClick?.(toWorld(this.transform, { x: event.clientX - rect.left, y: event.clientY - rect.top }));
    });
    new ResizeObserver(() => { this.dirty = true; }).observe(canvas.parentElement ?? canvas);
  }

  /** @param {Status} status */
  update(status) {
    this.tracks.add(status);
    this.status = status;
    this.dirty = true;
  }

  clearTrack() {
    this.tracks.clear();
    this.dirty = true;
  }

  /** @param {Point[]} points  waypoints typed or clicked into the form, not yet sent */
  setDraft(points) {
    this.draft = points;
    this.dirty = true;
  }

  // Everything the view must show.
  /** @returns {Point[]} */
  points() {
    const s = this.status;
    const mission = s?.mission;
    /** @type {Point[]} */
    const points = [...this.tracks.estimated, ...this.tracks.truth, ...this.draft, ...missionWaypoints(mission)];
    const pose = s?.pose;
    if (pose && finite(pose.x_m) && finite(pose.y_m)) {
      const r = finite(pose.position_sigma_m) ? pose.position_sigma_m : 0;
      points.push({ x: pose.x_m - r, y: pose.y_m - r }, { x: pose.x_m + r, y: pose.y_m + r });
    }
    return points;
  }

  draw() {
    if (!this.dirty) return;
    this.dirty = false;
    const canvas = this.canvas;
    const width = Math.max(1, canvas.parentElement?.clientWidth ?? canvas.clientWidth);
    const height = HEIGHT_PX;
    const ratio = window.devicePixelRatio || 1;
    if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
      canvas.width = Math.round(width * ratio);
      canvas.height = Math.round(height * ratio);
      canvas.style.width = `${width}px`;
      canvas.style.height = `${height}px`;
    }
    const ctx = canvas.getContext('2d');
    if (!ctx) return;
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, width, height);
    const t = fitView(boundsOf(this.points()), width, height);
    this.transform = t;
    this.width = width;
    this.height = height;
    this.drawGrid(ctx, t, width, height);
    this.drawTrack(ctx, t, this.tracks.truth, COLORS.truth, [6, 4]);
    this.drawTrack(ctx, t, this.tracks.estimated, COLORS.estimated, []);
    this.drawWaypoints(ctx, t);
    this.drawRover(ctx, t);
  }

  /**
   * @param {CanvasRenderingContext2D} ctx
   * @param {Transform} t
   * @param {number} width
   * @param {number} height
   */
  drawGrid(ctx, t, width, height) {
    const step = gridStep(t.scale);
    const lo = toWorld(t, { x: 0, y: height });
    const hi = toWorld(t, { x: width, y: 0 });
    ctx.lineWidth = 1;
    for (const [axis, from, to] of /** @type {const} */ ([['x', lo.x, hi.x], ['y', lo.y, hi.y]])) {
      for (let v = Math.ceil(from / step) * step; v <= to; v += step) {
        const zero = Math.abs(v) < step / 1e6;
        ctx.strokeStyle = zero ? COLORS.axis : COLORS.grid;
        ctx.beginPath();
        if (axis === 'x') {
          const px = Math.round(toScreen(t, { x: v, y: 0 }).x) + 0.5;
          ctx.moveTo(px, 0);
          ctx.lineTo(px, height);
        } else {
          const py = Math.round(toScreen(t, { x: 0, y: v }).y) + 0.5;
          ctx.moveTo(0, py);
          ctx.lineTo(width, py);
        }
        ctx.stroke();
      }
    }
    // The scale bar, bottom left: one grid step.
    const bar = step * t.scale;
    const y0 = height - 12;
    ctx.strokeStyle = COLORS.text;
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(10, y0 - 4);
    ctx.lineTo(10, y0);
    ctx.lineTo(10 + bar, y0);
    ctx.lineTo(10 + bar, y0 - 4);
    ctx.stroke();
    ctx.fillStyle = COLORS.text;
    ctx.font = '12px system-ui, sans-serif';
    ctx.fillText(`${formatMetres(step)} (grid)`, 16 + bar, y0);
    const label = 'x →  y ↑  (odometry frame)';
    ctx.fillText(label, width - ctx.measureText(label).width - 8, height - 8);
  }

  /**
   * @param {CanvasRenderingContext2D} ctx
   * @param {Transform} t
   * @param {Point[]} track
   * @param {string} color
   * @param {number[]} dash
   */
  drawTrack(ctx, t, track, color, dash) {
    if (track.length < 2) return;
    ctx.strokeStyle = color;
    ctx.lineWidth = 2;
    ctx.setLineDash(dash);
    ctx.beginPath();
    track.forEach((p, i) => {
      const s = toScreen(t, p);
      if (i === 0) ctx.moveTo(s.x, s.y);
      else ctx.lineTo(s.x, s.y);
    });
    ctx.stroke();
    ctx.setLineDash([]);
  }

  /**
   * @param {CanvasRenderingContext2D} ctx
   * @param {Transform} t
   */
  drawWaypoints(ctx, t) {
    const mission = this.status?.mission;
    const points = missionWaypoints(mission);
    /**
     * @param {Point[]} list
     * @param {string} color
     * @param {boolean} filled
     */
    const route = (list, color, filled) => {
      if (list.length > 1) {
        ctx.strokeStyle = color;
        ctx.lineWidth = 1;
        ctx.setLineDash([3, 3]);
        ctx.beginPath();
        list.forEach((p, i) => {
          const s = toScreen(t, p);
          if (i === 0) ctx.moveTo(s.x, s.y);
          else ctx.lineTo(s.x, s.y);
        });
        ctx.stroke();
        ctx.setLineDash([]);
      }
      list.forEach((p, i) => {
        const s = toScreen(t, p);
        ctx.beginPath();
        ctx.arc(s.x, s.y, 5, 0, 2 * Math.PI);
        ctx.strokeStyle = color;
        ctx.lineWidth = 2;
        if (filled) {
          ctx.fillStyle = color;
          ctx.fill();
        }
        ctx.stroke();
        ctx.fillStyle = color;
        ctx.font = '11px system-ui, sans-serif';
        ctx.fillText(String(i + 1), s.x + 7, s.y - 7);
      });
    };
    route(this.draft, COLORS.draft, false);
    route(points, COLORS.waypoint, true);
    const target = missionTarget(mission);
    if (target) {
      const s = toScreen(t, target);
      ctx.strokeStyle = COLORS.target;
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.arc(s.x, s.y, 10, 0, 2 * Math.PI);
      ctx.moveTo(s.x - 14, s.y);
      ctx.lineTo(s.x + 14, s.y);
      ctx.moveTo(s.x, s.y - 14);
      ctx.lineTo(s.x, s.y + 14);
      ctx.stroke();
    }
  }

  /**
   * @param {CanvasRenderingContext2D} ctx
   * @param {Transform} t
   */
  drawRover(ctx, t) {
    const s = this.status;
    const pose = s?.pose;
    if (!pose || !finite(pose.x_m) || !finite(pose.y_m)) return;
    const c = toScreen(t, { x: pose.x_m, y: pose.y_m });
    const sigma = finite(pose.position_sigma_m) ? pose.position_sigma_m * t.scale : 0;
    if (sigma > 0.5) {
      ctx.fillStyle = COLORS.sigma;
      ctx.strokeStyle = COLORS.estimated;
      ctx.lineWidth = 1;
      ctx.setLineDash([2, 3]);
      ctx.beginPath();
      ctx.arc(c.x, c.y, sigma, 0, 2 * Math.PI);
      ctx.fill();
      ctx.stroke();
      ctx.setLineDash([]);
    }
    const heading = finite(pose.heading_rad) ? pose.heading_rad : 0;
    // The heading the mission turns to: a red ray from the rover.
    const mission = s?.mission;
    if (mission?.state === 'running' && finite(mission.target_heading_rad)) {
      const a = mission.target_heading_rad;
      ctx.strokeStyle = COLORS.target;
      ctx.lineWidth = 2;
      ctx.setLineDash([6, 3]);
      ctx.beginPath();
      ctx.moveTo(c.x, c.y);
      ctx.lineTo(c.x + 40 * Math.cos(a), c.y - 40 * Math.sin(a));
      ctx.stroke();
      ctx.setLineDash([]);
    }
    // The rover: a triangle pointing along its heading (screen y is down: −sin).
    const size = 11;
    const ahead = { x: Math.cos(heading), y: -Math.sin(heading) };
    const left = { x: -ahead.y, y: ahead.x };
    ctx.fillStyle = COLORS.estimated;
    ctx.strokeStyle = '#fff';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(c.x + ahead.x * size * 1.4, c.y + ahead.y * size * 1.4);
    ctx.lineTo(c.x - ahead.x * size + left.x * size * 0.8, c.y - ahead.y * size + left.y * size * 0.8);
    ctx.lineTo(c.x - ahead.x * size * 0.5, c.y - ahead.y * size * 0.5);
    ctx.lineTo(c.x - ahead.x * size - left.x * size * 0.8, c.y - ahead.y * size - left.y * size * 0.8);
    ctx.closePath();
    ctx.fill();
    ctx.stroke();
    const truth = s?.truth?.odometry;
    if (truth && finite(truth.x_m) && finite(truth.y_m)) {
      const p = toScreen(t, { x: truth.x_m, y: truth.y_m });
      ctx.fillStyle = COLORS.truth;
      ctx.beginPath();
      ctx.arc(p.x, p.y, 4, 0, 2 * Math.PI);
      ctx.fill();
    }
  }
}

// 0.5 m, 2 m, 10 cm, 5 mm: the grid step for people.
/** @param {number} m */
export function formatMetres(m) {
  if (m >= 1) return `${Number(m.toPrecision(3))} m`;
  if (m >= 0.01) return `${Number((m * 100).toPrecision(3))} cm`;
  return `${Number((m * 1000).toPrecision(3))} mm`;
}
