// plx view --web: a small WebGL2 renderer written for plxtools (no third-party code).
//
// Unit primitives (box, sphere, cylinder, plane; capsules built per size; meshes as given) drawn
// with a position, a rotation and a scale per item; two directional lights and an ambient term;
// an orbit camera (Z up); picking by rendering each item's id as its colour and reading one pixel.
'use strict';

(function (global) {
  // ---------------------------------------------------------------- small vector / matrix helpers
  // 3x3 matrices are arrays of 9 numbers, column-major (as WebGL takes them).
  function quatToMat3(q) {
    const [w, x, y, z] = q;
    const n = Math.hypot(w, x, y, z) || 1;
    const a = w / n, b = x / n, c = y / n, d = z / n;
    return [
      1 - 2 * (c * c + d * d), 2 * (b * c + a * d), 2 * (b * d - a * c),
      2 * (b * c - a * d), 1 - 2 * (b * b + d * d), 2 * (c * d + a * b),
      2 * (b * d + a * c), 2 * (c * d - a * b), 1 - 2 * (b * b + c * c),
    ];
  }
  function mat3Mul(a, b) {
    const o = new Array(9);
    for (let c = 0; c < 3; c++) {
      for (let r = 0; r < 3; r++) {
        o[c * 3 + r] = a[r] * b[c * 3] + a[3 + r] * b[c * 3 + 1] + a[6 + r] * b[c * 3 + 2];
      }
    }
    return o;
  }
  function mat3Apply(m, v) {
    return [m[0] * v[0] + m[3] * v[1] + m[6] * v[2], m[1] * v[0] + m[4] * v[1] + m[7] * v[2],
      m[2] * v[0] + m[5] * v[1] + m[8] * v[2]];
  }
  // the rotation taking +Z to the unit vector d
  function mat3FromZ(d) {
    const z = norm(d);
    const t = Math.abs(z[2]) < 0.9 ? [0, 0, 1] : [1, 0, 0];
    const x = norm(cross(t, z));
    const y = cross(z, x);
    return [x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2]];
  }
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  function norm(a) { const n = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / n, a[1] / n, a[2] / n]; }

  function perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0];
  }
  function lookAt(eye, target, up) {
    const z = norm(sub(eye, target));
    const x = norm(cross(up, z));
    const y = cross(z, x);
    return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
      -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
  }
  function mat4Mul(a, b) {
    const o = new Array(16);
    for (let c = 0; c < 4; c++) {
      for (let r = 0; r < 4; r++) {
        let s = 0;
        for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
        o[c * 4 + r] = s;
      }
    }
    return o;
  }
  function project(m, p) {
    const x = m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12];
    const y = m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13];
    const w = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
    return w > 0 ? [x / w, y / w] : null;
  }

  // ---------------------------------------------------------------- unit primitives
  function boxMesh() {
    const p = [], n = [], idx = [];
    const dirs = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]];
    dirs.forEach((d) => {
      const a = d[0] ? [0, 1, 0] : [1, 0, 0];
      const b = cross(d, a);
      const base = p.length / 3;
      [[-1, -1], [1, -1], [1, 1], [-1, 1]].forEach(([s, t]) => {
        p.push(d[0] + a[0] * s + b[0] * t, d[1] + a[1] * s + b[1] * t, d[2] + a[2] * s + b[2] * t);
        n.push(...d);
      });
      idx.push(base, base + 1, base + 2, base, base + 2, base + 3);
    });
    return { p, n, idx };
  }
  function sphereMesh(rings, segs) {
    const p = [], n = [], idx = [];
    for (let i = 0; i <= rings; i++) {
      const th = (Math.PI * i) / rings;
      for (let j = 0; j <= segs; j++) {
        const ph = (2 * Math.PI * j) / segs;
        const v = [Math.sin(th) * Math.cos(ph), Math.sin(th) * Math.sin(ph), Math.cos(th)];
        p.push(...v); n.push(...v);
      }
    }
    for (let i = 0; i < rings; i++) {
      for (let j = 0; j < segs; j++) {
        const a = i * (segs + 1) + j, b = a + segs + 1;
        idx.push(a, b, a + 1, a + 1, b, b + 1);
      }
    }
    return { p, n, idx };
  }
  // a cylinder of radius 1 from z = -1 to 1 (MuJoCo's: along Z, size = radius, half length), capped
  function cylinderMesh(segs) {
    const p = [], n = [], idx = [];
    for (let j = 0; j <= segs; j++) {
      const ph = (2 * Math.PI * j) / segs, c = Math.cos(ph), s = Math.sin(ph);
      p.push(c, s, -1, c, s, 1); n.push(c, s, 0, c, s, 0);
    }
    for (let j = 0; j < segs; j++) { const a = 2 * j; idx.push(a, a + 2, a + 1, a + 1, a + 2, a + 3); }
    [-1, 1].forEach((z) => {
      const centre = p.length / 3;
      p.push(0, 0, z); n.push(0, 0, z);
      for (let j = 0; j <= segs; j++) {
        const ph = (2 * Math.PI * j) / segs;
        p.push(Math.cos(ph), Math.sin(ph), z); n.push(0, 0, z);
      }
      for (let j = 0; j < segs; j++) {
        if (z > 0) idx.push(centre, centre + 1 + j, centre + 2 + j);
        else idx.push(centre, centre + 2 + j, centre + 1 + j);
      }
    });
    return { p, n, idx };
  }
  // a capsule of radius r and half length h along Z (drawn at scale 1)
  function capsuleMesh(r, h, rings, segs) {
    const p = [], n = [], idx = [];
    const half = rings / 2;
    for (let i = 0; i <= rings + 1; i++) {
      const k = i <= half ? i : i - 1;
      const th = (Math.PI * k) / rings;
      const zc = i <= half ? h : -h;
      for (let j = 0; j <= segs; j++) {
        const ph = (2 * Math.PI * j) / segs;
        const v = [Math.sin(th) * Math.cos(ph), Math.sin(th) * Math.sin(ph), Math.cos(th)];
        p.push(v[0] * r, v[1] * r, v[2] * r + zc); n.push(...v);
      }
    }
    for (let i = 0; i <= rings; i++) {
      for (let j = 0; j < segs; j++) {
        const a = i * (segs + 1) + j, b = a + segs + 1;
        idx.push(a, b, a + 1, a + 1, b, b + 1);
      }
    }
    return { p, n, idx };
  }
  function planeMesh() {
    return { p: [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0], n: [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1], idx: [0, 1, 2, 0, 2, 3] };
  }
  // a mesh as MuJoCo holds it: flat vertices and triangles; flat-shaded (each face its own normal)
  function triMesh(vert, face) {
    const p = [], n = [], idx = [];
    for (let f = 0; f < face.length; f += 3) {
      const a = [vert[3 * face[f]], vert[3 * face[f] + 1], vert[3 * face[f] + 2]];
      const b = [vert[3 * face[f + 1]], vert[3 * face[f + 1] + 1], vert[3 * face[f + 1] + 2]];
      const c = [vert[3 * face[f + 2]], vert[3 * face[f + 2] + 1], vert[3 * face[f + 2] + 2]];
      const nn = norm(cross(sub(b, a), sub(c, a)));
      const base = p.length / 3;
      p.push(...a, ...b, ...c); n.push(...nn, ...nn, ...nn);
      idx.push(base, base + 1, base + 2);
    }
    return { p, n, idx };
  }

  // ---------------------------------------------------------------- shaders
  const VS = `#version 300 es
  in vec3 aPos; in vec3 aNormal;
  uniform mat4 uViewProj; uniform vec3 uPos; uniform mat3 uRot; uniform vec3 uScale;
  out vec3 vNormal; out vec3 vWorld;
  void main() {
    vec3 w = uPos + uRot * (uScale * aPos);
    vNormal = normalize(uRot * (aNormal / uScale));
    vWorld = w;
    gl_Position = uViewProj * vec4(w, 1.0);
  }`;
  const FS = `#version 300 es
  precision highp float;
  in vec3 vNormal; in vec3 vWorld;
  uniform vec4 uColor; uniform vec3 uTint; uniform float uTintAmount; uniform int uMode; uniform vec3 uEye;
  out vec4 outColor;
  void main() {
    if (uMode == 1) { outColor = uColor; return; }   // picking: the id as a colour
    vec3 n = normalize(vNormal);
    if (dot(n, uEye - vWorld) < 0.0) n = -n;          // two-sided
    vec3 l1 = normalize(vec3(0.4, 0.3, 1.0)), head = normalize(uEye - vWorld);   // a sky light and a headlight
    float d = 0.3 + 0.35 * max(dot(n, l1), 0.0) + 0.45 * max(dot(n, head), 0.0);
    vec3 c = mix(uColor.rgb, uTint, uTintAmount) * d;
    outColor = vec4(c, uColor.a);
  }`;
  const LINE_VS = `#version 300 es
  in vec3 aPos; uniform mat4 uViewProj;
  void main() { gl_Position = uViewProj * vec4(aPos, 1.0); }`;
  const LINE_FS = `#version 300 es
  precision highp float; uniform vec4 uColor; out vec4 outColor;
  void main() { outColor = uColor; }`;

  function compile(gl, vs, fs) {
    const prog = gl.createProgram();
    [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]].forEach(([type, src]) => {
      const sh = gl.createShader(type);
      gl.shaderSource(sh, src);
      gl.compileShader(sh);
      if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(sh));
      gl.attachShader(prog, sh);
    });
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
    return prog;
  }

  // ---------------------------------------------------------------- the renderer
  // ?aa=0 in the page's URL turns multisampling off (software WebGL draws four times faster without)
  const SOFTWARE_HINT = new URLSearchParams(global.location.search).get('aa') === '0';
  class Renderer {
    constructor(canvas) {
      const gl = canvas.getContext('webgl2', { antialias: !SOFTWARE_HINT, preserveDrawingBuffer: false });
      if (!gl) throw new Error('this browser has no WebGL2');
      this.gl = gl;
      this.canvas = canvas;
      this.prog = compile(gl, VS, FS);
      this.lineProg = compile(gl, LINE_VS, LINE_FS);
      this.u = {};
      ['uViewProj', 'uPos', 'uRot', 'uScale', 'uColor', 'uTint', 'uTintAmount', 'uMode', 'uEye'].forEach((k) => {
        this.u[k] = gl.getUniformLocation(this.prog, k);
      });
      this.lu = { uViewProj: gl.getUniformLocation(this.lineProg, 'uViewProj'), uColor: gl.getUniformLocation(this.lineProg, 'uColor') };
      this.shapes = {};
      this.shapes.box = this.upload(boxMesh());
      this.shapes.sphere = this.upload(sphereMesh(16, 24));
      this.shapes.cylinder = this.upload(cylinderMesh(32));
      this.shapes.plane = this.upload(planeMesh());
      this.capsules = new Map();
      this.meshes = [];
      this.grid = null;
      this.camera = { target: [0, 0, 0], distance: 10, azimuth: -2.2, elevation: 0.45, fovy: (45 * Math.PI) / 180 };
      this.pickFbo = null;
      this.background = [0.93, 0.94, 0.96];
    }

    upload(m) {
      const gl = this.gl;
      const vao = gl.createVertexArray();
      gl.bindVertexArray(vao);
      const buf = (data, loc) => {
        const b = gl.createBuffer();
        gl.bindBuffer(gl.ARRAY_BUFFER, b);
        gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(data), gl.STATIC_DRAW);
        gl.enableVertexAttribArray(loc);
        gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
      };
      buf(m.p, gl.getAttribLocation(this.prog, 'aPos'));
      buf(m.n, gl.getAttribLocation(this.prog, 'aNormal'));
      const ib = gl.createBuffer();
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint32Array(m.idx), gl.STATIC_DRAW);
      gl.bindVertexArray(null);
      return { vao, count: m.idx.length };
    }

    capsule(r, h) {
      const key = `${r.toFixed(5)}:${h.toFixed(5)}`;
      if (!this.capsules.has(key)) this.capsules.set(key, this.upload(capsuleMesh(r, h, 16, 24)));
      return this.capsules.get(key);
    }

    setMeshes(meshes) {
      this.meshes = meshes.map((m) => this.upload(triMesh(m.vert, m.face)));
    }

    // the shape and scale that draw a geom of the page's scene
    shapeOf(g) {
      const s = g.size;
      switch (g.kind) {
        case 'box': return [this.shapes.box, [s[0], s[1], s[2]]];
        case 'sphere': return [this.shapes.sphere, [s[0], s[0], s[0]]];
        case 'ellipsoid': return [this.shapes.sphere, [s[0], s[1], s[2]]];
        case 'cylinder': return [this.shapes.cylinder, [s[0], s[0], s[1]]];
        case 'capsule': return [this.capsule(s[0], s[1]), [1, 1, 1]];
        case 'plane': return [this.shapes.plane, [s[0], s[1], 1]];
        case 'mesh': return [this.meshes[g.mesh], [1, 1, 1]];
        default: return [null, null];
      }
    }

    setGrid(z, half, step) {
      const gl = this.gl;
      const p = [];
      for (let v = -half; v <= half + 1e-9; v += step) {
        p.push(-half, v, z, half, v, z, v, -half, z, v, half, z);
      }
      if (this.grid) gl.deleteBuffer(this.grid.buf);
      const vao = gl.createVertexArray();
      gl.bindVertexArray(vao);
      const buf = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, buf);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(p), gl.STATIC_DRAW);
      const loc = gl.getAttribLocation(this.lineProg, 'aPos');
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
      gl.bindVertexArray(null);
      this.grid = { vao, buf, count: p.length / 3 };
    }

    eye() {
      const c = this.camera;
      const d = [Math.cos(c.elevation) * Math.cos(c.azimuth), Math.cos(c.elevation) * Math.sin(c.azimuth), Math.sin(c.elevation)];
      return add(c.target, scale(d, c.distance));
    }

    viewProj() {
      const c = this.camera;
      const aspect = this.canvas.width / Math.max(1, this.canvas.height);
      const near = Math.max(c.distance * 0.01, 1e-3);
      return mat4Mul(perspective(c.fovy, aspect, near, c.distance * 100 + 100), lookAt(this.eye(), c.target, [0, 0, 1]));
    }

    // the screen position (CSS pixels) of a world point, or null behind the camera
    toScreen(p) {
      const s = project(this.viewProj(), p);
      if (!s) return null;
      const r = this.canvas.getBoundingClientRect();
      return [r.left + ((s[0] + 1) / 2) * r.width, r.top + ((1 - s[1]) / 2) * r.height];
    }

    resize() {
      const dpr = global.devicePixelRatio || 1;
      const w = Math.max(1, Math.round(this.canvas.clientWidth * dpr));
      const h = Math.max(1, Math.round(this.canvas.clientHeight * dpr));
      if (this.canvas.width !== w || this.canvas.height !== h) {
        this.canvas.width = w;
        this.canvas.height = h;
      }
    }

    // items: {shape, pos, rot (mat3), scale, color [r,g,b,a], tint [r,g,b] | null, overlay, id}
    draw(items, pick) {
      const gl = this.gl;
      gl.viewport(0, 0, this.canvas.width, this.canvas.height);
      const bg = pick ? [0, 0, 0] : this.background;
      gl.clearColor(bg[0], bg[1], bg[2], 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST);
      gl.disable(gl.CULL_FACE);   // shapes are drawn two-sided (the fragment shader turns the normal)
      gl.disable(gl.BLEND);
      const vp = this.viewProj();
      if (!pick && this.grid) {
        gl.useProgram(this.lineProg);
        gl.uniformMatrix4fv(this.lu.uViewProj, false, vp);
        gl.uniform4f(this.lu.uColor, 0.45, 0.47, 0.5, 1);
        gl.bindVertexArray(this.grid.vao);
        gl.drawArrays(gl.LINES, 0, this.grid.count);
      }
      gl.useProgram(this.prog);
      gl.uniformMatrix4fv(this.u.uViewProj, false, vp);
      gl.uniform1i(this.u.uMode, pick ? 1 : 0);
      gl.uniform3fv(this.u.uEye, this.eye());
      for (const pass of [false, true]) {   // the scene, then overlays seen through it
        if (pass) gl.disable(gl.DEPTH_TEST);
        for (const it of items) {
          if (!!it.overlay !== pass || !it.shape) continue;
          if (pick) {
            const id = it.id + 1;
            gl.uniform4f(this.u.uColor, (id & 255) / 255, ((id >> 8) & 255) / 255, ((id >> 16) & 255) / 255, 1);
          } else {
            gl.uniform4f(this.u.uColor, it.color[0], it.color[1], it.color[2], 1);
            gl.uniform3fv(this.u.uTint, it.tint || [0, 0, 0]);
            gl.uniform1f(this.u.uTintAmount, it.tint ? 0.7 : 0);
          }
          gl.uniform3fv(this.u.uPos, it.pos);
          gl.uniformMatrix3fv(this.u.uRot, false, it.rot);
          gl.uniform3fv(this.u.uScale, it.scale);
          gl.bindVertexArray(it.shape.vao);
          gl.drawElements(gl.TRIANGLES, it.shape.count, gl.UNSIGNED_INT, 0);
        }
      }
      gl.bindVertexArray(null);
    }

    // the id of the item under a CSS-pixel point of the canvas, or -1
    pick(items, x, y) {
      const gl = this.gl;
      const w = this.canvas.width, h = this.canvas.height;
      if (!this.pickFbo || this.pickFbo.w !== w || this.pickFbo.h !== h) {
        const fb = gl.createFramebuffer();
        const tex = gl.createRenderbuffer();
        gl.bindRenderbuffer(gl.RENDERBUFFER, tex);
        gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, w, h);
        const depth = gl.createRenderbuffer();
        gl.bindRenderbuffer(gl.RENDERBUFFER, depth);
        gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, w, h);
        gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
        gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, tex);
        gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, depth);
        this.pickFbo = { fb, w, h };
      }
      gl.bindFramebuffer(gl.FRAMEBUFFER, this.pickFbo.fb);
      this.draw(items, true);
      const r = this.canvas.getBoundingClientRect();
      const px = Math.floor(((x - r.left) / r.width) * w), py = Math.floor((1 - (y - r.top) / r.height) * h);
      const out = new Uint8Array(4);
      gl.readPixels(px, py, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, out);
      gl.bindFramebuffer(gl.FRAMEBUFFER, null);
      return (out[0] | (out[1] << 8) | (out[2] << 16)) - 1;
    }
  }

  global.PlxRender = { Renderer, quatToMat3, mat3Mul, mat3Apply, mat3FromZ, add, sub, scale, norm, dot, cross };
})(window);
