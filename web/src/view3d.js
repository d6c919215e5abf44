// The rover in 3-D (three.js), z up, x forward, y left as in the simulator (rover_mjcf.cpp).
// Side view of one lever (Figure 3.3, chassis_geometry.hpp): the strut of length b from the center
// axle to the joint, the lever of length a from the joint to the exterior axle, the bend γ between
// them (γf = −p6, γr = +p7):
//   c(γ) = sqrt(a² + b² − 2ab·cos γ)          distance of the exterior axle from the center axle
//   α    = arccos((b² + c² − a²) / (2bc))     elevation of the strut above the axles' line
// With the simulator's ground truth (status.truth) the rover stands where the simulator has it;
// without (a real rover) it stands level at the origin with the joints at their measured angles.

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

/** @typedef {import('./protocol').Status} Status */
/** @typedef {import('./protocol').MotorName} MotorName */
/** @typedef {import('./protocol').Truth} Truth */

/**
 * The lever geometry (chassis_geometry.hpp) and the wheels' size [m].
 * @typedef {{ joint_to_exterior_axle_m: number, center_axle_to_joint_m: number,
 *   wheel_radius_m: number, track_width_m: number, wheel_width_m: number }} Geometry
 */

/** The rover to draw: where it stands and turns, its wheels in its own frame, their angles.
 * @typedef {{ source: 'truth' | 'joints', position: THREE.Vector3, rotation: THREE.Euler,
 *   wheels: THREE.Vector3[], wheelAngles: (number | null | undefined)[] }} Pose
 */

/** @type {Geometry} */
export const GEOMETRY = {
  joint_to_exterior_axle_m: 0.145,  // a
  center_axle_to_joint_m: 0.413,    // b
  wheel_radius_m: 0.125,            // r
  track_width_m: 0.70,
  wheel_width_m: 0.15,
};

/** @type {MotorName[]} */
const WHEELS = ['FL', 'FR', 'CL', 'CR', 'BL', 'BR'];
const BLADES_PER_WHEEL = 12;
const GROUND_SIZE_M = 200;

/**
 * @param {number} bend_rad
 * @param {Geometry} [g]
 */
export function axleDistance(bend_rad, g = GEOMETRY) {
  const a = g.joint_to_exterior_axle_m, b = g.center_axle_to_joint_m;
  return Math.sqrt(a * a + b * b - 2 * a * b * Math.cos(bend_rad));
}

/**
 * @param {number} axle_distance_m
 * @param {Geometry} [g]
 */
export function strutElevation(axle_distance_m, g = GEOMETRY) {
  const a = g.joint_to_exterior_axle_m, b = g.center_axle_to_joint_m, c = axle_distance_m;
  return Math.acos(Math.max(-1, Math.min(1, (b * b + c * c - a * a) / (2 * b * c))));
}

// The joint above the line from the center axle to an exterior axle at (x, z) of the side view.
/**
 * @param {number} axle_x
 * @param {number} axle_z
 * @param {Geometry} [g]
 * @returns {[number, number]}
 */
export function jointPosition(axle_x, axle_z, g = GEOMETRY) {
  const c = Math.hypot(axle_x, axle_z);
  const alpha = strutElevation(c, g);
  const ux = axle_x / c, uz = axle_z / c;
  // The perpendicular that points up, for the front (u ≈ +x) and the rear (u ≈ −x) alike.
  let nx = -uz, nz = ux;
  if (nz < 0) { nx = -nx; nz = -nz; }
  const b = g.center_axle_to_joint_m;
  return [b * (Math.cos(alpha) * ux + Math.sin(alpha) * nx), b * (Math.cos(alpha) * uz + Math.sin(alpha) * nz)];
}

/**
 * @param {unknown} v
 * @returns {v is number}
 */
const finite = (v) => typeof v === 'number' && Number.isFinite(v);
/**
 * @param {unknown} v
 * @param {number} n
 * @returns {v is number[]}
 */
