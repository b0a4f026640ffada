// simbob view: the replay page's viewer (issue #23; docs/view.md). Reads the JSON of
// <script id="simbob-data"> (the compiled scene and the trajectories, written by lib/view/page.cpp),
// builds a three.js scene of the model the way lib/render draws it, and moves the bodies through
// the samples. No network: three.js and OrbitControls are inlined before this script.
(function () {
  'use strict';

  const timings = { start: performance.now() };  // ms since navigation: bench/view_bench.py reads them
  const data = JSON.parse(document.getElementById('simbob-data').textContent);
  timings.parsed = performance.now();
  const model = data.model;
  const $ = (id) => document.getElementById(id);

  // ---- Embedded arrays: base64 of little-endian float32/float64 (typed arrays read the host's
  // order; every browser platform in use is little-endian). ----
  function bytesOf(b64) {
    const text = atob(b64);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    return bytes.buffer;
  }
  const f32 = (b64) => new Float32Array(bytesOf(b64));
  const f64 = (b64) => new Float64Array(bytesOf(b64));

  // A trajectory: times, and per body 7 floats per sample (x y z qw qx qy qz, NaN = no row),
  // positions relative to the body's origin; pose() and poseInto() give them relative to the
  // page's origin (see ORIGIN) once rebase() has been called.
  function decodeTrajectory(t) {
    const out = { bodies: t.bodies, times: f64(t.times), origins: t.origins, poses: f32(t.poses), index: new Map() };
    // Per body: its origin less the page's, in doubles (exact where both are whole metres or 0).
    out.shift = t.origins;
    out.rebase = (o) => { out.shift = t.origins.map((g) => [g[0] - o[0], g[1] - o[1], g[2] - o[2]]); };
    t.bodies.forEach((key, i) => { out.index.set(key, i); });
    out.count = out.times.length;
    // The pose of body b at sample s as [x, y z, qw, qx, qy, qz] in doubles, or null.
    out.pose = function (b, s) {
      const o = (b * out.count + s) * 7;
      const p = out.poses;
      if (s < 0 || s >= out.count || Number.isNaN(p[o])) return null;
      const g = out.shift[b];
      return [g[0] + p[o], g[1] + p[o + 1], g[2] + p[o + 2], p[o + 3], p[o + 4], p[o + 5], p[o + 6]];
    };
    // The same into obj's position and quaternion, without allocating (the frame loop's path);
    // false, and nothing changed, where the body has no row.
    out.poseInto = function (b, s, obj) {
      const o = (b * out.count + s) * 7;
      const p = out.poses;
      if (s < 0 || s >= out.count) return false;
      for (let k = 0; k < 7; ++k) if (Number.isNaN(p[o + k])) return false;
      const g = out.shift[b];
      obj.position.set(g[0] + p[o], g[1] + p[o + 1], g[2] + p[o + 2]);
      obj.quaternion.set(p[o + 4], p[o + 5], p[o + 6], p[o + 3]);
      return true;
    };
    // The last sample at or before time t (0 before the first).
    out.sampleAt = function (t) {
      let lo = 0, hi = out.count - 1;
      if (hi < 0 || t <= out.times[0]) return 0;
      while (lo < hi) {
        const mid = (lo + hi + 1) >> 1;
        if (out.times[mid] <= t + 1e-12) lo = mid; else hi = mid - 1;
      }
      return lo;
    };
    return out;
  }
  const actual = decodeTrajectory(data.actual);
  const golden = data.golden ? decodeTrajectory(data.golden) : null;
  // The page's origin: what three.js calls (0, 0, 0). WebGL and the instance matrices hold
  // float32, which keeps 0.1 mm only within about 1,000 m, so a run that goes farther is drawn
  // relative to the middle of its bodies' origins (page.cpp gives a body an origin, a whole
  // metre, only on an axis where it goes beyond 1,000 m): every position, of the run, the golden
  // run and the scene's static parts, cameras and light, is moved by -ORIGIN in doubles; the
  // read-outs and the test hook add it back. 0 for a run within 1,000 m: nothing moves.
  const ORIGIN = [0, 1, 2].map((k) => {
    const vs = actual.origins.map((g) => g[k]);
    return vs.some((v) => v !== 0) ? Math.round((Math.min(...vs) + Math.max(...vs)) / 2) : 0;
  });
  actual.rebase(ORIGIN);
  if (golden) golden.rebase(ORIGIN);
  const shiftPoint = (p) => { for (let k = 0; k < 3; ++k) p[k] -= ORIGIN[k]; };
  for (const v of model.visuals) if (v.body < 0) shiftPoint(v.pose.p);
  for (const g of model.geoms) {
    if (g.body >= 0) continue;
    shiftPoint(g.pose.p);
    if (g.shape === 'plane') g.plane[3] -= g.plane[0] * ORIGIN[0] + g.plane[1] * ORIGIN[1] + g.plane[2] * ORIGIN[2];
  }
  for (const c of model.cameras) {
    if (c.kind !== 'mounted' || c.body < 0) shiftPoint(c.pose.p);
    shiftPoint(c.target);
  }
  if (model.view.light_pos[3] !== 0) shiftPoint(model.view.light_pos);
  const absolute = (x, k) => x + ORIGIN[k];  // a drawn coordinate as the CSV has it
  const compare = data.compare || null;
  const compareErrors = new Map(compare ? Object.entries(compare.errors) : []);  // body -> its error series
  timings.decoded = performance.now();

  // ---- three.js scene: renderer, light, background, fog ----
  const view = model.view;
  const rgb = (c) => new THREE.Color(c[0], c[1], c[2]);
  // Antialiasing costs a software renderer (SwiftShader) much of its frame: off by default from
  // LARGE bodies on; #aa=0 / #aa=1 in the first URL choose. Likewise #inst=0 draws every body on
  // its own instead of instancing (for comparisons: tests/view, bench/view_bench.py).
  const LARGE = 100;
  const ANTIALIAS = /aa=1/.test(location.hash) || (!/aa=0/.test(location.hash) && actual.bodies.length < LARGE);
  const INSTANCING = !/inst=0/.test(location.hash);
  const container = $('view');
  const renderer = new THREE.WebGLRenderer({ antialias: ANTIALIAS, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  container.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = rgb(view.clear_color);
  // One light at LightPos (w = 0: a direction), as the renderer's GL_LIGHT0. Its ambient part
  // is the skins' emissive term (see materialOf), so there is no ambient light here.
  const lp = view.light_pos;
  const light = lp[3] === 0 ? new THREE.DirectionalLight(rgb(view.light_color), 1) : new THREE.PointLight(rgb(view.light_color), 1, 0, 0);
  light.position.set(lp[0], lp[1], lp[2]);
  scene.add(light);
  const sceneFog = view.fog === 'linear' ? new THREE.Fog(rgb(view.fog_color), view.fog_start, view.fog_end)
    : view.fog === 'off' ? null : new THREE.FogExp2(rgb(view.fog_color), view.fog_density);

  // ---- Materials of the skins (lib/render/renderer.cpp's drawVisual) ----
  // One image element per texture file (the page holds each once, as PNG); the meshes' textures
  // (clones with their own repeat) share it and are all updated once it has decoded.
  let pendingTextures = 0;
  const imageUsers = new Map();  // image element -> the textures drawn from it
  const images = model.textures.map((url, i) => {
    const img = new Image();
    imageUsers.set(img, []);
    pendingTextures++;
    img.onload = () => { pendingTextures--; for (const t of imageUsers.get(img)) t.needsUpdate = true; };
    img.onerror = () => { pendingTextures--; console.error('simbob view: texture ' + i + ' did not load'); };
    // Only the data: URLs page.cpp embeds: a page never fetches, nor runs, what a link names.
    if (/^data:image\/png;base64,/.test(url)) img.src = url; else img.onerror();
    return img;
  });
  const materials = model.skins.map(materialOf);
  function materialOf(s) {
    const alpha = s.color[3];
    const common = { transparent: alpha < 1, opacity: alpha, depthWrite: alpha >= 1, side: THREE.DoubleSide };
    let m;
    if (s.mode === 'color' || s.mode === 'transparent_color') {
      m = new THREE.MeshBasicMaterial(Object.assign({ color: rgb(s.color) }, common));
    } else {
      const lc = view.light_color;
      const emissive = [0, 1, 2].map((k) => Math.min(1, s.ambient[k] * lc[k] + s.emission[k]));
      m = new THREE.MeshPhongMaterial(Object.assign({
        color: rgb(s.diffuse), emissive: rgb(emissive),
        specular: s.shininess > 0 ? rgb(s.specular) : new THREE.Color(0, 0, 0),
        shininess: Math.min(s.shininess, 128),
      }, common));
    }
    if (typeof s.texture === 'number' && images[s.texture]) {
      const img = images[s.texture];
      m.map = new THREE.Texture(img);
      m.map.wrapS = m.map.wrapT = THREE.RepeatWrapping;
      imageUsers.get(img).push(m.map);
      if (img.complete && img.naturalWidth) m.map.needsUpdate = true;
      if (!s.colored) m.color = new THREE.Color(1, 1, 1);
    }
    return m;
  }

  // ---- Shapes: a model (VisualDef) or a collision shape (GeomDef) as a mesh in its owner's frame ----
  function place(obj, pose) {
    obj.position.set(pose.p[0], pose.p[1], pose.p[2]);
    obj.quaternion.set(pose.q[1], pose.q[2], pose.q[3], pose.q[0]);
    return obj;
  }
  // Meshes (model.meshes, each embedded once): one three.js geometry per mesh and part, shared
  // by every visual and collision shape that shows it; one normal per face, as lib/render draws.
  const meshGeometries = new Map();
  function meshGeometry(index, part) {
    const name = index + ':' + part;
    if (!meshGeometries.has(name)) {
      const m = (model.meshes || [])[index];
      const d = m && m[part];
      let g = new THREE.BufferGeometry();
      if (d) {
        g.setAttribute('position', new THREE.BufferAttribute(f32(d.positions), 3));
        g.setIndex(new THREE.BufferAttribute(new Uint32Array(bytesOf(d.indices)), 1));
        g = g.toNonIndexed();
        g.computeVertexNormals();
      }
      meshGeometries.set(name, g);
    }
    return meshGeometries.get(name);
  }
  function visualGeometry(v) {
    const s = v.size;
    switch (v.shape) {
      case 'mesh': return meshGeometry(v.mesh, v.hull ? 'hull' : 'triangles');
      case 'cuboid': {
        const g = new THREE.BoxBufferGeometry(Math.abs(v.b[0] - v.a[0]), Math.abs(v.b[1] - v.a[1]), Math.abs(v.b[2] - v.a[2]));
        g.translate((v.a[0] + v.b[0]) / 2, (v.a[1] + v.b[1]) / 2, (v.a[2] + v.b[2]) / 2);
        return g;
      }
      case 'plane': return new THREE.PlaneBufferGeometry(s[0], s[1]);  // XY plane, normal +Z
      case 'ellipsoid': {
        const g = new THREE.SphereBufferGeometry(1, 32, 16);
        g.scale(s[0], s[1], s[2]);
        return g;
      }
      case 'cylinder': {  // along Z, centred; open unless a flat or capped end is asked for
        const g = new THREE.CylinderBufferGeometry(s[0], s[0], s[1], 32, 1, (v.mask & 30) === 0);
        g.rotateX(Math.PI / 2);
        return g;
      }
      case 'cone': {  // base at z = 0, apex at z = Length
        const g = new THREE.ConeBufferGeometry(s[0], s[1], 32, 1, (v.mask & 1) === 0);
        g.rotateX(Math.PI / 2);
        g.translate(0, 0, s[1] / 2);
        return g;
      }
    }
    return null;
  }
  function visualMesh(v) {
    const g = visualGeometry(v);
    let m = materials[v.skin] || materials[0];
    if (v.wire || v.one_sided || m.map) {
      m = m.clone();
      if (v.wire) m.wireframe = true;
      if (v.one_sided) m.side = THREE.FrontSide;
      if (m.map) {
        // Repeats per metre, or (negative) per extension, as the renderer maps its textures.
        // TexScale is the size of one image in m, or (negative) a fraction of the extension
        // (lib/render/shapes.cpp's texCoord); three.js's UVs run 0..1 over a face.
        const ts = v.tex_scale;
        const ext = v.shape === 'plane' ? [s0(v.size[0]), s0(v.size[1])]
          : v.shape === 'cuboid' ? [s0(v.b[0] - v.a[0]), s0(v.b[1] - v.a[1])] : [1, 1];
        m.map = m.map.clone();
        imageUsers.get(m.map.image).push(m.map);
        if (m.map.image && m.map.image.complete && m.map.image.naturalWidth) m.map.needsUpdate = true;
        if (ts !== 0) m.map.repeat.set(ts > 0 ? ext[0] / ts : 1 / -ts, ts > 0 ? ext[1] / ts : 1 / -ts);
      }
    }
    return place(new THREE.Mesh(g, m), v.pose);
  }
  const s0 = (x) => Math.abs(x) || 1;
  const geomFilled = new THREE.MeshPhongMaterial({ color: new THREE.Color(0.9, 0.55, 0.2), side: THREE.DoubleSide });
  const geomStatic = new THREE.MeshPhongMaterial({ color: new THREE.Color(0.6, 0.6, 0.6), side: THREE.DoubleSide });
  const geomWire = new THREE.MeshBasicMaterial({ color: new THREE.Color(1, 0.9, 0), wireframe: true });
  function geomMesh(g, material) {
    const s = g.size;
    let geo;
    switch (g.shape) {
      case 'box': geo = new THREE.BoxBufferGeometry(s[0], s[1], s[2]); break;
      case 'hull': geo = meshGeometry(g.mesh, 'hull'); break;
      case 'trimesh': geo = meshGeometry(g.mesh, 'triangles'); break;
      case 'sphere': geo = new THREE.SphereBufferGeometry(s[0], 24, 12); break;
      case 'cylinder': geo = new THREE.CylinderBufferGeometry(s[0], s[0], s[1], 24); geo.rotateX(Math.PI / 2); break;
      case 'capsule': {  // a cylinder with a half sphere at each end, along Z
        const grp = new THREE.Group();
        const c = new THREE.CylinderBufferGeometry(s[0], s[0], s[1], 24, 1, true);
        c.rotateX(Math.PI / 2);
        grp.add(new THREE.Mesh(c, material));
        for (const z of [-s[1] / 2, s[1] / 2]) {
          const e = new THREE.Mesh(new THREE.SphereBufferGeometry(s[0], 24, 12), material);
          e.position.z = z;
          grp.add(e);
        }
        return place(grp, g.pose);
      }
      case 'plane': {  // n.p = d, shown as a square around the point nearest the origin
        const n = new THREE.Vector3(g.plane[0], g.plane[1], g.plane[2]);
        const mesh = new THREE.Mesh(new THREE.PlaneBufferGeometry(sceneSpan * 2, sceneSpan * 2, 10, 10), material);
        mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n);
        mesh.position.copy(n.multiplyScalar(g.plane[3]));
        return mesh;
      }
    }
    return place(new THREE.Mesh(geo, material), g.pose);
  }

  // ---- Bodies: one group per trajectory body, holding its models; its collision shapes in a
  // second group that moves with it. Model bodies are matched to trajectory bodies by key. ----
  // Keys are the scene's and the CSV's text: every lookup by key goes through a Map (or an object
  // without a prototype), so that 'constructor' or '__proto__' is a name like any other.
  const modelBodyIndex = new Map();
  model.bodies.forEach((b, i) => { modelBodyIndex.set(b.key, i); });
  const visualsOf = model.bodies.map(() => []);
  const geomsOf = model.bodies.map(() => []);
  const staticVisuals = [], staticGeoms = [];
  model.visuals.forEach((v) => (v.body >= 0 ? visualsOf[v.body] : staticVisuals).push(v));
  model.geoms.forEach((g) => (g.body >= 0 ? geomsOf[g.body] : staticGeoms).push(g));

  // How far the scene reaches (for planes of collision, the default view and trails).
  let sceneSpan = 10;
  for (let b = 0; b < actual.bodies.length; ++b)
    for (let s = 0; s < actual.count; s += Math.max(1, actual.count >> 6)) {
      const p = actual.pose(b, s);
      if (p) sceneSpan = Math.max(sceneSpan, Math.abs(p[0]) * 2, Math.abs(p[1]) * 2, Math.abs(p[2]) * 2);
    }

  const bodies = actual.bodies.map((key, i) => {
    const mi = modelBodyIndex.get(key);
    const group = new THREE.Group();
    group.name = key;
    group.userData.body = i;
    const geoms = new THREE.Group();
    const vis = mi === undefined ? [] : visualsOf[mi];
    const shapes = mi === undefined ? [] : geomsOf[mi];
    for (const v of vis) group.add(visualMesh(v));
    // Alone (no model on the body): filled, shown by default. Over a model: a wire frame.
    for (const g of shapes) geoms.add(geomMesh(g, vis.length ? geomWire : geomFilled));
    if (vis.length === 0 && shapes.length === 0) group.add(new THREE.AxesHelper(0.2));  // a body we know nothing of
    group.add(geoms);
    geoms.visible = vis.length === 0;
    geoms.userData.alone = vis.length === 0;
    return { key, group, geoms, model: mi, trail: null, batch: null };
  });
  const batches = INSTANCING ? makeBatches() : [];
  for (const b of bodies) if (!b.batch) scene.add(b.group);
  for (const v of staticVisuals) scene.add(visualMesh(v));
  const staticGeomGroup = new THREE.Group();
  for (const g of staticGeoms) staticGeomGroup.add(geomMesh(g, staticVisuals.length ? geomWire : geomStatic));
  staticGeomGroup.userData.alone = staticVisuals.length === 0;
  staticGeomGroup.visible = staticGeomGroup.userData.alone;
  scene.add(staticGeomGroup);

  // ---- Instancing: bodies that carry the same models and shapes (a grid of 1,000 boxes) are
  // drawn as one InstancedMesh per mesh of such a body: one draw call for all of them. Their
  // groups stay out of the scene but keep the poses (test hook, selection, follow, highlight);
  // updateInstances writes each group's matrix times the mesh's place in it into the instance
  // matrices. Transparent meshes (drawn back to front one by one) and helpers are not instanced.
  function contentKey(mi) {
    if (mi === undefined) return null;
    const strip = (o) => { const c = Object.assign({}, o); delete c.body; delete c.key; return c; };
    return JSON.stringify([visualsOf[mi].map(strip), geomsOf[mi].map(strip)]);
  }
  function makeBatches() {
    const byContent = new Map();
    bodies.forEach((b, i) => {
      const k = contentKey(b.model);
      if (k === null) return;
      if (!byContent.has(k)) byContent.set(k, []);
      byContent.get(k).push(i);
    });
    const out = [];
    for (const members of byContent.values()) {
      if (members.length < 2) continue;
      const template = bodies[members[0]].group;
      const parts = [];
      let ok = true;
      template.traverse((o) => {
        if (o === template || o.isGroup) return;
        if (!o.isMesh || Array.isArray(o.material) || o.material.transparent) { ok = false; return; }
        const local = new THREE.Matrix4();
        const chain = [];
        for (let a = o; a !== template; a = a.parent) {
          a.updateMatrix();
          local.premultiply(a.matrix);
          if (a !== o) chain.push(a);
        }
        const mesh = new THREE.InstancedMesh(o.geometry, o.material, members.length);
        mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
        mesh.frustumCulled = false;  // its bounding sphere is one instance's
        parts.push({ mesh, local, inverse: new THREE.Matrix4().getInverse(local), chain });
      });
      if (!ok || parts.length === 0) continue;
      const batch = { members, parts };
      for (const i of members) bodies[i].batch = batch;
      for (const p of parts) scene.add(p.mesh);
      out.push(batch);
    }
    return out;
  }
  const instanceMatrix = new THREE.Matrix4();
  function updateInstances() {
    for (const batch of batches) {
      for (const part of batch.parts) {
        let shown = true;
        for (const a of part.chain) shown = shown && a.visible;  // the shapes' group: switched
        part.mesh.visible = shown;
        const m = part.mesh.instanceMatrix;
        for (let k = 0; k < batch.members.length; ++k) {
          const g = bodies[batch.members[k]].group;
          if (g.visible) {
            g.updateMatrix();
            instanceMatrix.multiplyMatrices(g.matrix, part.local);
          } else {
            instanceMatrix.makeScale(0, 0, 0);  // no row at this time: not drawn
          }
          instanceMatrix.toArray(m.array, k * 16);
        }
        m.needsUpdate = true;
      }
    }
  }

  // Golden ghosts: the golden run's bodies, translucent, with the same models (or shapes).
  const ghostMaterial = new THREE.MeshBasicMaterial({ color: 0x88aaff, transparent: true, opacity: 0.35, depthWrite: false });
  const ghosts = golden ? golden.bodies.map((key, i) => {
    const mi = modelBodyIndex.get(key);
    const group = new THREE.Group();
    group.name = 'golden:' + key;
    const vis = mi === undefined ? [] : visualsOf[mi];
    const shapes = mi === undefined ? [] : geomsOf[mi];
    for (const v of vis) if (v.shape !== 'plane') group.add(visualMesh(v));
    if (vis.length === 0) for (const g of shapes) group.add(geomMesh(g, ghostMaterial));
    group.traverse((o) => { if (o.isMesh) o.material = ghostMaterial; });
    scene.add(group);
    return { key, group, index: i };
  }) : [];

  // ---- State: time, selection, camera ----
  const state = { sample: 0, time: actual.count ? actual.times[0] : 0, playing: false, speed: 1, selected: -1, camera: 'orbit' };
  const t0 = actual.count ? actual.times[0] : 0;
  const tEnd = actual.count ? actual.times[actual.count - 1] : 0;

  function setPose(obj, traj, b, s) {
    obj.visible = traj.poseInto(b, s, obj);
  }
  // Puts every body (and ghost) at the sample of time t.
  function applyTime(t) {
    state.time = Math.min(Math.max(t, t0), tEnd);
    state.sample = actual.sampleAt(state.time);
    for (let i = 0; i < bodies.length; ++i) {
      const b = bodies[i];
      setPose(b.group, actual, i, state.sample);
      if (b.trail) b.trail.geometry.setDrawRange(0, state.sample + 1);
    }
    updateInstances();
    if (golden) {
      const gs = golden.sampleAt(state.time);
      for (const g of ghosts) {
        setPose(g.group, golden, g.index, gs);
        if (!$('ghosts').checked) g.group.visible = false;
      }
    }
    $('slider').value = String(state.sample);
    $('time').textContent = 't = ' + state.time.toFixed(3) + ' s  [' + state.sample + '/' + Math.max(0, actual.count - 1) + ']';
    showSelected();
  }

  // ---- Cameras: the orbit camera, and the scene's (static, mounted, spotlight, tracking) ----
  const camera = new THREE.PerspectiveCamera(60, 1, 0.05, 5000);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  const cameraState = new Map();  // per scene camera: tracking position, spotlight's first distance
  function frameAll() {
    // The default view of the renderer: from +Z and a little above, far enough to see everything.
    const box = new THREE.Box3();
    for (const b of bodies) {
      for (let s = 0; s < actual.count; s += Math.max(1, actual.count >> 5)) {
        const p = actual.pose(b.group.userData.body, s);
        if (p) box.expandByPoint(new THREE.Vector3(p[0], p[1], p[2]));
      }
    }
    applyTime(state.time);
    for (const b of bodies) if (b.group.visible) box.expandByObject(b.group);
    if (box.isEmpty()) box.expandByPoint(new THREE.Vector3(0, 0, 0));
    const center = box.getCenter(new THREE.Vector3());
    const radius = Math.max(0.5, box.getSize(new THREE.Vector3()).length() / 2);
    const dist = radius / Math.sin(22.5 * Math.PI / 180);  // the sphere fits a 45 degree view
    const dir = new THREE.Vector3(0, 0.5, 1).normalize();
    camera.position.copy(center).addScaledVector(dir, dist);
    controls.target.copy(center);
    camera.near = Math.max(0.01, (dist - radius) * 0.5);
    camera.far = dist + radius * 4 + 100;
    camera.fov = 45;
    controls.update();
  }
  // ViewAngle is the horizontal field of view; three.js's fov is the vertical one.
  function verticalFov(hfov, aspect) {
    return 2 * Math.atan(Math.tan(hfov * Math.PI / 360) / aspect) * 180 / Math.PI;
  }
  function bodyPoseOf(modelIndex, sample = state.sample) {
    const key = modelIndex >= 0 ? model.bodies[modelIndex].key : null;
    const i = key === null ? undefined : actual.index.get(key);
    return i === undefined ? null : actual.pose(i, sample);
  }
  // Where a camera looks (its body's position at a sample, else its fixed target).
  function targetAt(c, sample) {
    const bp = bodyPoseOf(c.body, sample);
    return bp ? new THREE.Vector3(bp[0], bp[1], bp[2]) : new THREE.Vector3(c.target[0], c.target[1], c.target[2]);
  }
  // A camera that moves or remembers is where `simbob render --at T` (and a recording) puts it:
  // the renderer follows every frame of a recording at FPS from t = 0 to before T, then draws T
  // (lib/render/renderer.cpp's cameraFrame, cmd/simbob/render.cpp's Follower). So its state is a
  // function of the time shown, not of the times the page happened to draw before.
  const FPS = 30;
  function trackingPosition(c, st) {
    // Pulled like a rod of length Distance: keep the direction from the body, fix the length.
    const pull = (pos, target) => {
      const away = pos.clone().sub(target);
      const len = away.length();
      return len > 1e-12 ? target.clone().addScaledVector(away, c.distance / len) : pos.clone();
    };
    if (!st.frames) {  // after frame 0 (t = 0): Distance from the body towards +Z, a little above
      st.frames = [pull(targetAt(c, 0).addScaledVector(new THREE.Vector3(0, 0.5, 1).normalize(), c.distance), targetAt(c, 0))];
    }
    // Frames k / FPS before the time shown, each with the pose sampled at or before it.
    const due = state.time - t0 > 1e-12 ? Math.ceil((state.time - t0) * FPS - 1e-9) : 0;
    while (st.frames.length < due) {
      const k = st.frames.length;
      st.frames.push(pull(st.frames[k - 1], targetAt(c, actual.sampleAt(t0 + k / FPS))));
    }
    return due === 0 ? st.frames[0] : pull(st.frames[due - 1], targetAt(c, state.sample));
  }
  function placeSceneCamera(c, aspect) {
    if (!cameraState.has(c.key)) cameraState.set(c.key, {});
    const st = cameraState.get(c.key);
    let va = c.view_angle;
    const bp = bodyPoseOf(c.body);
    const target = bp ? new THREE.Vector3(bp[0], bp[1], bp[2]) : new THREE.Vector3(c.target[0], c.target[1], c.target[2]);
    camera.up.set(0, 1, 0);
    if (c.kind === 'static' || (c.kind === 'mounted' && !bp)) {
      place(camera, c.pose);
    } else if (c.kind === 'mounted') {
      const q = new THREE.Quaternion(bp[4], bp[5], bp[6], bp[3]);
      const local = place(new THREE.Object3D(), c.pose);
      camera.position.copy(local.position).applyQuaternion(q).add(new THREE.Vector3(bp[0], bp[1], bp[2]));
      camera.quaternion.copy(q).multiply(local.quaternion);
    } else if (c.kind === 'spotlight') {
      camera.position.set(c.pose.p[0], c.pose.p[1], c.pose.p[2]);
      const dist = camera.position.distanceTo(target);
      if (c.auto_view_angle && dist > 0) {
        // Keep the body's apparent size: the view angle it had at the first frame's distance.
        if (st.dist0 === undefined) st.dist0 = camera.position.distanceTo(targetAt(c, 0)) || dist;
        va = 2 * Math.atan(Math.tan(c.view_angle * Math.PI / 360) * st.dist0 / dist) * 180 / Math.PI;
      }
      camera.lookAt(target);
    } else {  // tracking
      camera.position.copy(trackingPosition(c, st));
      camera.lookAt(target);
    }
    camera.fov = verticalFov(va, aspect);
    camera.near = c.near;
    camera.far = c.far;
  }
  const sceneCamera = (name) => model.cameras.find((c) => c.key === name);
  function setCamera(name) {
    if (name !== 'orbit' && !sceneCamera(name)) {
      console.warn('simbob view: no camera ' + name + ' in the scene');
      name = 'orbit';
    }
    state.camera = name;
    $('camera').value = name;
    controls.enabled = name === 'orbit';
    if (name === 'orbit') frameAll();
  }

  // ---- Selection: list, highlight, pose read-out, error chart ----
  const highlight = new THREE.BoxHelper(undefined, 0xffff00);
  highlight.visible = false;
  scene.add(highlight);
  function select(i) {
    state.selected = i;
    document.querySelectorAll('#bodies li').forEach((li, k) => li.classList.toggle('selected', k === i));
    showSelected();
    drawChart();
  }
  const fmt = (x) => (x === null || Number.isNaN(x) ? 'n/a' : x.toFixed(6));
  function showSelected() {
    const i = state.selected;
    if (i < 0) { highlight.visible = false; return; }
    const b = bodies[i];
    highlight.setFromObject(b.group);
    highlight.visible = b.group.visible;
    const p = actual.pose(i, state.sample);
    let text = b.key + '\n' + (p ? 'position  ' + p.slice(0, 3).map(absolute).map(fmt).join(' ') + ' m\nrotation  ' + p.slice(3).map(fmt).join(' ') + ' (w x y z)' : 'no row at this time');
    if (compareErrors.has(b.key)) {
      const e = errorSeries(b.key);
      const k = seriesIndexAt(state.time);
      if (k >= 0) text += '\nvs golden  ' + fmt(e.pos[k]) + ' m, ' + fmt(e.rot[k]) + ' rad';
    }
    $('pose').textContent = text;
    $('pose').classList.remove('muted');
  }
  const errorCache = new Map();
  function errorSeries(key) {
    if (!errorCache.has(key)) {
      const e = compareErrors.get(key);
      errorCache.set(key, { pos: f32(e.pos), rot: f32(e.rot) });
    }
    return errorCache.get(key);
  }
  const compareTimes = compare ? f64(compare.times) : new Float64Array(0);
  function seriesIndexAt(t) {
    let k = -1;
    for (let i = 0; i < compareTimes.length && compareTimes[i] <= t + 1e-12; ++i) k = i;
    return k;
  }
  // Position (blue, m) and rotation (red, rad) error of the selected body against the golden run,
  // each scaled to its own maximum; the dashed line is the tolerance, the grey one the time shown.
  function drawChart() {
    const cv = $('chart');
    const g = cv.getContext('2d');
    g.clearRect(0, 0, cv.width, cv.height);
    if (!compare) return;
    const i = state.selected;
    const key = i >= 0 ? bodies[i].key : null;
    g.fillStyle = '#555';
    g.font = '11px sans-serif';
    if (!key || !compareErrors.has(key)) { g.fillText(key ? 'not in the golden run' : 'select a body', 8, 16); return; }
    const e = errorSeries(key);
    const n = compareTimes.length;
    if (n === 0) return;
    const ta = compareTimes[0], tb = compareTimes[n - 1] > ta ? compareTimes[n - 1] : ta + 1;
    const x = (t) => 4 + (cv.width - 8) * (t - ta) / (tb - ta);
    const plot = (series, tol, colour, label, row) => {
      let max = tol;
      for (const v of series) if (v > max) max = v;
      const y = (v) => cv.height - 4 - (cv.height - 24) * v / max;
      g.strokeStyle = colour;
      g.setLineDash([4, 3]);
      g.beginPath(); g.moveTo(4, y(tol)); g.lineTo(cv.width - 4, y(tol)); g.stroke();
      g.setLineDash([]);
      g.beginPath();
      for (let k = 0; k < n; ++k) if (!Number.isNaN(series[k])) (k ? g.lineTo : g.moveTo).call(g, x(compareTimes[k]), y(series[k]));
      g.stroke();
      g.fillStyle = colour;
      g.fillText(label + ' max ' + max.toExponential(2), 8 + row * 135, 12);
    };
    plot(e.pos, compare.tol_pos, '#1f5fd6', 'pos m', 0);
    plot(e.rot, compare.tol_rot, '#c62828', 'rot rad', 1);
    g.strokeStyle = '#888';
    g.beginPath(); g.moveTo(x(state.time), 16); g.lineTo(x(state.time), cv.height); g.stroke();
  }

  // ---- Trails: each body's path up to the time shown ----
  function setTrails(on) {
    bodies.forEach((b, i) => {
      if (on && !b.trail) {
        const pts = new Float32Array(actual.count * 3);
        let last = [0, 0, 0];
        for (let s = 0; s < actual.count; ++s) {
          const p = actual.pose(i, s);
          if (p) last = p;
          pts.set([last[0], last[1], last[2]], s * 3);
        }
        const geo = new THREE.BufferGeometry();
        geo.setAttribute('position', new THREE.BufferAttribute(pts, 3));
        b.trail = new THREE.Line(geo, new THREE.LineBasicMaterial({ color: 0x333333 }));
        scene.add(b.trail);
      }
      if (b.trail) b.trail.visible = on;
    });
    applyTime(state.time);
  }

  // ---- URL fragment: #t=2.5&camera=Chase&body=Bot.Cart.Chassis ----
  function readFragment() {
    const f = new URLSearchParams(location.hash.replace(/^#/, ''));
    if (f.has('camera')) setCamera(f.get('camera'));
    if (f.has('body')) {
      const i = actual.index.get(f.get('body'));
      if (i === undefined) console.warn('simbob view: no body ' + f.get('body') + ' in the trajectory'); else select(i);
    }
    if (f.has('t')) {
      const t = Number(f.get('t'));
      if (Number.isFinite(t)) { state.playing = false; applyTime(t); }
    }
    updatePlayButton();
  }
  function writeFragment() {
    const f = new URLSearchParams();
    f.set('t', String(state.time));
    if (state.camera !== 'orbit') f.set('camera', state.camera);
    if (state.selected >= 0) f.set('body', bodies[state.selected].key);
    if (!ANTIALIAS) f.set('aa', '0');
    history.replaceState(null, '', '#' + f.toString());
  }

  // ---- Controls of the page ----
  $('title').textContent = data.title;
  const count = (n, one, many) => n + ' ' + (n === 1 ? one : many);
  $('scene').textContent = (data.scene ? data.scene + ' \u2014 ' : '') + count(actual.bodies.length, 'body', 'bodies') + ', ' +
    count(actual.count, 'sample', 'samples');
  const camSelect = $('camera');
  camSelect.add(new Option('orbit (drag to turn)', 'orbit'));
  for (const c of model.cameras) camSelect.add(new Option(c.key + ' (' + c.kind + ')', c.key));
  camSelect.onchange = () => { setCamera(camSelect.value); writeFragment(); };
  const list = $('bodies');
  bodies.forEach((b, i) => {
    const li = document.createElement('li');
    li.textContent = b.key;
    li.onclick = () => { select(i); writeFragment(); };
    if (compare && compare.divergence && compare.divergence.body === b.key) li.classList.add('diverged');
    list.appendChild(li);
  });
  const slider = $('slider');
  slider.max = String(Math.max(0, actual.count - 1));
  slider.oninput = () => { state.playing = false; updatePlayButton(); applyTime(actual.times[Number(slider.value)]); writeFragment(); };
  const step = (d) => { state.playing = false; updatePlayButton(); const s = Math.min(Math.max(state.sample + d, 0), actual.count - 1); applyTime(actual.times[s]); writeFragment(); };
  $('back').onclick = () => step(-1);
  $('fwd').onclick = () => step(1);
  function updatePlayButton() { $('play').innerHTML = state.playing ? '&#10074;&#10074;' : '&#9654;'; }
  $('play').onclick = () => {
    if (!state.playing && state.time >= tEnd) applyTime(t0);
    state.playing = !state.playing;
    updatePlayButton();
    if (!state.playing) writeFragment();
  };
  $('speed').onchange = () => { state.speed = Number($('speed').value); };
  $('geoms').onchange = () => {
    const all = $('geoms').checked;
    for (const b of bodies) b.geoms.visible = all || b.geoms.userData.alone;
    staticGeomGroup.visible = all || staticGeomGroup.userData.alone;
    updateInstances();
  };
  $('trails').onchange = () => setTrails($('trails').checked);
  $('ghosts').onchange = () => applyTime(state.time);
  $('fog').onchange = () => { scene.fog = $('fog').checked ? sceneFog : null; };
  scene.fog = sceneFog;
  if (!golden) $('ghosts').parentNode.style.display = 'none';
  if (!compare) {
    $('comparison').style.display = 'none';
  } else {
    const d = compare.divergence;
    $('verdict').textContent = compare.pass ? 'PASS: within tolerances (' + compare.tol_pos + ' m, ' + compare.tol_rot + ' rad)'
      : d ? 'FAIL: first divergence at t = ' + d.time + ' s, ' + d.body + ' (' + d.pos_err.toExponential(3) + ' m, ' + d.rot_err.toExponential(3) + ' rad)'
        : 'FAIL: the trajectories differ in bodies, times or rows';
    if (d && actual.count > 1) {
      // On the slider: where the thumb stands at the divergence's sample.
      const frac = actual.sampleAt(d.time) / (actual.count - 1);
      const marker = $('marker');
      marker.style.display = 'block';
      marker.style.left = 'calc(' + (frac * 100) + '% + ' + (8 - 16 * frac) + 'px - 1px)';
      marker.dataset.time = String(d.time);
    }
  }
  // Clicking a body in the view selects it (the nearest mesh hit that belongs to a body).
  const ray = new THREE.Raycaster();
  let down = null;
  renderer.domElement.addEventListener('pointerdown', (ev) => { down = [ev.clientX, ev.clientY]; });
  renderer.domElement.addEventListener('pointerup', (ev) => {
    if (!down || Math.hypot(ev.clientX - down[0], ev.clientY - down[1]) > 4) return;  // a drag turns the camera
    const r = renderer.domElement.getBoundingClientRect();
    for (const b of bodies) if (b.batch) b.group.updateMatrixWorld(true);  // out of the scene
    ray.setFromCamera(new THREE.Vector2((ev.clientX - r.left) / r.width * 2 - 1, -(ev.clientY - r.top) / r.height * 2 + 1), camera);
    for (const hit of ray.intersectObjects(bodies.map((b) => b.group), true)) {
      let o = hit.object;
      while (o && o.userData.body === undefined) o = o.parent;
      if (o && o.visible) { select(o.userData.body); writeFragment(); return; }
    }
  });
  document.addEventListener('keydown', (ev) => {
    if (ev.target.tagName === 'INPUT' || ev.target.tagName === 'SELECT') return;
    if (ev.key === ' ') { $('play').onclick(); ev.preventDefault(); }
    if (ev.key === 'ArrowLeft') step(-1);
    if (ev.key === 'ArrowRight') step(1);
  });
  window.addEventListener('hashchange', readFragment);

  // ---- The frame loop ----
  let last = null;
  function resize() {
    const w = container.clientWidth, h = container.clientHeight;
    if (renderer.domElement.width !== w || renderer.domElement.height !== h) renderer.setSize(w, h, false);
    renderer.domElement.style.width = w + 'px';
    renderer.domElement.style.height = h + 'px';
    camera.aspect = w / Math.max(1, h);
  }
  const followStep = new THREE.Vector3();
  function draw() {
    resize();
    const c = sceneCamera(state.camera);
    if (c) {
      placeSceneCamera(c, camera.aspect);
    } else {
      camera.fov = 45;
      if ($('follow').checked && state.selected >= 0 && bodies[state.selected].group.visible) {
        const p = bodies[state.selected].group.position;
        camera.position.add(followStep.copy(p).sub(controls.target));
        controls.target.copy(p);
      }
      controls.update();
    }
    camera.updateProjectionMatrix();
    renderer.render(scene, camera);
  }
  function frame(now) {
    if (state.playing && last !== null) {
      let t = state.time + (now - last) / 1000 * state.speed;
      if (t > tEnd) {
        if ($('loop').checked) t = t0 + (t - tEnd) % Math.max(1e-9, tEnd - t0); else { t = tEnd; state.playing = false; updatePlayButton(); }
      }
      applyTime(t);
      frames++;
    }
    last = now;
    draw();
    requestAnimationFrame(frame);
  }
  let frames = 0;

  timings.built = performance.now();
  // The scene's first camera, as `simbob render` draws by default; else the orbit camera.
  setCamera('orbit');
  if (model.cameras.length) setCamera(model.cameras[0].key);
  applyTime(t0);
  readFragment();
  draw();
  timings.drawn = performance.now();
  requestAnimationFrame(frame);

  // ---- The test hook (tests/view/): seek, read back the poses shown, render now ----
  const posesOf = (list) => {
    const out = Object.create(null);
    for (const b of list) {
      const o = b.group;
      out[b.key] = o.visible ? [absolute(o.position.x, 0), absolute(o.position.y, 1), absolute(o.position.z, 2), o.quaternion.w, o.quaternion.x, o.quaternion.y, o.quaternion.z] : null;
    }
    return out;
  };
  // The poses the instanced meshes draw: each instanced body's matrix in its batch's first mesh,
  // back through the mesh's place in the body (float32 matrices: not bit-equal to poses()).
  const instancedPoses = () => {
    const out = Object.create(null);
    const m = new THREE.Matrix4(), p = new THREE.Vector3(), q = new THREE.Quaternion(), s = new THREE.Vector3();
    for (const b of bodies) {
      if (!b.batch) continue;
      const part = b.batch.parts[0];
      m.fromArray(part.mesh.instanceMatrix.array, b.batch.members.indexOf(b.group.userData.body) * 16).multiply(part.inverse);
      m.decompose(p, q, s);
      out[b.key] = s.x === 0 ? null : [absolute(p.x, 0), absolute(p.y, 1), absolute(p.z, 2), q.w, q.x, q.y, q.z];
    }
    return out;
  };
  window.simbobView = {
    instancedPoses,
    drawCalls: () => renderer.info.render.calls,
    // The triangles of each mesh geometry built ("MESH:triangles" or "MESH:hull" -> count).
    meshTriangles: () => Object.fromEntries([...meshGeometries].map(([k, g]) => [k, g.attributes.position ? g.attributes.position.count / 3 : 0])),
    antialias: ANTIALIAS,
    get ready() { return pendingTextures === 0; },
    seek(t) { state.playing = false; updatePlayButton(); applyTime(t); draw(); return state.time; },
    time: () => state.time,
    sample: () => state.sample,
    poses: () => posesOf(bodies),
    goldenPoses: () => posesOf(ghosts),
    camera: () => state.camera,
    setCamera(name) { setCamera(name); draw(); },
    select(key) { if (actual.index.has(key)) select(actual.index.get(key)); },
    selected: () => (state.selected >= 0 ? bodies[state.selected].key : null),
    play() { if (!state.playing) $('play').onclick(); },
    playing: () => state.playing,
    frames: () => frames,
    divergence: () => (compare ? compare.divergence : null),
    timings,
    draw,
  };
})();
