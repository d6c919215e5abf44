// The messages between the console and the link server, as docs/operator-protocol.md gives them
// (src/link/operator_message.cpp parses the console's, server_messages.cpp and status_json.cpp
// build the server's). Types only: the modules import them in JSDoc,
//   /** @typedef {import('./protocol').Status} Status */
// and `npm test` checks them with `tsc --noEmit` (tsconfig.json).

// ---- Console → server ----

/** The wheel-walking gaits of chapter 5.3, by their protocol ids. */
export type GaitId =
  | 'none'
  | 'rolking'
  | 'front-wheel-walking'
  | 'rear-wheel-walking'
  | 'worm-like'
  | 'rolking-extended-base';

/** The stamp `Link.sendInput` adds to `gamepad` and `targets`. */
export interface InputStamp {
  /** 0 … 2⁵³ − 1, counting up on each connection from 1. */
  seq: number;
  /** The console's clock when sent [ms], any epoch. */
  sent_ms: number;
}

/** The W3C standard gamepad's first 4 axes (each −1..1) and 17 buttons. */
export interface GamepadReading {
  axes: number[];
  buttons: boolean[];
}

export interface GamepadInput extends GamepadReading {
  type: 'gamepad';
}

/** The velocities directly; a field left out is 0, "none" or false. */
export interface TargetsInput {
  type: 'targets';
  v1?: number;
  v2?: number;
  /** Sideways drift (m3, chapter 5.2) [rad/s]. */
  v3?: number;
  v4?: number;
  v6?: number;
  v7?: number;
  gait?: GaitId;
  gait_speed?: number;
  calibration_mode?: boolean;
}

/** cmd_vel: the rover's speed and turn rate directly; a stream like `targets`. */
export interface VelocityInput {
  type: 'velocity';
  /** Forward speed [m/s], < 0 backwards. */
  v_mps: number;
  /** Turn rate [rad/s], > 0 counter-clockwise. */
  yaw_radps: number;
}

/** A waypoint in the odometry frame (the frame of `status.pose`) [m]. */
export interface Waypoint {
  x_m: number;
  y_m: number;
}

/** Turn by a relative heading, + counter-clockwise (left). */
export interface TurnMission {
  type: 'mission';
  kind: 'turn';
  angle_rad: number;
  /** Standing after each leg [s], 0 < s ≤ 60; left out: navigation.settle_s. */
  settle_s?: number;
}

/** Drive a distance along the current heading, < 0 backwards. */
export interface MoveMission {
  type: 'mission';
  kind: 'move';
  distance_m: number;
  /** Standing after each leg [s], 0 < s ≤ 60; left out: navigation.settle_s. */
  settle_s?: number;
}

/** Drive through 1..64 waypoints in the odometry frame. */
export interface GotoMission {
  type: 'mission';
  kind: 'goto';
  waypoints: Waypoint[];
  /** Standing after each leg [s], 0 < s ≤ 60; left out: navigation.settle_s. */
  settle_s?: number;
}

export type MissionInput = TurnMission | MoveMission | GotoMission;

/** Keeps a running mission alive (operator input that moves nothing itself). */
export interface HeartbeatInput {
  type: 'heartbeat';
}

/** An operator input before `Link.sendInput` stamps it. */
export type OperatorInput = GamepadInput | TargetsInput | VelocityInput | MissionInput | HeartbeatInput;

export type GamepadMessage = GamepadInput & InputStamp;
export type TargetsMessage = TargetsInput & InputStamp;
export type VelocityMessage = VelocityInput & InputStamp;
export type MissionMessage = MissionInput & InputStamp;
export type HeartbeatMessage = HeartbeatInput & InputStamp;

export type BehaviourName =
  | 'power_management'
  | 'slant_response'
  | 'contract_on_turn'
  | 'axle_placement';

export type LoadDistribution = 'off' | 'v' | 's';

/** Run-time settings (RuntimeSettings); a key left out leaves that setting as it is. */
export interface ConfigureMessage {
  type: 'configure';
  /** Υ of (6.3) [V], in (0, 10]. */
  max_drop_v?: number;
  load_distribution?: LoadDistribution;
  behaviours?: Partial<Record<BehaviourName, boolean>>;
  /** Scales v1ᵈ, v2ᵈ, v3ᵈ, v4ᵈ, in [0, 1]. */
  speed_scale?: number;
  /** What feeds the rover: on the tether the duties keep the supply's current within its limit. */
  supply?: Supply;
}