const finiteVector = (v, n) => Array.isArray(v) && v.length >= n && v.slice(0, n).every(finite);

// The pose to draw, in the rover's frame (center axle at the origin) plus its place in the world.
// `truth` keys (the simulator's GroundTruth): position_m, roll_pitch_yaw_rad, joint_angle_rad
// (8: wheels' angles, then p6, p7), wheel_position_m (6 × [x, y, z]), wheel_angle_rad (6, optional).
/**
 * The pose from the simulator's truth, or null when a part of it is missing or not finite.
 * @param {Truth | undefined} truth
 * @param {Pose['wheelAngles']} wheelAngles
 * @returns {Pose | null}
 */
function truthPose(truth, wheelAngles) {
  const wheelPositions = truth?.wheel_position_m;
  if (!truth || !finiteVector(truth.position_m, 3) || !finiteVector(truth.roll_pitch_yaw_rad, 3) ||
      !Array.isArray(wheelPositions) || wheelPositions.length < 6 ||
      !wheelPositions.every((w) => finiteVector(w, 3))) return null;
  const position = new THREE.Vector3().fromArray(truth.position_m);
  const [roll, pitch, yaw] = truth.roll_pitch_yaw_rad;
  // R = Rz(yaw)·Ry(pitch)·Rx(roll): three's 'ZYX' order.
  const rotation = new THREE.Euler(roll, pitch, yaw, 'ZYX');
  const toLocal = new THREE.Quaternion().setFromEuler(rotation).invert();
  const wheels = wheelPositions.slice(0, 6)
    .map((w) => new THREE.Vector3().fromArray(w).sub(position).applyQuaternion(toLocal));
  return { source: 'truth', position, rotation, wheels, wheelAngles };
}

/**
 * @param {Partial<Pick<Status, 'motors' | 'truth'>>} status
 * @param {Geometry} [g]
 * @returns {Pose}
 */
export function roverPose(status, g = GEOMETRY) {
  const truth = status.truth;
  const motor = (/** @type {MotorName} */ name) => status.motors?.[name]?.position_rad;
  const joints = finiteVector(truth?.joint_angle_rad, 8) ? truth.joint_angle_rad : null;
  const p6 = joints ? joints[6] : motor('AF');
  const p7 = joints ? joints[7] : motor('AR');
  const givenAngles = truth?.wheel_angle_rad;
  const wheelAngles = finiteVector(givenAngles, 6) ? givenAngles
    : joints ? joints.slice(0, 6) : WHEELS.map((w) => (finite(motor(w)) ? motor(w) : 0));
  const fromTruth = truthPose(truth, wheelAngles);
  if (fromTruth) return fromTruth;

  const half = g.track_width_m / 2;
  /**
   * @param {unknown} p
   * @param {number} sign
   */
  const level = (p, sign) => (finite(p) ? axleDistance(sign * p, g) : Math.sqrt(
    g.center_axle_to_joint_m ** 2 - g.joint_to_exterior_axle_m ** 2));
  const front = level(p6, -1), rear = level(p7, +1);
  const wheels = [
    [front, half], [front, -half], [0, half], [0, -half], [-rear, half], [-rear, -half],
  ].map(([x, y]) => new THREE.Vector3(x, y, 0));
  return {
    source: 'joints',
    position: new THREE.Vector3(0, 0, g.wheel_radius_m),
    rotation: new THREE.Euler(0, 0, 0, 'ZYX'),
    wheels, wheelAngles,
  };
}

/**
 * The soil's surface around the rover (status.truth.soil, on the simulator's soft soils: the
 * ruts, issue #14) as a triangle mesh: a vertex at each sample, (x0 + c·h, y0 + r·h, height), two
 * triangles a square. Null for a patch that is not one (missing or non-integer sizes, fewer than
 * 2 × 2 samples, a height count that does not match, a height that is not a finite number): the
 * view then keeps what it had.
 * @param {import('./protocol').SoilPatch | undefined} patch
 * @returns {{ positions: Float32Array, indices: Uint32Array, colors: Float32Array,
 *   lowestReliefM: number } | null} lowestReliefM: the deepest point below the patch's plane [m]
 */
