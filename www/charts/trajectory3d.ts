// Paper Fig. "3D trajectory of the UAV": the true flight and each model's station estimate,
// rotatable with the mouse or touch (three.js + OrbitControls). The scene is recentred on the
// flight; z is up, as in ENU.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { Line2 } from 'three/addons/lines/Line2.js';
import { LineGeometry } from 'three/addons/lines/LineGeometry.js';
import { LineMaterial } from 'three/addons/lines/LineMaterial.js';
import type { SimReport } from '../loratrack';
import { MODEL_COLORS, PLAN_COLOR, TRUTH_COLOR } from './colors';

/** What a drawing shows, for its legend. */
export interface Drawn {
  /** Side of one grid square, m. */
  gridStep: number;
  /** Gateways too far to draw in place: shown as markers at the grid's edge, with their distance. */
  farGateways: number;
}

export interface Trajectory3d {
  element: HTMLElement;
  /** Whether the view is drawn: false where the browser offers no WebGL (a note stands there). */
  webgl: boolean;
  update(report: SimReport): Drawn | undefined;
  /** Back to the initial camera. */
  resetView(): void;
  /** The view drawn afresh at least `minWidth` device pixels wide, and the pixels per CSS pixel
   * it used (null when WebGL is unavailable). */
  snapshot(minWidth: number): { canvas: HTMLCanvasElement; scale: number } | null;
}

/** Whether this browser offers WebGL 2, which three.js needs. Asked of a canvas of our own first:
 * three.js finding none logs three console errors before it throws (headless Firefox, a browser
 * with WebGL turned off), which a reader's console should not hold for a view the page does
 * without. The trial context is given back at once. */
function webgl2Offered(): boolean {
  const gl = document.createElement('canvas').getContext('webgl2');
  gl?.getExtension('WEBGL_lose_context')?.loseContext();
  return gl !== null;
}