/** The run-time settings in force (the status' `settings`): every key present. */
export interface RuntimeSettings {
  max_drop_v: number;
  load_distribution: LoadDistribution;
  behaviours: Record<BehaviourName, boolean>;
  speed_scale: number;
  supply: Supply;
}

/** The rover's supply (Field Experiment 1.1). */
export type Supply = 'battery' | 'tether';

/** The messages without fields. */
export interface CommandMessage {
  type: 'stop' | 'clear_faults' | 'take_control' | 'release_control' | 'ping';
}

export type ConsoleMessage =
  | GamepadMessage
  | TargetsMessage
  | VelocityMessage
  | MissionMessage
  | HeartbeatMessage
  | ConfigureMessage
  | CommandMessage;

// ---- Server → console ----

/** The calibration file the driver loaded on top of the configuration. */
export interface CalibrationInfo {
  /** null: the configuration's nominal values. */
  file: string | null;
  procedures: string[];
}

export interface HelloMessage {
  type: 'hello';
  protocol: number;
  client_id: number;
  /** The controlling client's id, or null. */
  controller: number | null;
  read_only: boolean;
  calibration: CalibrationInfo;
  /** The largest |v_mps| and |yaw_radps| of a `velocity` message; absent from older servers. */
  velocity_limits?: VelocityLimits;
}

/** hello's velocity_limits: r·v1ᵈ [m/s] and r·v2ᵈ/(t/2) [rad/s]. */
export interface VelocityLimits {
  v_mps: number;
  yaw_radps: number;
}

export interface ControlMessage {
  type: 'control';
  controller: number | null;
  read_only: boolean;
  /** True only for the client that held control before. */
  lost_control: boolean;
  reason: string;
}

export interface StoppedMessage {
  type: 'stopped';
  by: number;
  reason: string;
}

export interface ErrorMessage {
  type: 'error';
  /** A path into the message: type, v1, axes[1], behaviours.slant_response, json. */
  field: string;
  message: string;
}

export interface PongMessage {
  type: 'pong';
}

export interface StatusMessage {
  type: 'status';
  status: Status;
}

export type ServerMessage =
  | HelloMessage
  | ControlMessage
  | StoppedMessage
  | ErrorMessage
  | PongMessage
  | StatusMessage;

// ---- The status (status_json) ----

/** A number of the status: one that is not finite is null in JSON. */
export type StatusNumber = number | null;

/** Dead reckoning from the gyro and the centre wheels, in the odometry frame of the driver's start
 * (x forward, y left, heading counter-clockwise). */
export interface Pose {
  x_m: StatusNumber;
  y_m: StatusNumber;
  heading_rad: StatusNumber;
  speed_mps: StatusNumber;
  yaw_rate_radps: StatusNumber;
  distance_m: StatusNumber;
  position_sigma_m: StatusNumber;
  heading_sigma_rad: StatusNumber;
}

/** The tip-over failsafe's attitude (src/core/estimation/failsafes.hpp): + left side up, + nose down. */
export interface Attitude {
  roll_rad: StatusNumber;
  pitch_rad: StatusNumber;
}

/** Motor 0…7 of (3.1). */
export type MotorName = 'FL' | 'FR' | 'CL' | 'CR' | 'BL' | 'BR' | 'AF' | 'AR';

export interface MotorStatus {
  shaft_position_rad: StatusNumber;
  position_rad: StatusNumber;
  position_uncertainty_rad: StatusNumber;
  velocity_radps: StatusNumber;
  no_load_velocity_radps: StatusNumber;
  load_radps: StatusNumber;
  /** τ = l/B±_icr(d) of (4.6) [N·m], the external torque's estimate. */
  torque_nm: StatusNumber;
  commanded_radps: StatusNumber;
  /** The slope hold's share of commanded_radps [rad/s] (a gait's wheels on a slope; else 0). */
  slope_hold_radps: StatusNumber;
  duty: StatusNumber;
  silent_cycles: number;
}

export interface Velocities {
  v1_radps: StatusNumber;
  v2_radps: StatusNumber;
  v3_radps: StatusNumber;
  v4_radps: StatusNumber;
  v6_radps: StatusNumber;
  v7_radps: StatusNumber;
}

export interface GaitStatus {
  id: GaitId;
  /** For people: "rolking with extended base". */
  name: string;
  state: number;
  speed: StatusNumber;
}

export interface JointBounds {
  front_min_rad: StatusNumber;
  front_max_rad: StatusNumber;
  rear_min_rad: StatusNumber;
  rear_max_rad: StatusNumber;
}