export function soilSurface(patch) {
  if (!patch || typeof patch !== 'object') return null;
  const { origin_m: origin, cell_m: h, columns, rows, height_mm: heights } = patch;
  if (!Number.isInteger(columns) || !Number.isInteger(rows) || columns < 2 || rows < 2) return null;
  if (!Array.isArray(origin) || origin.length !== 2 || !origin.every(finite)) return null;
  if (!finite(h) || h <= 0) return null;
  if (!Array.isArray(heights) || heights.length !== rows * columns || !heights.every(finite)) return null;
  const positions = new Float32Array(rows * columns * 3);
  for (let r = 0; r < rows; ++r) {
    for (let c = 0; c < columns; ++c) {
      const k = r * columns + c;
      positions[3 * k] = origin[0] + c * h;
      positions[3 * k + 1] = origin[1] + r * h;
      positions[3 * k + 2] = heights[k] / 1000;
    }
  }
  // Colours by the relief: each vertex's height over the patch's least-squares plane (the ground
  // as it lay, flat or sloped), sand where level, darker in a rut, lighter on a bank: 3 cm deep
  // is 0.55 of the sand's brightness.
  const plane = leastSquaresPlane(positions);
  const colors = new Float32Array(rows * columns * 3);
  let lowestReliefM = 0;
  for (let k = 0; k < rows * columns; ++k) {
    const [x, y, z] = [positions[3 * k], positions[3 * k + 1], positions[3 * k + 2]];
    const relief = z - (plane[0] + plane[1] * x + plane[2] * y);
    lowestReliefM = Math.min(lowestReliefM, relief);
    const shade = Math.min(1.4, Math.max(0.35, 1 + 15 * relief));
    colors.set(SAND.map((v) => Math.min(1, v * shade)), 3 * k);
  }
  const indices = new Uint32Array((rows - 1) * (columns - 1) * 6);
  let n = 0;
  for (let r = 0; r + 1 < rows; ++r) {
    for (let c = 0; c + 1 < columns; ++c) {
      const k = r * columns + c;
      // Counter-clockwise seen from above (+z): the faces' normals point up.
      indices.set([k, k + 1, k + columns + 1, k, k + columns + 1, k + columns], n);
      n += 6;
    }
  }
  return { positions, indices, colors, lowestReliefM };
}

const SAND = [0.45, 0.31, 0.17];  // linear RGB of the soil patch where it is level (≈ #b59673)

/**
 * z = a + b·x + c·y through the points (x, y, z, x, y, z, …) by least squares, about their mean
 * (well conditioned whatever the coordinates); [mean z, 0, 0] when x or y does not vary.
 * @param {Float32Array} p
 * @returns {[number, number, number]}
 */
export function leastSquaresPlane(p) {
  const n = p.length / 3;
  let mx = 0, my = 0, mz = 0;
  for (let k = 0; k < n; ++k) { mx += p[3 * k]; my += p[3 * k + 1]; mz += p[3 * k + 2]; }
  mx /= n; my /= n; mz /= n;
  let sxx = 0, sxy = 0, syy = 0, sxz = 0, syz = 0;
  for (let k = 0; k < n; ++k) {
    const x = p[3 * k] - mx, y = p[3 * k + 1] - my, z = p[3 * k + 2] - mz;
    sxx += x * x; sxy += x * y; syy += y * y; sxz += x * z; syz += y * z;
  }
  const det = sxx * syy - sxy * sxy;
  if (!(det > 1e-12)) return [mz, 0, 0];
  const b = (sxz * syy - syz * sxy) / det;
  const c = (syz * sxx - sxz * sxy) / det;
  return [mz - b * mx - c * my, b, c];
}

