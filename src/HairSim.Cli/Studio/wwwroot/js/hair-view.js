// The 3D view: the streamed strands as lit lines, the head's colliders as a skin-coloured body, an orbit camera.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// Kajiya & Kay 1989, as the Godot addon's hair_strand.gdshader: a strand is a thin cylinder, so diffuse goes with
// sin(T, L) and the highlight with sin(T, H)^p, T the strand direction. Lights are fixed to the camera so the
// hair is lit the same way from wherever the artist looks.
const vertexShader = /* glsl */`
attribute vec3 strandDir;
attribute float along;
attribute float seed;
attribute float selected;
varying vec3 vDir;
varying vec3 vViewPos;
varying float vAlong;
varying float vSeed;
varying float vSelected;
void main() {
  vec4 mv = modelViewMatrix * vec4(position, 1.0);
  vViewPos = mv.xyz;
  vDir = mat3(modelViewMatrix) * strandDir;
  vAlong = along; vSeed = seed; vSelected = selected;
  gl_Position = projectionMatrix * mv;
}`;

const fragmentShader = /* glsl */`
uniform vec3 rootColor;
uniform vec3 tipColor;
uniform vec3 selectColor;
varying vec3 vDir;
varying vec3 vViewPos;
varying float vAlong;
varying float vSeed;
varying float vSelected;
float sinAngle(vec3 t, vec3 d) { float c = dot(t, d); return sqrt(max(0.0, 1.0 - c * c)); }
vec3 strandLight(vec3 base, vec3 t, vec3 v, vec3 l, vec3 colour) {
  vec3 h = normalize(l + v);
  float diffuse = mix(0.3, 1.0, sinAngle(t, l));
  float primary = pow(sinAngle(t, h), 80.0);
  float secondary = pow(sinAngle(normalize(t - 0.1 * v), h), 20.0);   // tinted second lobe, shifted towards the root
  return colour * (base * diffuse + 0.35 * primary + 0.2 * secondary * base * 2.0);
}
void main() {
  vec3 t = length(vDir) > 1e-8 ? normalize(vDir) : vec3(0.0, 1.0, 0.0);
  vec3 v = normalize(-vViewPos);
  vec3 base = mix(rootColor, tipColor, vAlong) * (1.0 + 0.3 * (vSeed - 0.5));
  vec3 c = 0.22 * base;
  c += strandLight(base, t, v, normalize(vec3(-0.5, 0.7, 0.6)), vec3(1.0, 0.96, 0.9));
  c += strandLight(base, t, v, normalize(vec3(0.7, 0.2, -0.6)), vec3(0.35, 0.4, 0.5));
  c = mix(c, selectColor, vSelected * 0.65);
  gl_FragColor = vec4(c, 1.0);
}`;