export interface BusStatus {
  frames: number;
  malformed: number;
  duplicates: number;
  foreign: number;
  missed: number;
  last_error: string;
}

/** The simulator's ground truth for the 3-D view (only in simulation). */
export interface Truth {
  position_m?: number[];
  roll_pitch_yaw_rad?: number[];
  velocity_mps?: number[];
  /** 8: the wheels' angles, then p6, p7. */
  joint_angle_rad?: number[];
  wheel_angle_rad?: number[];
  /** 6 × [x, y, z]. */
  wheel_position_m?: number[][];
  wheel_slip_mps?: number[];
  supply_v?: number;
  computer_on?: boolean;
  /** The true pose in the odometry frame of the driver's (re)start, the frame of `status.pose`. */
  odometry?: TruthOdometry;
  /** On a soft soil, about once a second: the surface around the rover (its ruts). */
  soil?: SoilPatch;
}

/** The soil's surface on a square grid: height_mm[r·columns + c] at (origin_m[0] + c·cell_m,
 * origin_m[1] + r·cell_m), world z in mm. */
export interface SoilPatch {
  origin_m: number[];
  cell_m: number;
  columns: number;
  rows: number;
  height_mm: number[];
}

/** The simulator's true pose carried into the driver's odometry frame. */
export interface TruthOdometry {
  x_m: StatusNumber;
  y_m: StatusNumber;
  /** Unwrapped, like `pose.heading_rad`. */
  heading_rad: StatusNumber;
}

export type MissionKind = 'none' | 'velocity' | 'turn' | 'move' | 'goto';
export type MissionState = 'idle' | 'running' | 'reached' | 'aborted';

/** The operator's mission: velocity, turn, move or goto. */
export interface MissionStatus {
  /** Counts missions started, 0 before any. */
  id: number;
  kind: MissionKind;
  state: MissionState;
  /** Why it was aborted, else "". */
  reason: string;
  /** 0..1. */
  progress: StatusNumber;
  /** goto: the index of the waypoint being driven to; else 0. */
  leg: number;
  /** goto's waypoints; turn/move: [[x, y]] of the end point ([] for turn). */
  waypoints: StatusNumber[][];
  /** The heading being turned or held to (null when none). */
  target_heading_rad: StatusNumber;
  /** Distance still to go (null for turn). */
  remaining_m: StatusNumber;
  /** Heading still to turn (null when none). */
  remaining_rad: StatusNumber;
  /** Legs driven again after ending off their target. */
  corrections?: number;
  /** The mission's standing after each leg [s] (0 before any mission and for velocity). */
  settle_s?: number;
}

export interface Status {
  mission_time_s: StatusNumber;
  cycle_time_s: StatusNumber;
  cycle: number;
  mode: 'startup' | 'driving' | 'calibration' | 'fault';
  startup_phase: 'configure' | 'dead-man' | 'calibrate' | 'done';
  supply_v: StatusNumber;
  reference_supply_v: StatusNumber;
  yaw_rate_radps: StatusNumber;
  accel_mps2: StatusNumber[];
  front_tilt_rad: StatusNumber;
  rear_tilt_rad: StatusNumber;
  slope_rad: StatusNumber;
  motors: Record<MotorName, MotorStatus>;
  sensor_silent_cycles: number;
  max_duty: StatusNumber;
  /** The supply's current the duties sent could draw at most, every motor stalled [A]. */
  supply_current_bound_a: StatusNumber;
  /** D_I: the bound on D that keeps that within the tether's limit (1 on the battery). */
  current_duty_bound: StatusNumber;
  driving_scale: StatusNumber;
  walking_scale: StatusNumber;
  targets: Velocities;
  commands: Velocities;
  gait: GaitStatus;
  front_axle_factor: StatusNumber;
  rear_axle_factor: StatusNumber;
  joint_bounds: JointBounds;
  joints_known: boolean;
  joint_origin: string;
  operator_timeout: boolean;
  operator_rejection: string;
  stop_latched: boolean;
  stop_reason: string;
  faults: string[];
  warnings: string[];
  bus: BusStatus;
  lcd: string;
  pose: Pose;
  attitude: Attitude;
  stalled_s: StatusNumber;
  /** Front and rear joint; absent from older servers. */
  joint_stalled_s?: StatusNumber[];
  /** Absent from servers without missions. */
  mission?: MissionStatus;
  /** The run-time settings in force; absent from older servers. */
  settings?: RuntimeSettings;
  truth?: Truth;
}