// A checkerboard of 0.5 m squares: without marks on the ground the rover's motion is invisible.
// (A texture rather than GridHelper lines, which software renderers draw too faint to see.)
function groundTexture() {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = 64;
  const g = canvas.getContext('2d');
  if (!g) throw new Error('no 2-D canvas for the ground texture');
  g.fillStyle = '#c9a77c';
  g.fillRect(0, 0, 64, 64);
  g.fillStyle = '#b8966b';
  g.fillRect(0, 0, 32, 32);
  g.fillRect(32, 32, 32, 32);
  const texture = new THREE.CanvasTexture(canvas);
  texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
  texture.repeat.set(GROUND_SIZE_M / 1.0, GROUND_SIZE_M / 1.0);  // one 64 px tile = 1 m, 2 × 2 squares
  texture.colorSpace = THREE.SRGBColorSpace;
  texture.anisotropy = 8;
  return texture;
}

/**
 * @param {Geometry} g
 * @param {Record<'wheel' | 'blade', THREE.Material>} materials
 */
function wheelMesh(g, materials) {
  const wheel = new THREE.Group();
  const r = g.wheel_radius_m, w = g.wheel_width_m;
  wheel.add(new THREE.Mesh(new THREE.CylinderGeometry(r * 0.92, r * 0.92, w, 32), materials.wheel));
  // Blades on the rim: they make the wheels' turning visible.
  const blade = new THREE.BoxGeometry(0.012, w, r * 0.16);
  for (let k = 0; k < BLADES_PER_WHEEL; ++k) {
    const angle = (2 * Math.PI * k) / BLADES_PER_WHEEL;
    const mesh = new THREE.Mesh(blade, materials.blade);
    mesh.position.set(Math.sin(angle) * r * 0.92, 0, Math.cos(angle) * r * 0.92);
    mesh.rotation.y = angle;
    wheel.add(mesh);
  }
  const holder = new THREE.Group();  // orientation of the axle; the wheel spins inside it
  holder.add(wheel);
  holder.userData.spin = wheel;
  return holder;
}

// A rod from one point to another (a strut, a lever, an axle).
/**
 * @param {THREE.Object3D} mesh
 * @param {THREE.Vector3} from
 * @param {THREE.Vector3} to
 */
function setRod(mesh, from, to) {
  const direction = new THREE.Vector3().subVectors(to, from);
  mesh.position.copy(from).addScaledVector(direction, 0.5);
  mesh.scale.set(1, Math.max(direction.length(), 1e-6), 1);
  mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), direction.normalize());
}

/**
 * @typedef {{ renderer: THREE.WebGLRenderer, scene: THREE.Scene, camera: THREE.PerspectiveCamera,
 *   controls: OrbitControls }} Stage
 * @typedef {{ strut: THREE.Mesh, lever: THREE.Mesh, axle: THREE.Mesh, joint: THREE.Mesh }} Lever
 * @typedef {{ rover: THREE.Group, levers: Lever[], wheels: THREE.Group[] }} RoverModel
 */

/**
 * The renderer, the lit scene with its ground, and the camera the operator turns; null where the
 * browser gives no WebGL (the container then says so).
 * @param {HTMLElement} container
 * @param {() => void} onChange called when the operator moves the camera
 * @returns {Stage | null}
 */
function createStage(container, onChange) {
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (err) {
    const why = err instanceof Error ? err.message : String(err);
    container.textContent = `No 3-D view: this browser gives no WebGL context (${why}).`;
    container.classList.add('unavailable');
    return null;
  }
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  container.appendChild(renderer.domElement);

  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xe8e4dc);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8d7a66, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(3, -2, 5);
  scene.add(sun);

  // The ground is a backdrop: drawn first and writing no depth, so that the soil's ruts below
  // its level (the soil patch, on soft soils) and wheels sunk into them are not hidden by it.
  const ground = new THREE.Mesh(new THREE.PlaneGeometry(GROUND_SIZE_M, GROUND_SIZE_M),
    new THREE.MeshLambertMaterial({ map: groundTexture(), depthWrite: false }));
  ground.renderOrder = -1;
  scene.add(ground);

  const camera = new THREE.PerspectiveCamera(45, 1, 0.05, 200);
  camera.up.set(0, 0, 1);
  camera.position.set(-1.3, -1.7, 1.0);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.set(0, 0, 0.15);
  controls.addEventListener('change', onChange);
  return { renderer, scene, camera, controls };
}

