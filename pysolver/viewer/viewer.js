// pysolver's animation page: reads the scene data (pysolver/viewer/scene.py) and plays it
// with three.js (the global THREE, vendored in pysolver/viewer/vendor). The URL fragment
// #t=<time> or #frame=<row> opens the page paused there.
(function () {
  'use strict';
  const S = JSON.parse(document.getElementById('scene-data').textContent);
  const $ = (id) => document.getElementById(id);

  function decode(b64, Type) {
    const bin = atob(b64);
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    return new Type(bytes.buffer);
  }
  const T = decode(S.t, Float64Array);
  const n = S.n, g = S.glyph, R = S.radius;
  const t0 = T[0], t1 = T[n - 1];
  const V3 = (a) => new THREE.Vector3(a[0], a[1], a[2]);

  // renderer, camera, lights ----------------------------------------------------------------
  const view = $('view');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (err) {
    $('nowebgl').style.display = 'block';
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f6f8);
  const up = V3(S.up);
  const camera = new THREE.PerspectiveCamera(35, 1, R / 2000, R * 400);
  camera.up.copy(up);
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;
  const sky = new THREE.HemisphereLight(0xffffff, 0x8090a0, 1.6);
  sky.position.copy(up);
  scene.add(sky);
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(0.4, 0.8, 1);
  camera.add(sun);
  scene.add(camera);

  function home() {
    const dist = 1.05 * R / Math.sin((camera.fov / 2) * Math.PI / 180) *
                 Math.max(1, 1 / camera.aspect);
    controls.target.set(0, 0, 0);
    camera.position.copy(V3(S.view).multiplyScalar(dist));
    camera.lookAt(0, 0, 0);
    controls.update();
  }

  // materials and small builders ------------------------------------------------------------
  const solid = (color, opacity) => new THREE.MeshStandardMaterial({
    color, roughness: 0.55, metalness: 0.1, transparent: opacity < 1, opacity,
    side: opacity < 1 ? THREE.DoubleSide : THREE.FrontSide, depthWrite: opacity >= 1 });
  const lineMat = (color) => new THREE.LineBasicMaterial({ color });
  function line(points, color, dashed) {
    const geo = new THREE.BufferGeometry().setFromPoints(points);
    const mat = dashed ? new THREE.LineDashedMaterial({ color, dashSize: g, gapSize: 0.6 * g })
                       : lineMat(color);
    const obj = new THREE.Line(geo, mat);
    if (dashed) obj.computeLineDistances();
    return obj;
  }
  function triad(len) {
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.Float32BufferAttribute(
      [0, 0, 0, len, 0, 0, 0, 0, 0, 0, len, 0, 0, 0, 0, 0, 0, len], 3));
    geo.setAttribute('color', new THREE.Float32BufferAttribute(
      [.85, .1, .1, .85, .1, .1, .1, .6, .1, .1, .6, .1, .15, .3, .9, .15, .3, .9], 3));
    return new THREE.LineSegments(geo, new THREE.LineBasicMaterial({ vertexColors: true }));
  }
  function curve(fn, count) {
    const pts = [];
    for (let k = 0; k <= count; k++) pts.push(fn(k / count));
    return pts;
  }

  // ground: a grid across up under the scene, and the global axes at the origin --------------
  const groundLayer = new THREE.Group();
  scene.add(groundLayer);
  {
    const raw = R / 4, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const cell = [1, 2, 5, 10].map((m) => m * mag).find((c) => c >= raw);
    const cells = 2 * Math.ceil(1.2 * R / cell);
    const grid = new THREE.GridHelper(cells * cell, cells, 0xaab4bf, 0xd3d9df);
    grid.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), up);
    grid.position.copy(up).multiplyScalar(S.floor);
    groundLayer.add(grid);
    const origin = V3(S.origin).negate();
    if (origin.length() < 3 * R) {
      const axes = triad(2.5 * g);
      axes.position.copy(origin);
      groundLayer.add(axes);
    }
  }

  // bodies and their markers ----------------------------------------------------------------
  const markerLayer = [], itemLayer = new THREE.Group(), frames = {}, bodies = [];
  scene.add(itemLayer);
  const spokes = {};
  for (const m of S.markers) (spokes[m.body] = spokes[m.body] || []).push(m);
  for (const b of S.bodies) {
    const group = new THREE.Group();
    scene.add(group);
    const body = { group, pos: decode(b.pos, Float32Array),
                   quat: b.quat ? decode(b.quat, Float32Array) : null };
    bodies.push(body);
    frames['body' + b.id] = group;
    if (b.glyph) {
      const ball = new THREE.Mesh(new THREE.SphereGeometry(b.kind === 'point' ? g : 0.7 * g, 32, 16),
                                  solid(b.color, 1));
      group.add(ball);
      if (b.kind === 'rigid') group.add(triad(2.2 * g));
      // a rod from the centre of mass to each of the body's markers
      for (const m of spokes[b.id] || []) {
        const len = Math.hypot(m.p[0], m.p[1], m.p[2]);
        if (len < 1e-9 * R) continue;
        const geo = new THREE.CylinderGeometry(0.18 * g, 0.18 * g, len, 12, 1, false);
        geo.translate(0, len / 2, 0);
        const rod = new THREE.Mesh(geo, solid(b.color, 1));
        rod.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), V3(m.p).divideScalar(len));
        group.add(rod);
      }
    }
  }
  // each body's path (its centre of mass over every row), faint
  const pathLayer = new THREE.Group();
  scene.add(pathLayer);
  S.bodies.forEach((b, k) => {
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.BufferAttribute(bodies[k].pos, 3));
    pathLayer.add(new THREE.Line(geo, new THREE.LineBasicMaterial({
      color: b.color, transparent: true, opacity: 0.45 })));
  });
  pathLayer.visible = S.bodies.length <= 20;
  $('show-paths').checked = pathLayer.visible;
  for (const m of S.markers) {
    const frame = new THREE.Group();
    frame.position.copy(V3(m.p));
    frame.quaternion.set(m.q[0], m.q[1], m.q[2], m.q[3]);
    (m.body ? frames['body' + m.body] : scene).add(frame);
    frames[m.id] = frame;
    const axes = triad(0.9 * g);
    frame.add(axes);
    markerLayer.push(axes);
  }

  // shapes in marker frames, links between markers, penalty planes --------------------------
  const links = [];
  const legend = {};
  function shape(it) {
    const op = it.opacity === undefined ? 1 : it.opacity;
    switch (it.kind) {
      case 'cylinder': {
        const lo = Math.min(it.z0, it.z1), hi = Math.max(it.z0, it.z1);
        const rlo = it.z0 <= it.z1 ? it.r0 : it.r1, rhi = it.z0 <= it.z1 ? it.r1 : it.r0;
        const geo = new THREE.CylinderGeometry(rhi, rlo, Math.max(hi - lo, 1e-9 * R), 40, 1, !!it.open);
        geo.rotateX(Math.PI / 2);
        geo.translate(0, 0, (lo + hi) / 2);
        return new THREE.Mesh(geo, solid(it.color, op));
      }
      case 'box': {
        const geo = new THREE.BoxGeometry(it.s[0], it.s[1], it.s[2]);
        geo.translate(it.c[0], it.c[1], it.c[2]);
        return new THREE.Mesh(geo, solid(it.color, op));
      }
      case 'sphere': {
        const mesh = new THREE.Mesh(new THREE.SphereGeometry(it.r, 40, 20), solid(it.color, op));
        mesh.scale.set(it.scale[0], it.scale[1], it.scale[2]);
        mesh.position.copy(V3(it.c));
        return mesh;
      }
      case 'arc':
        return line(curve((s) => {
          const a = it.a0 + s * (it.a1 - it.a0);
          return new THREE.Vector3(it.r * Math.cos(a), it.r * Math.sin(a), 0);
        }, 96), it.color);
      case 'square': {
        const mesh = new THREE.Mesh(new THREE.PlaneGeometry(it.s, it.s), solid(it.color, 0.35));
        mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(mesh.geometry), lineMat(it.color)));
        return mesh;
      }
      case 'helix':
        return line(curve((s) => {
          const a = 2 * Math.PI * it.turns * s;
          return new THREE.Vector3(it.r * Math.cos(a), it.r * Math.sin(a), it.z0 + s * (it.z1 - it.z0));
        }, Math.ceil(24 * it.turns)), it.color);
      case 'spiral':
        return line(curve((s) => {
          const a = 2 * Math.PI * it.turns * s, r = it.r0 + s * (it.r1 - it.r0);
          return new THREE.Vector3(r * Math.cos(a), r * Math.sin(a), 0);
        }, Math.ceil(32 * it.turns)), it.color);
      case 'axis':
        return line([new THREE.Vector3(0, 0, it.z0), new THREE.Vector3(0, 0, it.z1)], it.color);
    }
    return null;
  }
  function planeMesh(it) {
    const mesh = new THREE.Mesh(new THREE.PlaneGeometry(it.w, it.h), solid(it.color, 0.28));
    mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(mesh.geometry), lineMat(it.color)));
    const u = V3(it.u), v = V3(it.v);
    mesh.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(u, v, u.clone().cross(v)));
    mesh.position.copy(V3(it.centre));
    return mesh;
  }
  function link(it) {
    const count = it.kind === 'coil' ? Math.ceil(24 * it.turns) + 4 : it.markers.length - 1;
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * (count + 1)), 3));
    const mat = it.dashed ? new THREE.LineDashedMaterial({ color: it.color, dashSize: g, gapSize: 0.6 * g })
                          : lineMat(it.color);
    const obj = new THREE.Line(geo, mat);
    obj.frustumCulled = false;
    itemLayer.add(obj);
    links.push({ it, obj, count });
  }
  for (const it of S.items) {
    const name = it.label.split(' ')[0];
    legend[name] = it.color;
    if (it.kind === 'plane') { itemLayer.add(planeMesh(it)); continue; }
    if (it.markers) { link(it); continue; }
    const obj = shape(it);
    if (!obj) continue;
    const frame = frames[it.marker];
    // shapes of graphics belong with the body; joint and force shapes with the items layer
    if (name === 'Post_Graphic') frame.add(obj);
    else {
      const holder = new THREE.Group();
      holder.userData.frame = frame;
      holder.add(obj);
      itemLayer.add(holder);
    }
  }

  const A = new THREE.Vector3(), B = new THREE.Vector3(), D = new THREE.Vector3();
  const U = new THREE.Vector3(), W = new THREE.Vector3();
  function updateLinks() {
    for (const holder of itemLayer.children) {
      const f = holder.userData.frame;
      if (f) { f.getWorldPosition(holder.position); f.getWorldQuaternion(holder.quaternion); }
    }
    for (const { it, obj, count } of links) {
      const arr = obj.geometry.attributes.position.array;
      if (it.kind === 'coil') {
        frames[it.markers[0]].getWorldPosition(A);
        frames[it.markers[1]].getWorldPosition(B);
        D.subVectors(B, A);
        const len = D.length() || 1e-12;
        D.divideScalar(len);
        U.set(1, 0, 0);
        if (Math.abs(D.x) > 0.9) U.set(0, 1, 0);
        U.cross(D).normalize();
        W.crossVectors(D, U);
        const lead = Math.min(0.1 * len, 2 * g), body = count - 4;
        // straight leads at both ends, the coil between
        const put = (k, s, r, a) => {
          arr[3 * k] = A.x + D.x * s + r * (Math.cos(a) * U.x + Math.sin(a) * W.x);
          arr[3 * k + 1] = A.y + D.y * s + r * (Math.cos(a) * U.y + Math.sin(a) * W.y);
          arr[3 * k + 2] = A.z + D.z * s + r * (Math.cos(a) * U.z + Math.sin(a) * W.z);
        };
        put(0, 0, 0, 0);
        put(1, lead, 0, 0);
        for (let k = 0; k <= body; k++) {
          const s = k / body;
          put(k + 2, lead + s * (len - 2 * lead), it.r, 2 * Math.PI * it.turns * s);
        }
        put(count - 1, len - lead, 0, 0);
        put(count, len, 0, 0);
      } else {
        it.markers.forEach((mid, k) => {
          frames[mid].getWorldPosition(A);
          arr[3 * k] = A.x; arr[3 * k + 1] = A.y; arr[3 * k + 2] = A.z;
        });
      }
      obj.geometry.attributes.position.needsUpdate = true;
      obj.geometry.computeBoundingSphere();
      if (it.dashed) obj.computeLineDistances();
    }
  }

  // poses at a time: positions interpolated, orientations slerped between output rows ---------
  function row(t) {
    let lo = 0, hi = n - 1;
    if (t <= T[0]) return 0;
    if (t >= T[hi]) return hi;
    while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (T[mid] <= t) lo = mid; else hi = mid; }
    return lo;
  }
  function pose(t) {
    const k = row(t), k1 = Math.min(k + 1, n - 1);
    const span = T[k1] - T[k], a = span > 0 ? Math.min(Math.max((t - T[k]) / span, 0), 1) : 0;
    for (const b of bodies) {
      const p = b.pos;
      b.group.position.set(p[3 * k] + a * (p[3 * k1] - p[3 * k]),
                           p[3 * k + 1] + a * (p[3 * k1 + 1] - p[3 * k + 1]),
                           p[3 * k + 2] + a * (p[3 * k1 + 2] - p[3 * k + 2]));
      if (b.quat) {
        const q = [0, 0, 0, 1];
        THREE.Quaternion.slerpFlat(q, 0, b.quat, 4 * k, b.quat, 4 * k1, a);
        b.group.quaternion.set(q[0], q[1], q[2], q[3]).normalize();
      }
    }
    scene.updateMatrixWorld(true);
    updateLinks();
    return k;
  }

  // controls, text on screen ----------------------------------------------------------------
  const digits = Math.min(9, Math.max(2, Math.ceil(-Math.log10((t1 - t0) || 1)) + 3));
  $('title').textContent = S.title + '  (lengths in ' + S.length + ')';
  if (!S.status.success) $('status').textContent = 'the run failed: ' + S.status.message;
  const names = Object.keys(legend);
  if (names.length) {
    const box = $('legend');
    for (const name of names) {
      const sw = document.createElement('span');
      sw.className = 'sw';
      sw.style.background = legend[name];
      box.appendChild(sw);
      box.appendChild(document.createTextNode(name));
    }
  }
  const notes = S.notes;           // the rows kept when not all are, then what is not drawn
  if (notes.length) {
    $('notes').hidden = false;
    $('notes').querySelector('summary').textContent = notes.length + ' note' + (notes.length > 1 ? 's' : '');
    for (const text of notes) {
      const li = document.createElement('li');
      li.textContent = text;
      $('notes').querySelector('ul').appendChild(li);
    }
  }
  for (const e of S.events) {
    if (t1 <= t0) break;
    const tick = document.createElement('i');
    tick.style.left = (100 * (e.t - t0) / (t1 - t0)) + '%';
    tick.title = e.label + ' at t = ' + e.t;
    $('ticks').appendChild(tick);
  }

  // speeds: multiples of real time in 1-2-5 steps, real time when the run lasts 2 to 30 s,
  // else the step that plays it in ~8 s; an option's value is deck time units per second
  const speed = $('speed');
  const seconds = S.seconds || 1;
  const span = ((t1 - t0) || 1) * seconds;
  const steps = [];
  for (let e = Math.floor(Math.log10(span / 200)); e <= Math.ceil(Math.log10(span)); e++)
    for (const m of [1, 2, 5]) steps.push(m * Math.pow(10, e));
  const wanted = span / 8;
  let best = steps[0];
  for (const s of steps) if (Math.abs(Math.log(s / wanted)) < Math.abs(Math.log(best / wanted))) best = s;
  if (span >= 2 && span <= 30) best = 1;
  if (!steps.includes(best)) steps.push(best);
  for (const s of steps.sort((a, b) => a - b)) {
    const opt = document.createElement('option');
    opt.value = s / seconds;
    opt.textContent = (s === 1 ? 'real time' : parseFloat(s.toPrecision(3)) + '\u00d7');
    if (s === best) opt.selected = opt.defaultSelected = true;   // defaultSelected: the DOM says so
    speed.appendChild(opt);
  }

  const slider = $('slider');
  slider.min = t0; slider.max = t1;
  let time = t0, playing = n > 1, last = null;
  const play = $('play');
  function setPlaying(on) {
    playing = on && n > 1;
    play.innerHTML = playing ? '&#10074;&#10074;' : '&#9654;';
    last = null;
  }
  function show(t) {
    time = Math.min(Math.max(t, t0), t1);
    const k = pose(time);
    slider.value = time;
    $('clock').textContent = 't = ' + time.toFixed(digits) + ' ' + S.time +
      '   (row ' + (k + 1) + ' of ' + n + ')';
  }
  play.onclick = () => { if (!playing && time >= t1) time = t0; setPlaying(!playing); };
  slider.oninput = () => { setPlaying(false); show(parseFloat(slider.value)); };
  $('home').onclick = home;
  $('show-markers').onchange = (ev) => markerLayer.forEach((m) => { m.visible = ev.target.checked; });
  $('show-items').onchange = (ev) => { itemLayer.visible = ev.target.checked; };
  $('show-paths').onchange = (ev) => { pathLayer.visible = ev.target.checked; };
  $('show-ground').onchange = (ev) => { groundLayer.visible = ev.target.checked; };
  window.addEventListener('keydown', (ev) => {
    if (ev.target.tagName === 'SELECT') return;
    if (ev.key === ' ') { ev.preventDefault(); play.onclick(); }
    if (ev.key === 'ArrowRight' || ev.key === 'ArrowLeft') {
      setPlaying(false);
      const k = row(time) + (ev.key === 'ArrowRight' ? 1 : (T[row(time)] < time ? 0 : -1));
      show(T[Math.min(Math.max(k, 0), n - 1)]);
    }
  });

  // #t=<time> or #frame=<row>: open paused there
  const hash = new URLSearchParams(location.hash.slice(1) || location.search.slice(1));
  if (hash.has('t')) { setPlaying(false); time = parseFloat(hash.get('t')); }
  else if (hash.has('frame')) {
    setPlaying(false);
    time = T[Math.min(Math.max(parseInt(hash.get('frame'), 10), 0), n - 1)];
  } else setPlaying(playing);

  function resize() {
    const w = view.clientWidth || window.innerWidth, h = view.clientHeight || window.innerHeight;
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  window.addEventListener('resize', resize);
  resize();
  home();
  show(time);
  renderer.setAnimationLoop((now) => {
    if (playing) {
      if (last !== null) {
        let t = time + (now - last) / 1000 * parseFloat(speed.value);
        if (t > t1) t = t0 + (t - t1) % ((t1 - t0) || 1);
        show(t);
      }
      last = now;
    }
    controls.update();
    renderer.render(scene, camera);
  });
})();