export class HairView {
  constructor(canvas) {
    this.canvas = canvas;
    // preserveDrawingBuffer: the page (and its browser test) can read back what is on screen.
    const params = new URLSearchParams(location.search);
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: params.get('aa') !== '0', preserveDrawingBuffer: true });   // ?aa=0: no MSAA (software WebGL)
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    this.renderer.setClearColor(0x2a2d33);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
    this.camera.position.set(0, 0.05, 0.95);
    this.controls = new OrbitControls(this.camera, canvas.parentElement);
    this.controls.target.set(0, -0.06, 0);
    this.controls.enableDamping = true;
    this.controls.minDistance = 0.1;
    this.controls.maxDistance = 20;
    this.controls.update();

    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.6));
    const key = new THREE.DirectionalLight(0xffffff, 1.8);
    key.position.set(-1, 2, 2);
    this.scene.add(key);
    const grid = new THREE.GridHelper(2, 20, 0x555555, 0x3a3a3a);
    grid.position.y = -0.45;
    this.scene.add(grid);

    this.head = new THREE.Group();
    this.scene.add(this.head);
    this.colliderGroup = new THREE.Group();   // the head's colliders (and a face), rebuilt when they change
    this.meshGroup = new THREE.Group();       // the head mesh of a mesh groom
    this.head.add(this.colliderGroup, this.meshGroup);
    this.colliderKey = '';

    this.geometry = new THREE.BufferGeometry();
    this.material = new THREE.ShaderMaterial({
      vertexShader, fragmentShader,
      uniforms: {
        rootColor: { value: new THREE.Color(0.16, 0.10, 0.06) },
        tipColor: { value: new THREE.Color(0.45, 0.32, 0.20) },
        selectColor: { value: new THREE.Color(1.0, 0.55, 0.1) },
      },
    });
    this.lines = new THREE.LineSegments(this.geometry, this.material);
    this.lines.frustumCulled = false;   // positions change every frame; the bound would have to follow them
    this.scene.add(this.lines);

    this.topology = null;
    this.topologyBuffer = null;
    this.particleCount = 0;
    // Draw one strand in this many (a preview density for slow machines); the simulation keeps them all.
    this.strandStride = Math.max(1, +(params.get('show') ?? 1) | 0);
    this.selection = new Set();
    this.resize();
    new ResizeObserver(() => this.resize()).observe(canvas.parentElement);
  }

  resize() {
    const w = this.canvas.parentElement.clientWidth, h = this.canvas.parentElement.clientHeight;
    if (w === 0 || h === 0) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  /** Puts the camera in front of, beside, behind or above the head, at the current distance. */
  setView(name) {
    const d = this.camera.position.distanceTo(this.controls.target);
    const dir = { front: [0, 0.1, 1], side: [-1, 0.1, 0], back: [0, 0.1, -1], top: [0, 1, 0.001] }[name];
    if (!dir) return;
    const v = new THREE.Vector3(...dir).normalize().multiplyScalar(d);
    this.camera.position.copy(this.controls.target).add(v);
    this.controls.update();
  }

  /** The camera as the server's StrokeCamera reads it (see CameraRequest). */
  strokeCamera() {
    this.camera.updateMatrixWorld();
    return {
      view: Array.from(this.camera.matrixWorldInverse.elements),
      projection: Array.from(this.camera.projectionMatrix.elements),
      width: this.canvas.clientWidth,
      height: this.canvas.clientHeight,
    };
  }

  /** Canvas pixel (CSS px from the top-left) of a world point. */
  project([x, y, z]) {
    this.camera.updateMatrixWorld();
    const v = new THREE.Vector3(x, y, z).project(this.camera);
    return [(v.x + 1) / 2 * this.canvas.clientWidth, (1 - v.y) / 2 * this.canvas.clientHeight];
  }

  /** Topology (binary "HST1"): which particles make which strand, and how many are live. */
  setTopology(buffer) {
    this.topologyBuffer = buffer;
    const dv = new DataView(buffer);
    if (dv.getUint32(0, true) !== 0x31545348) throw new Error('not a topology message');
    const revision = dv.getInt32(4, true), strands = dv.getInt32(8, true), particles = dv.getInt32(12, true);
    const first = new Int32Array(strands), live = new Int32Array(strands), capacity = new Int32Array(strands);
    let segments = 0;
    for (let s = 0; s < strands; s++) {
      const o = 16 + 16 * s;
      first[s] = dv.getInt32(o, true); live[s] = dv.getInt32(o + 4, true); capacity[s] = dv.getInt32(o + 8, true);
      if (s % this.strandStride === 0) segments += Math.max(0, live[s] - 1);
    }
    const index = new Uint32Array(2 * segments);
    const along = new Float32Array(particles), seed = new Float32Array(particles);
    let n = 0;
    for (let s = 0; s < strands; s++) {
      const r = fract(Math.sin(s * 12.9898) * 43758.5453);
      for (let k = 0; k < capacity[s]; k++) {
        along[first[s] + k] = k / Math.max(1, capacity[s] - 1);
        seed[first[s] + k] = r;
      }
      if (s % this.strandStride !== 0) continue;
      for (let k = 0; k + 1 < live[s]; k++) { index[n++] = first[s] + k; index[n++] = first[s] + k + 1; }
    }
    if (particles !== this.particleCount) {
      this.particleCount = particles;
      this.geometry.dispose();
      this.geometry = new THREE.BufferGeometry();
      this.positions = new Float32Array(3 * particles);
      this.directions = new Float32Array(3 * particles);
      this.selectedAttr = new Float32Array(particles);
      this.geometry.setAttribute('position', new THREE.BufferAttribute(this.positions, 3).setUsage(THREE.DynamicDrawUsage));
      this.geometry.setAttribute('strandDir', new THREE.BufferAttribute(this.directions, 3).setUsage(THREE.DynamicDrawUsage));
      this.geometry.setAttribute('selected', new THREE.BufferAttribute(this.selectedAttr, 1).setUsage(THREE.DynamicDrawUsage));
      this.lines.geometry = this.geometry;
    }
    this.geometry.setAttribute('along', new THREE.BufferAttribute(along, 1));
    this.geometry.setAttribute('seed', new THREE.BufferAttribute(seed, 1));
    this.geometry.setIndex(new THREE.BufferAttribute(index, 1));
    this.topology = { revision, strands, particles, first, live, capacity, segments };
    this.applySelection();
  }

  /** Draw every strand (1) or one in 2, 4, 8 … */
  setStrandStride(stride) {
    this.strandStride = Math.max(1, stride | 0);
    if (this.topologyBuffer) this.setTopology(this.topologyBuffer);
  }

  /** A frame (binary "HSF1"): quantised positions and the head pose. Returns its header. */
  setFrame(buffer) {
    const dv = new DataView(buffer);
    if (dv.getUint32(0, true) !== 0x31465348) throw new Error('not a frame message');
    const header = {
      frame: dv.getUint32(4, true), revision: dv.getInt32(8, true), particles: dv.getInt32(12, true),
      stepMs: dv.getFloat32(60, true),
    };
    const topo = this.topology;
    if (!topo || topo.revision !== header.revision || topo.particles !== header.particles) return header;
    const ox = dv.getFloat32(16, true), oy = dv.getFloat32(20, true), oz = dv.getFloat32(24, true), q = dv.getFloat32(28, true);
    const data = new Int16Array(buffer, 64, 3 * header.particles);
    const p = this.positions, d = this.directions;
    for (let i = 0, n = 3 * header.particles; i < n; i += 3) {
      p[i] = ox + q * data[i]; p[i + 1] = oy + q * data[i + 1]; p[i + 2] = oz + q * data[i + 2];
    }
    // Strand directions for the lighting: forward differences, the tip takes its segment's.
    for (let s = 0; s < topo.strands; s++) {
      const a = 3 * topo.first[s], n = topo.live[s];
      for (let k = 0; k < n; k++) {
        const i = a + 3 * k, j = k + 1 < n ? i + 3 : i, h = k + 1 < n ? i : i - 3;
        d[i] = p[j] - p[h]; d[i + 1] = p[j + 1] - p[h + 1]; d[i + 2] = p[j + 2] - p[h + 2];
      }
    }
    this.geometry.attributes.position.needsUpdate = true;
    this.geometry.attributes.strandDir.needsUpdate = true;
    this.head.position.set(dv.getFloat32(32, true), dv.getFloat32(36, true), dv.getFloat32(40, true));
    this.head.quaternion.set(dv.getFloat32(44, true), dv.getFloat32(48, true), dv.getFloat32(52, true), dv.getFloat32(56, true));
    return header;
  }

  setSelection(strands) {
    this.selection = new Set(strands);
    this.applySelection();
  }

  applySelection() {
    const topo = this.topology;
    if (!topo || !this.selectedAttr) return;
    this.selectedAttr.fill(0);
    for (const s of this.selection)
      if (s < topo.strands) this.selectedAttr.fill(1, topo.first[s], topo.first[s] + topo.capacity[s]);
    this.geometry.attributes.selected.needsUpdate = true;
  }

  /** The head's colliders (head space) as a body; the face is decoration so the front is obvious. */
  setColliders(colliders) {
    const key = JSON.stringify(colliders);
    if (key === this.colliderKey) return;
    this.colliderKey = key;
    for (const child of [...this.colliderGroup.children]) { this.colliderGroup.remove(child); child.geometry?.dispose(); }
    const skin = new THREE.MeshStandardMaterial({ color: 0xd9ad8f, roughness: 0.75 });
    for (const c of colliders) {
      let mesh;
      if (c.kind === 'Capsule') {
        const a = new THREE.Vector3(...c.center), b = new THREE.Vector3(...c.end);
        mesh = new THREE.Mesh(new THREE.CapsuleGeometry(c.radii[0], a.distanceTo(b), 8, 24), skin);
        mesh.position.copy(a).add(b).multiplyScalar(0.5);
        mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), b.clone().sub(a).normalize());
      } else if (c.kind === 'Plane') {
        // A 1 m square of the plane (its end is the normal), seen from both sides.
        const floor = new THREE.MeshStandardMaterial({ color: 0x8f9aa6, roughness: 0.9, transparent: true, opacity: 0.5, side: THREE.DoubleSide });
        mesh = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), floor);
        mesh.position.set(...c.center);
        mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3(...c.end).normalize());
      } else {
        mesh = new THREE.Mesh(new THREE.SphereGeometry(1, 48, 32), skin);
        mesh.position.set(...c.center);
        mesh.scale.set(...(c.kind === 'Sphere' ? [c.radii[0], c.radii[0], c.radii[0]] : c.radii));
        mesh.quaternion.set(...c.rotation);
      }
      this.colliderGroup.add(mesh);
    }
    const head = colliders.find(c => c.kind === 'Ellipsoid');
    if (head) this.addFace(head);
  }

  addFace(e) {
    const [rx, ry, rz] = e.radii, [cx, cy, cz] = e.center;
    const onFront = (x, y) => [cx + x, cy + y, cz + rz * Math.sqrt(Math.max(0, 1 - (x / rx) ** 2 - (y / ry) ** 2))];
    const dark = new THREE.MeshStandardMaterial({ color: 0x2b1d16, roughness: 0.4 });
    for (const side of [-1, 1]) {
      const eye = new THREE.Mesh(new THREE.SphereGeometry(0.007, 16, 12), dark);
      eye.position.set(...onFront(side * 0.3 * rx, 0.05 * ry));
      this.colliderGroup.add(eye);
    }
    const nose = new THREE.Mesh(new THREE.ConeGeometry(0.009, 0.025, 16), new THREE.MeshStandardMaterial({ color: 0xcf9f82, roughness: 0.8 }));
    nose.position.set(...onFront(0, -0.2 * ry));
    nose.rotation.x = Math.PI / 2;
    this.colliderGroup.add(nose);
  }

  /** The head mesh (binary "HSM1", head space) of a mesh groom, or null to remove it. */
  setHeadMesh(buffer) {
    for (const child of [...this.meshGroup.children]) { this.meshGroup.remove(child); child.geometry?.dispose(); }
    this.headMesh = null;
    if (!buffer) return;
    const dv = new DataView(buffer);
    if (dv.getUint32(0, true) !== 0x314D5348) throw new Error('not a mesh message');
    const nv = dv.getInt32(4, true), nt = dv.getInt32(8, true);
    const indexed = new THREE.BufferGeometry();
    indexed.setAttribute('position', new THREE.BufferAttribute(new Float32Array(buffer.slice(12, 12 + 12 * nv)), 3));
    indexed.setIndex(new THREE.BufferAttribute(new Uint32Array(buffer.slice(12 + 12 * nv, 12 + 12 * nv + 12 * nt)), 1));
    indexed.computeVertexNormals();
    // Three vertices of its own per triangle (smooth normals kept), so each triangle can show its own scalp colour.
    const geometry = indexed.toNonIndexed();
    indexed.dispose();
    geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(9 * nt), 3));
    this.headMesh = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color: 0xffffff, vertexColors: true, roughness: 0.75 }));
    this.meshTriangles = nt;
    this.meshGroup.add(this.headMesh);
    this.applyScalp();
  }

  /** The painted scalp (binary "HSS1": a byte per triangle of the head mesh), or null. Returns its revision. */
  setScalpMask(buffer) {
    if (!buffer) { this.scalpMask = null; this.applyScalp(); return null; }
    const dv = new DataView(buffer);
    if (dv.getUint32(0, true) !== 0x31535348) throw new Error('not a scalp message');
    const revision = dv.getInt32(4, true), n = dv.getInt32(8, true);
    this.scalpMask = new Uint8Array(buffer, 12, n);
    this.applyScalp();
    return revision;
  }

  /** While painting the scalp: the painted triangles coloured on the head mesh, and the hair hidden if asked. */
  setPainting(on, hideHair) {
    this.painting = on;
    this.lines.visible = !(on && hideHair);
    this.applyScalp();
  }

  /** How many painted triangles the head mesh shows in the scalp colour (for the tests). */
  scalpShown() {
    if (!this.painting || !this.scalpMask || this.scalpMask.length !== this.meshTriangles) return 0;
    return this.scalpMask.reduce((n, b) => n + b, 0);
  }

  applyScalp() {
    if (!this.headMesh) return;
    const skin = new THREE.Color(0xd9ad8f), scalp = new THREE.Color(0xc8402e);
    const attr = this.headMesh.geometry.attributes.color, c = attr.array;
    const mask = this.painting && this.scalpMask?.length === this.meshTriangles ? this.scalpMask : null;
    for (let t = 0; t < this.meshTriangles; t++) {
      const k = mask && mask[t] ? scalp : skin;
      for (let v = 9 * t; v < 9 * t + 9; v += 3) { c[v] = k.r; c[v + 1] = k.g; c[v + 2] = k.b; }
    }
    attr.needsUpdate = true;
  }

  /** The strands' roots (first particles) as last drawn, world space. */
  roots() {
    const topo = this.topology;
    if (!topo) return [];
    const p = this.positions, out = [];
    for (let s = 0; s < topo.strands; s++) { const i = 3 * topo.first[s]; out.push([p[i], p[i + 1], p[i + 2]]); }
    return out;
  }

  render() {
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }

  /** Share of the canvas's pixels that differ from the background, and how many distinct colours it has. */
  pixelStats() {
    const gl = this.renderer.getContext();
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const px = new Uint8Array(4 * w * h);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const bg = [px[0], px[1], px[2]];
    let differ = 0;
    const colours = new Set();
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - bg[0]) + Math.abs(px[i + 1] - bg[1]) + Math.abs(px[i + 2] - bg[2]) > 12) differ++;
      if (colours.size < 5000) colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
    }
    return { width: w, height: h, differing: differ / (w * h), colours: colours.size };
  }
}

function fract(x) { return x - Math.floor(x); }