/**
 * The rover's body, center axle, levers and wheels, added to `scene`.
 * @param {THREE.Scene} scene
 * @param {Geometry} g
 * @returns {RoverModel}
 */
function buildRover(scene, g) {
  const materials = {
    body: new THREE.MeshStandardMaterial({ color: 0xd8d8d0, metalness: 0.2, roughness: 0.6 }),
    rod: new THREE.MeshStandardMaterial({ color: 0x505860, metalness: 0.5, roughness: 0.4 }),
    joint: new THREE.MeshStandardMaterial({ color: 0xc0392b }),
    wheel: new THREE.MeshStandardMaterial({ color: 0x9aa0a6, metalness: 0.4, roughness: 0.5 }),
    blade: new THREE.MeshStandardMaterial({ color: 0x2d3436 }),
  };
  const rover = new THREE.Group();
  scene.add(rover);
  const half = g.track_width_m / 2;
  const bodyWidth = g.track_width_m - g.wheel_width_m - 0.1;
  const body = new THREE.Mesh(new THREE.BoxGeometry(0.5, bodyWidth, 0.14), materials.body);
  body.position.set(0, 0, 0.17);
  rover.add(body);
  const rod = (/** @type {number} */ radius) => {
    const mesh = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, 1, 12), materials.rod);
    rover.add(mesh);
    return mesh;
  };
  setRod(rod(0.03), new THREE.Vector3(0, half - 0.08, 0), new THREE.Vector3(0, -half + 0.08, 0));
  const levers = ['front', 'rear'].map(() => {
    const joint = new THREE.Mesh(new THREE.CylinderGeometry(0.045, 0.045, 0.12, 20), materials.joint);
    rover.add(joint);
    return { strut: rod(0.03), lever: rod(0.03), axle: rod(0.04), joint };
  });
  const wheels = WHEELS.map(() => {
    const wheel = wheelMesh(g, materials);
    rover.add(wheel);
    return wheel;
  });
  return { rover, levers, wheels };
}

/**
 * Places the levers and wheels of `model` as `pose` has them.
 * @param {RoverModel} model
 * @param {Pose} pose
 * @param {Geometry} g
 */
function placeRover(model, pose, g) {
  const axleOf = (/** @type {number} */ left, /** @type {number} */ right) =>
    new THREE.Vector3().addVectors(pose.wheels[left], pose.wheels[right]).multiplyScalar(0.5);
  const ends = [axleOf(0, 1), axleOf(4, 5)];
  const center = new THREE.Vector3(0, 0, 0);
  ends.forEach((axle, i) => {
    const [jx, jz] = jointPosition(axle.x, axle.z, g);
    const joint = new THREE.Vector3(jx, axle.y, jz);
    const parts = model.levers[i];
    setRod(parts.strut, center, joint);
    setRod(parts.lever, joint, axle);
    parts.joint.position.copy(joint);
    const left = pose.wheels[i === 0 ? 0 : 4], right = pose.wheels[i === 0 ? 1 : 5];
    const inward = 0.08 / g.track_width_m;
    setRod(parts.axle, left.clone().lerp(right, inward), right.clone().lerp(left, inward));
  });
  pose.wheels.forEach((position, i) => {
    const holder = model.wheels[i];
    holder.position.copy(position);
    // The exterior axles roll about their own x (θ): orient the wheel along its axle.
    const partner = pose.wheels[i % 2 === 0 ? i + 1 : i - 1];
    const axis = i % 2 === 0 ? position.clone().sub(partner) : partner.clone().sub(position);
    if (axis.lengthSq() > 1e-9) holder.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis.normalize());
    // A positive wheel angle is a turn about +y: the top of the wheel moves forward.
    const angle = pose.wheelAngles[i];
    holder.userData.spin.rotation.y = finite(angle) ? angle : 0;
  });
}

