// The reconstruction in 3D (three.js, served from /vendor): the point cloud
// and its surface mesh (Delaunay over the ground plane, delaunator) coloured
// by the grind plane each point lies on (ground and rock otherwise, the
// colours of `petra eval`: GET /api/palette), a disc per plane, the arm
// as ARM_STATUS reports it (solid) and the pose planned for the picked plane
// (ghost, with its standoff waypoint). Drag to rotate, wheel to zoom.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import Delaunator from 'delaunator';

// Triangles with an edge longer than this many times the median edge span a
// gap in the cloud (occlusion, the rock's outline): not drawn.
const MAX_EDGE_OVER_MEDIAN = 3;

export class View3D {
  // palette: GET /api/palette (tlm/palette.hpp).
  constructor(el, palette) {
    this.el = el;
    this.palette = palette;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.setClearColor(0x101317);
    el.appendChild(this.renderer.domElement);
    this.label = document.createElement('div');
    this.label.className = 'overlay-label';
    el.appendChild(this.label);
    this.scene = new THREE.Scene();
    this.scene.add(new THREE.AmbientLight(0xffffff, 1.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.set(1, -1, -1);
    this.scene.add(sun);
    this.camera = new THREE.PerspectiveCamera(45, 1, 1, 20000);
    this.camera.up.set(0, -1, 0);
    this.camera.position.set(0, 0, -500);
    this.groups = { cloud: new THREE.Group(), planes: new THREE.Group(), pose: new THREE.Group(),
                    arm: new THREE.Group(), plan: new THREE.Group() };
    for (const g of Object.values(this.groups)) this.scene.add(g);
    this.points = null;
    this.planes = [];
    this.ground = null;
    this.resetControls();
    new ResizeObserver(() => this.resize()).observe(el);
    this.resize();
  }

  // Renders once on the next animation frame, only when something changed
  // (a continuous loop keeps a CPU core busy where WebGL is software).
  redraw() {
    if (this.pending) return;
    this.pending = requestAnimationFrame(() => {
      this.pending = 0;
      this.renderer.render(this.scene, this.camera);
    });
  }

  resetControls() {
    if (this.controls) this.controls.dispose();
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = false;
    this.controls.addEventListener('change', () => this.redraw());
    this.redraw();
  }

  resize() {
    const w = this.el.clientWidth, h = this.el.clientHeight;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.redraw();
  }

  setLabel(text) { this.label.textContent = text; }

  planeColour(rank) { return this.palette.planes[Math.min(rank, this.palette.planes.length - 1)]; }

  // What is drawn, for the operator's checks and the end-to-end test.
  stats() {
    const tipOf = (g) => (g.userData.skeleton ? g.userData.skeleton[g.userData.skeleton.length - 1] : null);
    return { points: this.points ? this.points.length / 3 : 0, colourCounts: this.colourCounts || [],
             meshTriangles: this.meshTriangles || 0, canvases: this.el.querySelectorAll('canvas').length,
             planes: this.groups.planes.children.length, armTip: tipOf(this.groups.arm), planTip: tipOf(this.groups.plan),
             armMeshes: this.groups.arm.children.length, planMeshes: this.groups.plan.children.length,
             camera: this.camera.position.toArray() };
  }

  // Ground plane: {normal:[3], d_mm}; "up" is along its normal.
  setGround(ground) { this.ground = ground; }

  setCloud(xyz) {
    this.points = xyz;
    this.rebuildCloud();
    this.frame();
  }

  // Frame the rock and the arm (once its base is known), "up" along the
  // ground normal (world z otherwise).
  // mode 'arm': the rock and the whole arm; 'rock': a close-up of the rock.
  frame(mode = this.mode || 'arm') {
    this.mode = mode;
    if (!this.points) return;
    const box = new THREE.Box3().setFromBufferAttribute(new THREE.BufferAttribute(this.points, 3));
    const rock = box.getCenter(new THREE.Vector3());
    const rockSize = box.getSize(new THREE.Vector3()).length();
    if (this.armBase && mode === 'arm') box.expandByPoint(this.armBase);
    // Mostly the rock, with the arm's reach towards it in view.
    const centre = box.getCenter(new THREE.Vector3()).lerp(rock, 0.45);
    const size = mode === 'rock' ? rockSize * 0.9 : Math.max(box.getSize(new THREE.Vector3()).length(), rockSize * 2);
    const up = new THREE.Vector3().fromArray(this.ground ? this.ground.normal : [0, 0, 1]).normalize();
    this.camera.up.copy(up);
    // From the rig's side (towards the world origin), above, and from the
    // side away from the arm: the rock in front, the whole arm beside it.
    const back = rock.clone().negate();
    back.addScaledVector(up, -back.dot(up));
    if (back.lengthSq() < 1) back.set(0, -1, 0);
    back.normalize();
    const side = new THREE.Vector3().crossVectors(up, back).normalize();
    if (this.armBase && side.dot(this.armBase.clone().sub(rock)) > 0) side.negate();
    this.camera.position.copy(centre).addScaledVector(back, size * 0.55)
      .addScaledVector(side, size * 0.8).addScaledVector(up, size * 0.6);
    this.camera.near = size / 100;
    this.camera.far = size * 20;
    this.camera.updateProjectionMatrix();
    this.resetControls();
    this.controls.target.copy(centre);
    this.controls.update();
    this.drawGrid(rock, up);
  }

  // A 100 mm grid on the ground plane (GROUND_PLANE, else world z = 0) for depth.
  drawGrid(near, up) {
    if (this.grid) this.scene.remove(this.grid);
    this.grid = new THREE.GridHelper(1400, 14, 0x3a4450, 0x2a323b);
    // GridHelper lies in its x-z plane: turn its y axis onto the ground normal.
    this.grid.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), up);
    const d = this.ground ? this.ground.d_mm : 0;
    const onPlane = near.clone().addScaledVector(up, -(near.dot(up) + d));
    this.grid.position.copy(onPlane);
    this.scene.add(this.grid);
    this.redraw();
  }