export function createTrajectory3d(container: HTMLElement): Trajectory3d {
  let renderer: THREE.WebGLRenderer | undefined;
  try {
    if (webgl2Offered()) renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch {
    // The context was offered to the trial and refused to three.js: the same note.
  }
  if (!renderer) {
    const note = document.createElement('p');
    note.className = 'note';
    note.textContent = 'The 3D view needs WebGL, which this browser does not offer. The other charts work without it.';
    container.replaceChildren(note);
    return { element: note, webgl: false, update: () => undefined, resetView: () => undefined, snapshot: () => null };
  }
  const width = () => Math.max(280, container.clientWidth);
  const height = () => Math.min(480, Math.round(width() * 0.6));
  renderer.setPixelRatio(Math.min(2, window.devicePixelRatio));
  renderer.setSize(width(), height());
  renderer.setClearColor(0xffffff);
  // Labels of far gateways, placed over the canvas at their markers after every render.
  const labels = document.createElement('div');
  labels.className = 'gateway-labels';
  labels.setAttribute('aria-hidden', 'true');
  container.style.position = 'relative';
  container.replaceChildren(renderer.domElement, labels);
  renderer.domElement.setAttribute('role', 'img');
  renderer.domElement.setAttribute('aria-label', '3D trajectory: true flight and station estimates; drag to rotate, scroll to zoom');

  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(45, width() / height(), 0.1, 1e6);
  camera.up.set(0, 0, 1);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;
  // The scroll wheel scrolls the page unless the view has focus (or Ctrl is held): a reader
  // scrolling past must not be caught zooming. This listener runs before OrbitControls' own.
  controls.enableZoom = false;
  renderer.domElement.addEventListener('wheel', (e) => (controls.enableZoom = document.activeElement === renderer.domElement || e.ctrlKey), { capture: true });
  const group = new THREE.Group();
  scene.add(group);
  let far: { at: THREE.Vector3; text: string }[] = [];
  /** The far gateways' labels where the camera sees their markers, px from the view's top left. */
  const farLabels = () =>
    far.map(({ at, text }) => {
      const p = at.clone().project(camera);
      return { text, left: Math.round(((p.x + 1) / 2) * width()), top: Math.round(((1 - p.y) / 2) * height()), hidden: p.z > 1 };
    });
  const render = () => {
    renderer.render(scene, camera);
    labels.replaceChildren(
      ...farLabels().map(({ text, left, top, hidden }) => {
        const span = document.createElement('span');
        span.className = 'gateway-label';
        span.textContent = text;
        span.style.left = `${left}px`;
        span.style.top = `${top}px`;
        span.hidden = hidden;
        return span;
      }),
    );
  };
  controls.addEventListener('change', render);
  new ResizeObserver(() => {
    renderer.setSize(width(), height());
    for (const child of group.children) if (child instanceof Line2) child.material.resolution.set(width(), height());
    camera.aspect = width() / height();
    camera.updateProjectionMatrix();
    render();
  }).observe(container);

  /** Adds a track as a line 2 CSS px wide (WebGL draws its own lines 1 device pixel wide: a hairline
   * on a high-density screen, a projector or a slide's PNG); a plan 5 px wide in `dash` m dashes. */
  const addLine = (xs: ArrayLike<number>, ys: ArrayLike<number>, zs: ArrayLike<number>, color: string, centre: THREE.Vector3, dash?: number): void => {
    // A station that never received a packet has no track (and Line2 needs a segment).
    if (xs.length < 2) return;
    const geometry = new LineGeometry();
    const positions = new Float32Array(xs.length * 3);
    for (let i = 0; i < xs.length; i++) {
      positions[3 * i] = xs[i] - centre.x;
      positions[3 * i + 1] = ys[i] - centre.y;
      positions[3 * i + 2] = zs[i] - centre.z;
    }
    geometry.setPositions(positions);
    // The plan is wider, so that where the drone keeps to it its dashes still show beside the tracks on it.
    const material = new LineMaterial({ color, linewidth: dash === undefined ? 2 : 5, dashed: dash !== undefined, dashSize: dash ?? 1, gapSize: (dash ?? 1) * 0.7 });
    // Line widths are in CSS pixels of this size, at any pixel ratio (a snapshot's too).
    material.resolution.set(width(), height());
    const track = new Line2(geometry, material);
    if (dash !== undefined) track.computeLineDistances();
    group.add(track);
  };

  // The camera is placed for the first flight shown and for each new one; changing a setting
  // keeps the user's rotation and zoom.
  let placedFor = '';
  let lastSize = 10;
  const place = () => {
    camera.position.set(lastSize * 0.9, -lastSize * 0.9, lastSize * 0.7);
    controls.target.set(0, 0, 0);
    controls.update();
    render();
  };
  renderer.domElement.tabIndex = 0;
  // Keyboard: arrows rotate, + and − zoom (OrbitControls' own keys pan).
  renderer.domElement.addEventListener('keydown', (e) => {
    const offset = camera.position.clone().sub(controls.target);
    const spherical = new THREE.Spherical().setFromVector3(new THREE.Vector3(offset.x, offset.z, -offset.y));
    const turn = { ArrowLeft: [-0.1, 0], ArrowRight: [0.1, 0], ArrowUp: [0, -0.1], ArrowDown: [0, 0.1] }[e.key];
    if (turn) {
      spherical.theta += turn[0];
      spherical.phi = Math.min(Math.PI - 0.01, Math.max(0.01, spherical.phi + turn[1]));
    } else if (e.key === '+' || e.key === '=') spherical.radius *= 0.85;
    else if (e.key === '-') spherical.radius /= 0.85;
    else return;
    e.preventDefault();
    const v = new THREE.Vector3().setFromSpherical(spherical);
    camera.position.copy(controls.target).add(new THREE.Vector3(v.x, -v.z, v.y));
    controls.update();
    render();
  });

  return {
    element: renderer.domElement,
    webgl: true,
    resetView: place,
    update(report: SimReport) {
      const s = report.series;
      if (!s) return;
      // Everything drawn for the last report (tracks, grid, gateways) leaves the scene now and gives
      // its GPU buffers back once the new drawing is rendered: disposed before it, its materials
      // took their compiled shaders with them, and every redraw compiled and linked them again.
      const last = [...group.children];
      group.remove(...last);
      const box = new THREE.Box3().setFromPoints(Array.from(s.x, (x, i) => new THREE.Vector3(x, s.y[i], s.z[i])));
      const centre = box.getCenter(new THREE.Vector3());
      const size = box.getSize(new THREE.Vector3()).length() || 10;
      addLine(s.x, s.y, s.z, TRUTH_COLOR, centre);
      // The mission's plan: dashed, so it reads as intent rather than a track.
      if (s.plan) addLine(s.plan.map((w) => w[0]), s.plan.map((w) => w[1]), s.plan.map((w) => w[2]), PLAN_COLOR, centre, size * 0.015);
      for (const m of s.models) addLine(m.x, m.y, m.z, MODEL_COLORS[m.model], centre);
      const grid = new THREE.GridHelper(size * 1.2, 12, 0xcccccc, 0xeeeeee);
      grid.rotation.x = Math.PI / 2;
      grid.position.z = box.min.z - centre.z;
      group.add(grid);
      // Every gateway, at its place when near the flight; otherwise a marker at the grid's edge
      // in its direction, labelled with its distance (the view would shrink the flight to a dot).
      far = [];
      (s.gateways ?? [s.gateway]).forEach(([gx, gy, gz], i, all) => {
        const gateway = new THREE.Mesh(new THREE.ConeGeometry(size * 0.015, size * 0.05, 12), new THREE.MeshBasicMaterial({ color: 0x444444 }));
        gateway.rotation.x = Math.PI / 2;
        const at = new THREE.Vector3(gx - centre.x, gy - centre.y, gz - centre.z);
        if (at.length() > size * 3) {
          const ground = new THREE.Vector3(at.x, at.y, 0);
          const edge = ground.clone().setLength(size * 0.6);
          edge.z = box.min.z - centre.z;
          // Grey as every gateway: an orange one stood beside the mission station's orange track.
          gateway.position.copy(edge);
          far.push({ at: edge, text: `${all.length > 1 ? `gateway ${i + 1}` : 'gateway'} ${(ground.length() / 1000).toFixed(1)} km →` });
        } else gateway.position.copy(at);
        group.add(gateway);
      });
      lastSize = size;
      if (placedFor !== s.flight) {
        placedFor = s.flight;
        place();
      } else render();
      for (const child of last) {
        const drawn = child as THREE.Mesh;
        drawn.geometry?.dispose();
        for (const material of [drawn.material ?? []].flat()) material.dispose();
      }
      return { gridStep: (size * 1.2) / 12, farGateways: far.length };
    },
    snapshot(minWidth: number) {
      const ratio = renderer.getPixelRatio();
      const scale = Math.max(2, minWidth / width());
      renderer.setPixelRatio(scale);
      renderer.setSize(width(), height());
      render();
      const copy = document.createElement('canvas');
      copy.width = renderer.domElement.width;
      copy.height = renderer.domElement.height;
      const ctx = copy.getContext('2d')!;
      ctx.drawImage(renderer.domElement, 0, 0);
      // The far gateways' labels are HTML over the canvas on the page: drawn in, as `.gateway-label`
      // places them (centred above the marker), so that the picture gives their distance too.
      ctx.font = `${13 * scale}px system-ui, sans-serif`;
      ctx.textAlign = 'center';
      ctx.fillStyle = '#333';
      for (const { text, left, top, hidden } of farLabels()) if (!hidden) ctx.fillText(text, left * scale, top * scale - 8 * scale);
      renderer.setPixelRatio(ratio);
      renderer.setSize(width(), height());
      render();
      return { canvas: copy, scale };
    },
  };
}
