// What main.js puts on `window` for the browser's developer tools and the tests.
import type { Link } from './link.js';
import type { RoverView } from './view3d.js';
import type { MapPanel } from './map.js';
import type { Status } from './protocol';

declare global {
  interface Window {
    marsokhod: { link: Link; view: RoverView; map: MapPanel; status: Status | null };
  }
}

export {};
