// uPlot charts of the last 30 s of mission time: duty cycles, wheel speeds, loads, and the supply
// voltage U with its reference Ū beside D of (6.3), the duty bound of power management.

import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import { MOTORS } from './status.js';

/** @typedef {import('./protocol').Status} Status */
/** @typedef {import('./protocol').MotorName} MotorName */
/** @typedef {import('./protocol').StatusNumber} StatusNumber */

/**
 * One chart: its series, and the value of each for a status (null or undefined: a gap).
 * @typedef {{ title: string, unit: string, series: uPlot.Series[],
 *   values: (s: Status) => (StatusNumber | undefined)[], range?: uPlot.Range.MinMax,
 *   secondAxis?: string }} Chart
 */

const WINDOW_S = 30;
const REDRAW_MS = 100;
const HEIGHT_PX = 170;
const COLORS = ['#e6194b', '#3cb44b', '#4363d8', '#f58231', '#911eb4', '#42a5b5', '#9a6324', '#808000'];
const WHEELS = MOTORS.slice(0, 6);

/**
 * @param {MotorName[]} names
 * @returns {uPlot.Series[]}
 */
const motorSeries = (names) => names.map((name) => ({
  label: name, stroke: COLORS[MOTORS.indexOf(name)], width: 1.5,
}));

/** @type {Chart[]} */
const CHARTS = [
  {
    title: 'duty cycle d', unit: '',
    series: motorSeries(MOTORS),
    values: (s) => MOTORS.map((m) => s.motors?.[m]?.duty),
    range: [-1, 1],
  },
  {
    title: 'wheel speed w [rad/s]', unit: 'rad/s',
    series: motorSeries(WHEELS),
    values: (s) => WHEELS.map((m) => s.motors?.[m]?.velocity_radps),
  },
  {
    title: 'load l [rad/s]', unit: 'rad/s',
    series: motorSeries(MOTORS),
    values: (s) => MOTORS.map((m) => s.motors?.[m]?.load_radps),
  },
  {
    title: 'torque τ of (4.6) [N·m]', unit: 'N·m',
    series: motorSeries(MOTORS),
    values: (s) => MOTORS.map((m) => s.motors?.[m]?.torque_nm),
  },
  {
    title: 'supply U, Ū [V] and D', unit: 'V',
    series: [
      { label: 'U', stroke: '#d62728', width: 1.5 },
      { label: 'Ū', stroke: '#7f7f7f', width: 1.5, dash: [6, 4] },
      { label: 'D', stroke: '#1f77b4', width: 1.5, scale: 'duty' },
    ],
    values: (s) => [s.supply_v, s.reference_supply_v, s.max_duty],
    secondAxis: 'duty',
  },
];

// Non-finite (null in JSON) becomes a gap, which uPlot draws as a break in the line.
const finiteOrNull = (/** @type {unknown} */ v) => (typeof v === 'number' && Number.isFinite(v) ? v : null);

/**
 * @param {Chart} chart
 * @param {number} width
 * @returns {uPlot.Options}
 */
function chartOptions(chart, width) {
  /** @type {uPlot.Axis[]} */
  const axes = [
    { label: 'mission time [s]', size: 40 },
    { label: chart.unit, size: 50 },
  ];
  // Always the last 30 s, so that the charts line up and a fresh console fills from the right.
  /** @type {uPlot.Scales} */
  const scales = {
    x: { time: false, range: (u, min, max) => (max == null ? [0, WINDOW_S] : [max - WINDOW_S, max]) },
  };
  if (chart.range) scales.y = { range: chart.range };
  if (chart.secondAxis) {
    scales[chart.secondAxis] = { range: [0, 1] };
    axes.push({ scale: chart.secondAxis, side: 1, label: 'D', size: 40, grid: { show: false } });
  }
  return {
    title: chart.title,
    width, height: HEIGHT_PX,
    scales, axes,
    legend: { live: false },
    cursor: { drag: { x: false, y: false } },
    series: [{ label: 't [s]', value: (u, v) => (v == null ? '–' : v.toFixed(2)) }, ...chart.series],
  };
}

export class Plots {
  /** @param {HTMLElement} container */
  constructor(container) {
    this.container = container;
    // Per chart: the times, and one column of values per series.
    /** @type {{ times: number[], values: (number | null)[][] }[]} */
    this.data = CHARTS.map((chart) => ({ times: [], values: chart.series.map(() => []) }));
    this.plots = CHARTS.map((chart, i) => {
      const div = document.createElement('div');
      div.className = 'plot';
      container.appendChild(div);
      return new uPlot(chartOptions(chart, this.chartWidth()), this.aligned(i), div);
    });
    this.dirty = false;
    this.lastDraw = 0;
    new ResizeObserver(() => this.resize()).observe(container);
  }

  /**
   * Chart i's data as uPlot takes it.
   * @param {number} i
   * @returns {uPlot.AlignedData}
   */
  aligned(i) {
    return [this.data[i].times, ...this.data[i].values];
  }

  chartWidth() {
    const style = getComputedStyle(this.container);
    const columns = style.gridTemplateColumns ? style.gridTemplateColumns.split(' ').length : 1;
    return Math.max(240, Math.floor(this.container.clientWidth / columns) - 16);
  }

  resize() {
    const width = this.chartWidth();
    for (const plot of this.plots) plot.setSize({ width, height: HEIGHT_PX });
  }

  /** @param {Status} status */
  add(status) {
    const t = status.mission_time_s;
    if (typeof t !== 'number' || !Number.isFinite(t)) return;
    CHARTS.forEach((chart, i) => {
      const { times, values } = this.data[i];
      // The driver restarted (mission time went back): start over rather than draw a zigzag.
      if (times.length && t < times[times.length - 1]) {
        times.length = 0;
        values.forEach((c) => { c.length = 0; });
      }
      times.push(t);
      chart.values(status).forEach((v, k) => values[k].push(finiteOrNull(v)));
      let old = 0;
      while (old < times.length && times[old] < t - WINDOW_S) ++old;
      if (old) {
        times.splice(0, old);
        values.forEach((c) => c.splice(0, old));
      }
    });
    this.dirty = true;
  }

  // Called every animation frame; redraws at most every REDRAW_MS.
  /** @param {number} now */
  draw(now) {
    if (!this.dirty || now - this.lastDraw < REDRAW_MS) return;
    this.plots.forEach((plot, i) => plot.setData(this.aligned(i)));
    this.dirty = false;
    this.lastDraw = now;
  }
}
