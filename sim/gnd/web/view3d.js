// The reconstruction in 3D (three.js, served from /vendor): the point cloud
// coloured by the grind plane each point lies on, a disc per plane, and the
// planned grinder pose on the picked plane. Drag to rotate, wheel to zoom.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export const PLANE_COLOURS = ['#e6194b', '#3cb44b', '#4363d8', '#f58231', '#911eb4', '#42d4f4', '#f032e6', '#bfef45'];

export class View3D {
  constructor(el) {
    this.el = el;
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
    this.groups = { cloud: new THREE.Group(), planes: new THREE.Group(), pose: new THREE.Group() };
    for (const g of Object.values(this.groups)) this.scene.add(g);
    this.points = null;
    this.planes = [];
    this.ground = null;
    this.resetControls();
    new ResizeObserver(() => this.resize()).observe(el);
    this.resize();
    this.renderer.setAnimationLoop(() => { this.controls.update(); this.renderer.render(this.scene, this.camera); });
  }

  resetControls() {
    if (this.controls) this.controls.dispose();
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = false;
  }

  resize() {
    const w = this.el.clientWidth, h = this.el.clientHeight;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  setLabel(text) { this.label.textContent = text; }

  // Ground plane: {normal:[3], d_mm}; "up" is along its normal.
  setGround(ground) { this.ground = ground; }

  setCloud(xyz) {
    this.points = xyz;
    this.rebuildCloud();
    // Frame the cloud: look at its centre from the rig's side, ground normal up.
    const box = new THREE.Box3().setFromBufferAttribute(new THREE.BufferAttribute(xyz, 3));
    const centre = box.getCenter(new THREE.Vector3());
    const size = box.getSize(new THREE.Vector3()).length();
    if (this.ground) this.camera.up.fromArray(this.ground.normal).normalize();
    const back = new THREE.Vector3(0, 0, -1);  // towards the rig (camera looks along +z)
    this.camera.position.copy(centre).addScaledVector(back, size * 1.3)
      .addScaledVector(this.camera.up, size * 0.5);
    this.camera.near = size / 100;
    this.camera.far = size * 20;
    this.camera.updateProjectionMatrix();
    this.resetControls();
    this.controls.target.copy(centre);
    this.controls.update();
  }

  setPlanes(planes) {
    this.planes = planes;
    this.rebuildCloud();
    this.groups.planes.clear();
    for (const p of planes) {
      const radius = Math.sqrt(p.area_mm2 / Math.PI);
      const disc = new THREE.Mesh(new THREE.CircleGeometry(radius, 48),
        new THREE.MeshBasicMaterial({ color: PLANE_COLOURS[p.rank % 8], transparent: true, opacity: 0.35, side: THREE.DoubleSide }));
      disc.position.fromArray(p.centroid_mm);
      disc.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3().fromArray(p.normal).normalize());
      this.groups.planes.add(disc);
    }
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
      tol: Math.max(1.5, 3 * p.flatness_rms_mm), r2: 1.5 * p.area_mm2 / Math.PI, colour: new THREE.Color(PLANE_COLOURS[p.rank % 8]) }));
    const v = new THREE.Vector3();
    for (let i = 0; i < n; ++i) {
      v.fromArray(this.points, i * 3);
      c.setRGB(0.62, 0.62, 0.62);
      for (const f of fits) {
        const d = v.clone().sub(f.o);
        const along = d.dot(f.n);
        if (Math.abs(along) < f.tol && d.lengthSq() - along * along < f.r2) { c.copy(f.colour); break; }
      }
      colours.set([c.r, c.g, c.b], i * 3);
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(this.points, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    this.groups.cloud.add(new THREE.Points(geometry, new THREE.PointsMaterial({ size: 2, vertexColors: true })));
  }

  // The planned grinder pose on a plane: tool axis along -normal, its face on
  // the centroid, and the approach waypoint `standoff` mm out along the normal.
  showPose(plane, standoff) {
    this.groups.pose.clear();
    if (!plane) return;
    const n = new THREE.Vector3().fromArray(plane.normal).normalize();
    const c = new THREE.Vector3().fromArray(plane.centroid_mm);
    const toolLength = 60, toolRadius = 12;
    const material = new THREE.MeshStandardMaterial({ color: 0xd0d4da, metalness: 0.3, roughness: 0.5 });
    const tool = new THREE.Mesh(new THREE.CylinderGeometry(toolRadius, toolRadius, toolLength, 32), material);
    tool.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), n);
    tool.position.copy(c).addScaledVector(n, toolLength / 2);
    this.groups.pose.add(tool);
    const way = c.clone().addScaledVector(n, toolLength + standoff);
    const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([c.clone().addScaledVector(n, toolLength), way]),
      new THREE.LineDashedMaterial({ color: 0xffd479, dashSize: 6, gapSize: 4 }));
    line.computeLineDistances();
    this.groups.pose.add(line);
    const marker = new THREE.Mesh(new THREE.SphereGeometry(5, 16, 12), new THREE.MeshBasicMaterial({ color: 0xffd479 }));
    marker.position.copy(way);
    this.groups.pose.add(marker);
    this.groups.pose.add(new THREE.ArrowHelper(n, c, toolLength * 2.2, PLANE_COLOURS[plane.rank % 8]));
  }
}