  // The arm from its skeleton (base, shoulder, elbow, wrist, hand end, tip;
  // mm, world): `group` 'arm' (telemetry, solid) or 'plan' (ghost).
  setArm(which, skeleton, options = {}) {
    const group = this.groups[which];
    group.clear();
    group.userData.skeleton = skeleton;
    if (!skeleton) return;
    const pts = skeleton.map((p) => new THREE.Vector3().fromArray(p));
    if (which === 'arm' && !this.armBase) { this.armBase = pts[0].clone(); this.frame(); }
    const ghost = which === 'plan';
    const colour = ghost ? 0xffd479 : 0xc9ced6;
    const material = new THREE.MeshStandardMaterial({ color: colour, metalness: 0.2, roughness: 0.6,
      transparent: ghost, opacity: ghost ? 0.45 : 1, depthWrite: !ghost });
    const radii = [22, 16, 13, 11, 9];  // base column, upper arm, forearm, hand, tool
    for (let k = 0; k < pts.length - 1; ++k) {
      const a = pts[k], b = pts[k + 1];
      const len = a.distanceTo(b);
      if (len < 1e-6) continue;
      const link = new THREE.Mesh(new THREE.CylinderGeometry(radii[k], radii[k], len, 20), material);
      link.position.copy(a).add(b).multiplyScalar(0.5);
      link.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), b.clone().sub(a).normalize());
      group.add(link);
    }
    for (let k = 0; k < pts.length - 1; ++k) {
      const joint = new THREE.Mesh(new THREE.SphereGeometry(radii[Math.min(k, 4)] * 1.25, 20, 14), material);
      joint.position.copy(pts[k]);
      group.add(joint);
    }
    // The grinder disc at the tip, across the tool axis.
    const tip = pts[pts.length - 1], hand = pts[pts.length - 2];
    const disc = new THREE.Mesh(new THREE.CylinderGeometry(20, 20, 6, 32),
      new THREE.MeshStandardMaterial({ color: ghost ? 0xffd479 : 0xff9f43, transparent: ghost, opacity: ghost ? 0.5 : 1 }));
    disc.position.copy(tip);
    disc.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), tip.clone().sub(hand).normalize());
    group.add(disc);
    if (options.waypoint) {
      const marker = new THREE.Mesh(new THREE.SphereGeometry(6, 16, 12), new THREE.MeshBasicMaterial({ color: 0xffd479 }));
      marker.position.fromArray(options.waypoint);
      group.add(marker);
      const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3().fromArray(options.waypoint), tip]),
        new THREE.LineDashedMaterial({ color: 0xffd479, dashSize: 6, gapSize: 4 }));
      line.computeLineDistances();
      group.add(line);
    }
    this.redraw();
  }

  setPlanes(planes) {
    this.planes = planes;
    this.rebuildCloud();
    this.groups.planes.clear();
    for (const p of planes) {
      const radius = Math.sqrt(p.area_mm2 / Math.PI);
      const disc = new THREE.Mesh(new THREE.CircleGeometry(radius, 48),
        new THREE.MeshBasicMaterial({ color: this.planeColour(p.rank), transparent: true, opacity: 0.25, side: THREE.DoubleSide, depthWrite: false }));
      disc.position.fromArray(p.centroid_mm);
      disc.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3().fromArray(p.normal).normalize());
      this.groups.planes.add(disc);
    }
    this.redraw();
  }

  // Each point takes the colour of the plane it lies on (within the plane's
  // flatness and area); the others are grey.
  rebuildCloud() {
    this.groups.cloud.clear();
    if (!this.points) return;
    const n = this.points.length / 3;
    const colours = new Float32Array(n * 3);
    const c = new THREE.Color();
    const fits = this.planes.map((p) => ({
      n: new THREE.Vector3().fromArray(p.normal).normalize(), o: new THREE.Vector3().fromArray(p.centroid_mm),
      tol: Math.max(1.5, 3 * p.flatness_rms_mm), r2: 1.5 * p.area_mm2 / Math.PI, colour: new THREE.Color(this.planeColour(p.rank)) }));
    const v = new THREE.Vector3();
    const up = new THREE.Vector3().fromArray(this.ground ? this.ground.normal : [0, 0, 1]).normalize();
    const groundD = this.ground ? this.ground.d_mm : null;
    const rock = new THREE.Color(this.palette.rock), ground = new THREE.Color(this.palette.ground);
    this.colourCounts = this.planes.map(() => 0);
    for (let i = 0; i < n; ++i) {
      v.fromArray(this.points, i * 3);
      c.copy(groundD !== null && Math.abs(v.dot(up) + groundD) < 3 ? ground : rock);
      for (let k = 0; k < fits.length; ++k) {
        const f = fits[k];
        const d = v.clone().sub(f.o);
        const along = d.dot(f.n);
        if (Math.abs(along) < f.tol && d.lengthSq() - along * along < f.r2) { c.copy(f.colour); ++this.colourCounts[k]; break; }
      }
      colours.set([c.r, c.g, c.b], i * 3);
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(this.points, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    this.groups.cloud.add(new THREE.Points(geometry, new THREE.PointsMaterial({ size: 2, vertexColors: true })));
    const index = this.meshIndex(up);
    this.meshTriangles = index.length / 3;
    if (index.length) {
      const mesh = geometry.clone();
      mesh.setIndex(index);
      mesh.computeVertexNormals();
      this.groups.cloud.add(new THREE.Mesh(mesh, new THREE.MeshStandardMaterial({
        vertexColors: true, side: THREE.DoubleSide, roughness: 0.9, metalness: 0 })));
    }
    this.redraw();
  }

  // The surface: Delaunay triangles of the points seen along `up` (the rock
  // is a height field over the ground), without those spanning gaps.
  meshIndex(up) {
    const n = this.points.length / 3;
    if (n < 3) return [];
    const a = new THREE.Vector3(1, 0, 0);
    if (Math.abs(a.dot(up)) > 0.9) a.set(0, 1, 0);
    const e1 = a.sub(up.clone().multiplyScalar(a.dot(up))).normalize();
    const e2 = new THREE.Vector3().crossVectors(up, e1);
    const flat = new Float64Array(2 * n);
    const v = new THREE.Vector3();
    for (let i = 0; i < n; ++i) {
      v.fromArray(this.points, i * 3);
      flat[2 * i] = v.dot(e1);
      flat[2 * i + 1] = v.dot(e2);
    }
    const tri = new Delaunator(flat).triangles;
    const p = this.points;
    const len = (i, j) => Math.hypot(p[3 * i] - p[3 * j], p[3 * i + 1] - p[3 * j + 1], p[3 * i + 2] - p[3 * j + 2]);
    const longest = [];
    for (let t = 0; t < tri.length; t += 3)
      longest.push(Math.max(len(tri[t], tri[t + 1]), len(tri[t + 1], tri[t + 2]), len(tri[t + 2], tri[t])));
    const median = [...longest].sort((x, y) => x - y)[Math.floor(longest.length / 2)] || 0;
    const index = [];
    for (let t = 0; t < tri.length; t += 3)
      if (longest[t / 3] <= MAX_EDGE_OVER_MEDIAN * median) index.push(tri[t], tri[t + 1], tri[t + 2]);
    return index;
  }

  // The picked plane's target: its normal as an arrow from the centroid
  // (the grinder's axis will point the other way, into the rock).
  showPose(plane) {
    this.groups.pose.clear();
    if (!plane) return;
    const n = new THREE.Vector3().fromArray(plane.normal).normalize();
    const c = new THREE.Vector3().fromArray(plane.centroid_mm);
    this.groups.pose.add(new THREE.ArrowHelper(n, c, 90, this.planeColour(plane.rank), 18, 10));
    this.redraw();
  }
}
