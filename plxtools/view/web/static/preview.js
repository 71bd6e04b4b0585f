// plx view --web: the page. It draws the scene plx simulates, at the poses plx streams (events),
// and links it to the text: a click reveals a declaration, the editor's cursor lights an element.
'use strict';

(function () {
  const R = window.PlxRender;
  const token = new URLSearchParams(location.search).get('t') || '';
  const $ = (id) => document.getElementById(id);
  const q = (name) => `${name}?t=${encodeURIComponent(token)}`;   // relative: works behind a proxy prefix

  function post(name, body) {
    return fetch(q(name), {
      method: 'POST', headers: { 'Content-Type': 'application/json', 'X-Plx-Token': token },
      body: JSON.stringify(body || {}),
    }).then((r) => r.json()).catch((e) => ({ ok: false, error: String(e) }));
  }

  const TINT_SELECTED = [0.1, 0.45, 1.0];
  const TINT_CURSOR = [1.0, 0.85, 0.0];
  const TINT_FINDING = [0.9, 0.05, 0.05];
  const GROUP_VISUAL = 2, GROUP_COVERED = 3;

  const state = {
    scene: null, status: null, poses: [], time: 0, rtf: 1, paused: false, generation: 0,
    showCollision: false, showFrames: false, selected: null, cursor: new Set(), findingElements: new Set(),
    dirty: true, frames: 0, drawnGeneration: 0, drawnPosesTime: -1, received: {}, lastReveal: null,
    elements: [], items: [], connected: false, webgl: true, error: null,
  };

  let renderer = null;
  try {
    renderer = new R.Renderer($('view'));
  } catch (e) {
    state.webgl = false;
    state.error = String(e);
  }

  // ---------------------------------------------------------------- the scene's elements
  // every thing a click or a cursor can name: bodies, geoms, connectors, mates (key 'kind:index')
  function buildElements(scene) {
    const els = [];
    scene.bodies.forEach((b, i) => els.push({ key: `body:${i}`, kind: 'body', index: i, path: b.path, src: b.src, ranges: b.ranges }));
    scene.geoms.forEach((g, i) => els.push({ key: `geom:${i}`, kind: 'geom', index: i, path: g.path, src: g.src, ranges: g.ranges, body: g.body }));
    scene.connectors.forEach((c, i) => els.push({ key: `connector:${i}`, kind: 'connector', index: i, path: c.path, src: c.src, ranges: c.ranges, body: c.body }));
    scene.mates.forEach((m, i) => els.push({ key: `mate:${i}`, kind: 'mate', index: i, path: m.path, src: m.src, ranges: m.ranges }));
    return els;
  }
  const byKey = (key) => state.elements.find((e) => e.key === key);

  // the elements whose innermost defining block holds (file, line); several when a model is used
  // several times (a cursor in `Wheel` lights the four wheels)
  function elementsAt(file, line) {
    let best = Infinity;
    const hits = [];
    for (const e of state.elements) {
      for (const [f, a, b] of e.ranges || []) {
        if (f === file && a <= line && line <= b) {
          const len = b - a;
          if (len < best) { best = len; hits.length = 0; }
          if (len === best && !hits.includes(e)) hits.push(e);
        }
      }
    }
    return hits;
  }

  // ---------------------------------------------------------------- poses and draw items
  function bodyPose(i) {
    if (i < 0) return { pos: [0, 0, 0], rot: [1, 0, 0, 0, 1, 0, 0, 0, 1] };
    const o = 7 * i, p = state.poses;
    if (p.length < o + 7) {
      return { pos: [0, 0, 0], rot: [1, 0, 0, 0, 1, 0, 0, 0, 1] };
    }
    return { pos: [p[o], p[o + 1], p[o + 2]], rot: R.quatToMat3([p[o + 3], p[o + 4], p[o + 5], p[o + 6]]) };
  }

  function geomVisible(g) {
    if (g.group === GROUP_VISUAL) return !state.showCollision;
    if (g.group === GROUP_COVERED) return state.showCollision;
    return true;
  }

  function tintFor(keys) {
    if (keys.some((k) => state.cursor.has(k))) return TINT_CURSOR;
    if (keys.some((k) => k === state.selected)) return TINT_SELECTED;
    if (keys.some((k) => state.findingElements.has(k))) return TINT_FINDING;
    return null;
  }

  function sceneSize() {
    return state.extent || 1;
  }

  function buildItems() {
    const scene = state.scene;
    const items = [];
    if (!scene || !renderer) return items;
    scene.geoms.forEach((g, i) => {
      if (!geomVisible(g)) return;
      const [shape, scl] = renderer.shapeOf(g);
      if (!shape) return;
      const bp = bodyPose(g.body);
      const pos = R.add(bp.pos, R.mat3Apply(bp.rot, g.pos));
      const rot = R.mat3Mul(bp.rot, R.quatToMat3(g.quat));
      const keys = [`geom:${i}`].concat(g.body >= 0 ? [`body:${g.body}`] : []);
      items.push({ shape, pos, rot, scale: scl, color: g.rgba, tint: tintFor(keys), pick: g.body >= 0 ? `body:${g.body}` : `geom:${i}` });
    });
    const size = sceneSize();
    const thin = size * 0.006, len = size * 0.06;
    const shown = (key) => state.showFrames || key === state.selected || state.cursor.has(key) || state.findingElements.has(key);
    const cyl = renderer.shapes.cylinder, sph = renderer.shapes.sphere;
    const world = (c) => {
      const bp = bodyPose(c.body);
      return { p: R.add(bp.pos, R.mat3Apply(bp.rot, c.pos)), a: R.mat3Apply(bp.rot, c.axis), n: R.mat3Apply(bp.rot, c.normal) };
    };
    scene.mates.forEach((m, i) => {
      const key = `mate:${i}`;
      if (!shown(key)) return;
      const c = world(scene.connectors[m.connectors[0]]);
      const tint = tintFor([key]);
      items.push({ shape: cyl, pos: c.p, rot: R.mat3FromZ(c.a), scale: [thin * 1.6, thin * 1.6, len * 0.8], color: [0.95, 0.55, 0.1, 1], tint, overlay: true, pick: key });
    });
    scene.connectors.forEach((cn, i) => {
      const key = `connector:${i}`;
      if (!shown(key)) return;
      const c = world(cn);
      const tint = tintFor([key]);
      items.push({ shape: sph, pos: c.p, rot: [1, 0, 0, 0, 1, 0, 0, 0, 1], scale: [thin * 3, thin * 3, thin * 3], color: [0.2, 0.2, 0.25, 1], tint, overlay: true, pick: key });
      items.push({ shape: cyl, pos: R.add(c.p, R.scale(c.a, len / 2)), rot: R.mat3FromZ(c.a), scale: [thin, thin, len / 2], color: [0.15, 0.35, 0.95, 1], tint, overlay: true, pick: key });
      items.push({ shape: cyl, pos: R.add(c.p, R.scale(c.n, len / 4)), rot: R.mat3FromZ(c.n), scale: [thin * 0.8, thin * 0.8, len / 4], color: [0.1, 0.7, 0.2, 1], tint, overlay: true, pick: key });
    });
    const ids = new Map();
    items.forEach((it) => {
      if (!ids.has(it.pick)) ids.set(it.pick, ids.size);
      it.id = ids.get(it.pick);
    });
    state.pickKeys = [...ids.keys()];
    return items;
  }

  // ---------------------------------------------------------------- camera
  function fit() {
    const scene = state.scene;
    if (!scene || !renderer) return;
    const dyn = scene.geoms.filter((g) => g.body >= 0 && scene.bodies[g.body].dynamic && g.kind !== 'plane');
    const use = dyn.length ? dyn : scene.geoms.filter((g) => g.kind !== 'plane');
    let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    use.forEach((g) => {
      const bp = bodyPose(g.body);
      const c = R.add(bp.pos, R.mat3Apply(bp.rot, g.pos));
      const s = g.size;
      const r = g.kind === 'sphere' ? s[0] : g.kind === 'capsule' ? s[0] + s[1] : g.kind === 'cylinder' ? Math.hypot(s[0], s[1]) : Math.hypot(s[0], s[1], s[2]);
      lo = lo.map((v, k) => Math.min(v, c[k] - r));
      hi = hi.map((v, k) => Math.max(v, c[k] + r));
    });
    if (!use.length) { lo = [-1, -1, -1]; hi = [1, 1, 1]; }
    const centre = R.scale(R.add(lo, hi), 0.5);
    const radius = Math.max(Math.hypot(...R.sub(hi, lo)) / 2, 0.05);
    state.extent = radius * 2;
    const cam = renderer.camera;
    cam.target = centre;
    cam.distance = (1.05 * radius) / Math.tan(cam.fovy / 2);
    cam.azimuth = -2.3;
    cam.elevation = 0.42;
    state.dirty = true;
  }

  function floorGrid() {
    const scene = state.scene;
    // the top of the widest static geometry (a ground plate or plane), else the lowest point drawn
    let z = null, widest = 0;
    scene.geoms.forEach((g) => {
      const isStatic = g.body < 0 || !scene.bodies[g.body].dynamic;
      if (!isStatic) return;
      const bp = bodyPose(g.body);
      const c = R.add(bp.pos, R.mat3Apply(bp.rot, g.pos));
      const w = g.kind === 'plane' ? Infinity : g.kind === 'box' ? g.size[0] * g.size[1] : 0;
      if (w > widest) { widest = w; z = g.kind === 'plane' ? c[2] : c[2] + g.size[2]; }
    });
    if (z === null) z = 0;
    const half = Math.max(5, Math.ceil(sceneSize() * 3));
    renderer.setGrid(z + 1e-3, half, half > 40 ? 5 : 1);
  }

  // ---------------------------------------------------------------- drawing
  function frame() {
    if (renderer && state.dirty && state.scene) {
      renderer.resize();
      state.items = buildItems();
      renderer.draw(state.items, false);
      state.frames += 1;
      state.dirty = false;
      state.drawnGeneration = state.scene.generation;
      state.drawnPosesTime = state.time;
      const at = state.received[state.scene.generation];
      if (at && !at.drawn) at.drawn = performance.now();
    }
    requestAnimationFrame(frame);
  }

  // ---------------------------------------------------------------- panels
  const baseName = (f) => f.split(/[\\/]/).pop();
  function where(src) { return src ? `${baseName(src.file)}:${src.line}` : 'no source line'; }

  function showClock() {
    const s = state.scene ? state.scene.model : 'no scene';
    $('model').textContent = s;
    const run = state.paused ? 'paused' : 'running';
    const slow = !state.paused && state.rtf < 0.95 ? ` · slower than real time x${state.rtf.toFixed(2)}` : ` · real time x${state.rtf.toFixed(2)}`;
    $('clock').textContent = `t = ${state.time.toFixed(3)} s · ${run}${slow}`;
    $('play').textContent = state.paused ? 'Play' : 'Pause';
  }

  function showStatus() {
    const st = state.status;
    if (!st) return;
    document.body.classList.toggle('failed', !st.ok && !st.loading);
    const banner = $('banner');
    if (!st.ok && !st.loading) {
      banner.hidden = false;
      banner.textContent = `LOAD FAILED: ${st.error || 'the file does not load'}` + (state.scene ? ' (showing the last good scene)' : '');
    } else {
      banner.hidden = true;
    }
    const list = $('findings-list');
    list.textContent = '';
    (st.findings || []).forEach((f) => {
      const li = document.createElement('li');
      li.className = f.severity;
      li.textContent = `${f.file ? `${baseName(f.file)}:${f.line}:${f.column}: ` : ''}${f.severity} ${f.code} ${f.message}`;
      if (f.file && f.line) {
        li.title = 'reveal this line';
        li.addEventListener('click', () => reveal({ path: f.code, file: f.file, line: f.line, column: f.column }));
      }
      list.appendChild(li);
    });
    const n = (st.findings || []).length;
    $('findings').hidden = n === 0;
    $('findings-head').textContent = st.ok ? `${n} finding${n === 1 ? '' : 's'}` : `the file does not load: ${n} finding${n === 1 ? '' : 's'}`;
    // findings at a line inside a body's blocks tint that body (its geoms, its connector, its mate)
    state.findingElements = new Set();
    (st.findings || []).forEach((f) => {
      if (!f.file) return;
      elementsAt(f.file, f.line).forEach((e) => {
        state.findingElements.add(e.key);
        if (e.body !== undefined && e.body >= 0 && e.kind !== 'connector') state.findingElements.add(`body:${e.body}`);
      });
    });
    const keys = st.keys || [];
    $('keys').hidden = keys.length === 0;
    $('keys').textContent = keys.map(([name, , key]) => `${key}: ${name}`).join(' · ');
    state.boundKeys = new Set(keys.map(([, code]) => code));
    state.dirty = true;
  }

  function showSelection() {
    const box = $('selection');
    const e = state.selected ? byKey(state.selected) : null;
    if (!e) { box.hidden = true; return; }
    box.hidden = false;
    box.textContent = '';
    const head = document.createElement('div');
    head.textContent = `${e.kind} ${e.path}`;
    box.appendChild(head);
    const link = document.createElement('a');
    link.textContent = e.src ? `${e.src.file}:${e.src.line}:${e.src.column}` : 'no source line';
    link.id = 'selection-link';
    link.addEventListener('click', () => reveal({ path: e.path, ...(e.src || {}) }));
    box.appendChild(link);
    if (state.lastReveal && state.lastReveal.editor) {
      const ed = document.createElement('div');
      ed.textContent = `opened in ${state.lastReveal.editor}`;
      box.appendChild(ed);
    } else if (state.lastReveal && state.lastReveal.editorError) {
      const ed = document.createElement('div');
      ed.textContent = state.lastReveal.editorError;
      box.appendChild(ed);
    }
  }

  function reveal(info) {
    return post('api/select', info).then((r) => { state.lastReveal = r; showSelection(); return r; });
  }

  function select(key) {
    state.selected = key;
    state.dirty = true;
    const e = key ? byKey(key) : null;
    showSelection();
    if (e) return reveal({ path: e.path, ...(e.src || {}) });
    return Promise.resolve(null);
  }

  // ---------------------------------------------------------------- events from plx
  function onScene(scene) {
    const first = !state.scene || state.scene.file !== scene.file;   // another file: frame it anew
    state.scene = scene;
    state.elements = buildElements(scene);
    state.poses = scene.poses;
    state.time = scene.time;
    state.generation = scene.generation;
    state.received[scene.generation] = { at: performance.now() };
    if (renderer) renderer.setMeshes(scene.meshes);
    if (state.selected && !byKey(state.selected)) state.selected = null;
    if (first) fit();
    if (renderer) floorGrid();
    showStatus();
    showSelection();
    showClock();
    state.dirty = true;
  }

  function connect() {
    const es = new EventSource(q('events'));
    es.addEventListener('open', () => { state.connected = true; });
    es.addEventListener('error', () => { state.connected = false; });
    es.addEventListener('scene', (ev) => onScene(JSON.parse(ev.data)));
    es.addEventListener('status', (ev) => { state.status = JSON.parse(ev.data); showStatus(); });
    es.addEventListener('poses', (ev) => {
      const p = JSON.parse(ev.data);
      state.paused = p.paused;
      state.rtf = p.rtf;
      if (state.scene && p.generation === state.scene.generation) {
        state.poses = p.q;
        state.time = p.t;
        state.dirty = true;
      }
      showClock();
    });
    es.addEventListener('cursor', (ev) => {
      const c = JSON.parse(ev.data);
      state.cursor = new Set(elementsAt(c.file, c.line).map((e) => e.key));
      state.cursorAt = c;
      state.dirty = true;
    });
    return es;
  }

  // ---------------------------------------------------------------- input
  const canvas = $('view');
  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('mousedown', (e) => {
    canvas.focus();
    drag = { x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY, button: e.button, shift: e.shiftKey };
  });
  window.addEventListener('mouseup', (e) => {
    if (drag && Math.hypot(e.clientX - drag.x0, e.clientY - drag.y0) < 4 && drag.button === 0) {
      pickAt(e.clientX, e.clientY);
    }
    drag = null;
  });
  window.addEventListener('mousemove', (e) => {
    if (!drag || !renderer) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    const cam = renderer.camera;
    if (drag.button === 2 || drag.shift) {   // move the target in the view plane
      const eye = renderer.eye();
      const fwd = R.norm(R.sub(cam.target, eye));
      const right = R.norm(R.cross(fwd, [0, 0, 1]));
      const up = R.cross(right, fwd);
      const k = (cam.distance * 2 * Math.tan(cam.fovy / 2)) / canvas.clientHeight;
      cam.target = R.add(cam.target, R.add(R.scale(right, -dx * k), R.scale(up, dy * k)));
    } else {
      cam.azimuth -= dx * 0.008;
      cam.elevation = Math.max(-1.55, Math.min(1.55, cam.elevation + dy * 0.008));
    }
    state.dirty = true;
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    if (!renderer) return;
    renderer.camera.distance *= Math.exp(e.deltaY * 0.0015);
    state.dirty = true;
  }, { passive: false });

  function pickAt(x, y) {
    if (!renderer || !state.scene) return null;
    const items = buildItems();
    const id = renderer.pick(items, x, y);
    state.dirty = true;
    const key = id >= 0 ? state.pickKeys[id] : null;
    select(key);
    return key;
  }

  const GLFW = { ArrowUp: 265, ArrowDown: 264, ArrowLeft: 263, ArrowRight: 262, Enter: 257, Escape: 256, Backspace: 259,
    Tab: 258, PageUp: 266, PageDown: 267, Home: 268, End: 269, Insert: 260, Delete: 261, ' ': 32 };
  function glfwCode(e) {
    if (GLFW[e.key] !== undefined) return GLFW[e.key];
    const f = /^F([1-9]|1[0-2])$/.exec(e.key);
    if (f) return 289 + Number(f[1]);
    if (e.key.length === 1) return e.key.toUpperCase().charCodeAt(0);
    return null;
  }
  const held = new Set();
  window.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey || e.target.tagName === 'INPUT') return;
    const code = glfwCode(e);
    if (code !== null && state.boundKeys && state.boundKeys.has(code)) {   // the model's own keys come first
      e.preventDefault();
      if (!held.has(code)) { held.add(code); post('api/key', { code, down: true }); }
      return;
    }
    const k = e.key.toLowerCase();
    const act = { e: () => control('toggle'), r: () => control('reset'), 1: () => control('reload'), f5: () => control('reload'),
      g: () => toggle('collision'), c: () => toggle('frames'), ' ': fit, '.': () => control('step'),
      escape: () => select(null) }[k];
    if (act) { e.preventDefault(); act(); }
  });
  window.addEventListener('keyup', (e) => {
    const code = glfwCode(e);
    if (code !== null && held.has(code)) { held.delete(code); post('api/key', { code, down: false }); }
  });

  function control(action, extra) { return post('api/control', { action, ...(extra || {}) }); }
  function toggle(which) {
    const box = $(which);
    box.checked = !box.checked;
    box.dispatchEvent(new Event('change'));
  }
  $('play').addEventListener('click', () => control('toggle'));
  $('step').addEventListener('click', () => control('step'));
  $('reset').addEventListener('click', () => control('reset'));
  $('reload').addEventListener('click', () => control('reload'));
  $('fit').addEventListener('click', fit);
  $('collision').addEventListener('change', (e) => { state.showCollision = e.target.checked; state.dirty = true; });
  $('frames').addEventListener('change', (e) => { state.showFrames = e.target.checked; state.dirty = true; });
  window.addEventListener('resize', () => { state.dirty = true; });

  // ---------------------------------------------------------------- for tests and bench/view_web.py
  window.plxPreview = {
    state,
    elementsAt: (file, line) => elementsAt(file, line).map((e) => e.path),
    // the screen point (CSS pixels) of an element's origin: where a click selects it
    screenOf(path) {
      const e = state.elements.find((x) => x.path === path);
      if (!e || !renderer) return null;
      let p;
      if (e.kind === 'body') p = bodyPose(e.index).pos;
      else if (e.kind === 'geom') { const g = state.scene.geoms[e.index]; const bp = bodyPose(g.body); p = R.add(bp.pos, R.mat3Apply(bp.rot, g.pos)); }
      else if (e.kind === 'connector') { const c = state.scene.connectors[e.index]; const bp = bodyPose(c.body); p = R.add(bp.pos, R.mat3Apply(bp.rot, c.pos)); }
      else return null;
      return renderer.toScreen(p);
    },
    selectedPath: () => (state.selected ? byKey(state.selected).path : null),
    // look from another side (radians; the target and distance stay)
    setView(azimuth, elevation) {
      renderer.camera.azimuth = azimuth;
      renderer.camera.elevation = elevation;
      state.dirty = true;
    },
    // draw n frames now and return the milliseconds each took (the page's frame rate ceiling)
    benchDraw(n) {
      const gl = renderer.gl, px = new Uint8Array(4), azimuth = renderer.camera.azimuth;
      const t0 = performance.now();
      for (let i = 0; i < n; i++) {
        renderer.camera.azimuth += 0.01;
        renderer.draw(buildItems(), false);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);   // waits for the frame to be drawn
      }
      const ms = (performance.now() - t0) / n;
      renderer.camera.azimuth = azimuth;
      state.dirty = true;
      return ms;
    },
    control,
  };

  if (!state.webgl) {
    $('model').textContent = `cannot draw: ${state.error}`;
  }
  connect();
  requestAnimationFrame(frame);
})();