export class RoverView {
  /**
   * @param {HTMLElement} container
   * @param {Geometry} [g]
   */
  constructor(container, g = GEOMETRY) {
    this.container = container;
    this.g = g;
    this.dirty = true;
    /** @type {Pose['source'] | undefined} */
    this.source = undefined;
    /** @type {THREE.Mesh | undefined} the soil's patch (soft soils only) */
    this.soil = undefined;
    this.stage = createStage(container, () => { this.dirty = true; });
    this.model = this.stage ? buildRover(this.stage.scene, g) : null;
    if (!this.stage) return;
    this.update({});  // level, joints vertical, until the first status arrives
    this.resize();
    new ResizeObserver(() => this.resize()).observe(container);
  }

  /** @param {Partial<Pick<Status, 'motors' | 'truth'>>} status */
  update(status) {
    const { stage, model } = this;
    if (!stage || !model) return;
    const pose = roverPose(status, this.g);
    const moved = new THREE.Vector3().subVectors(pose.position, model.rover.position);
    model.rover.position.copy(pose.position);
    model.rover.rotation.copy(pose.rotation);
    // The camera follows the rover, keeping the operator's angle and distance.
    stage.camera.position.add(moved);
    stage.controls.target.add(moved);
    stage.controls.update();
    placeRover(model, pose, this.g);
    this.source = pose.source;
    this.updateSoil(status.truth?.soil);
    this.dirty = true;
  }

  /**
   * A new connection (the server may run on other ground): the last ruts go until a patch comes.
   */
  clearSoil() {
    if (this.soil) this.soil.visible = false;
    if (this.container) this.container.dataset.soil = 'none';
    this.dirty = true;
  }

  /**
   * The ruts: the soil patch the simulator sends about once a second replaces the last one.
   * @param {import('./protocol').SoilPatch | undefined} patch
   */
  updateSoil(patch) {
    if (!this.stage) return;
    if (patch && patch.columns === 0) {  // no soil around the rover's position: nothing to show
      if (this.soil) this.soil.visible = false;
      return;
    }
    const surface = soilSurface(patch);
    if (!surface) return;
    if (!this.soil) {
      const material = new THREE.MeshLambertMaterial({ vertexColors: true });
      this.soil = new THREE.Mesh(new THREE.BufferGeometry(), material);
      this.stage.scene.add(this.soil);
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(surface.positions, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(surface.colors, 3));
    geometry.setIndex(new THREE.BufferAttribute(surface.indices, 1));
    geometry.computeVertexNormals();
    this.soil.geometry.dispose();
    this.soil.geometry = geometry;
    this.soil.visible = true;
    // What is shown, for the operator's tools and the browser tests.
    this.container.dataset.soil = `${patch?.columns}x${patch?.rows}`;
    this.container.dataset.soilPatches = String(Number(this.container.dataset.soilPatches ?? 0) + 1);
    this.container.dataset.soilDeepestMm = String(Math.round(surface.lowestReliefM * 1000));
  }

  resize() {
    if (!this.stage) return;
    const width = Math.max(1, this.container.clientWidth);
    const height = Math.max(1, this.container.clientHeight);
    this.stage.renderer.setSize(width, height);
    this.stage.camera.aspect = width / height;
    this.stage.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  // Called every animation frame; renders only when something changed.
  draw() {
    if (!this.stage || !this.dirty) return;
    this.stage.renderer.render(this.stage.scene, this.stage.camera);
    this.dirty = false;
  }
}
