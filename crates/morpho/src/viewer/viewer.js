"use strict";
// morpho viewer: a small WebGL 2 renderer for the scene embedded in this page (no network).
(function () {
  const errors = [];
  const oe = console.error;
  console.error = function (...a) { errors.push(a.join(" ")); oe.apply(console, a); };
  window.addEventListener("error", (e) => errors.push(String(e.message)));
  const scene = JSON.parse(document.getElementById("morpho-scene").textContent);
  function blob(id) {
    const s = document.getElementById("b" + id).textContent.trim();
    if (Uint8Array.fromBase64) return Uint8Array.fromBase64(s);
    const b = atob(s), u = new Uint8Array(b.length);
    for (let i = 0; i < b.length; i++) u[i] = b.charCodeAt(i);
    return u;
  }
  const canvas = document.getElementById("c");
  // the drawing buffer: full size at rest; while the camera moves, the proxies are drawn at
  // MOVING_SCALE of it (the CSS size stays, the browser scales the picture up): with software
  // GL the pixel count costs as much as the triangles
  const W = window.innerWidth, H = window.innerHeight, MOVING_SCALE = 0.5;
  canvas.width = W; canvas.height = H;
  function resolution(scale) {
    const w = Math.max(1, Math.round(W * scale)), h = Math.max(1, Math.round(H * scale));
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  }
  const gl = canvas.getContext("webgl2", { antialias: false });
  if (!gl) {
    errors.push("WebGL 2 is not available");
    document.getElementById("morpho-selftest").textContent = JSON.stringify({ errors });
    window.morphoSelftest = Promise.resolve({ errors });
    return;
  }
  function prog(vs, fs) {
    const p = gl.createProgram();
    for (const [t, s] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
      const sh = gl.createShader(t); gl.shaderSource(sh, s); gl.compileShader(sh);
      if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) errors.push(gl.getShaderInfoLog(sh));
      gl.attachShader(p, sh);
    }
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) errors.push(gl.getProgramInfoLog(p));
    return p;
  }
  const P = prog(SHADERS.vert, SHADERS.frag);
  const SP = prog(SHADERS.svert, SHADERS.sfrag);
  const U = {};
  for (const n of ["uMVP", "uOff", "uScl", "uEye", "uColor", "uMode", "uRange", "uLit", "uPS"]) U[n] = gl.getUniformLocation(P, n);
  // colour map: blue - white - red for signed values, viridis-like ramp otherwise
  function cmap(t, signed) {
    if (signed) return t < 0.5 ? [2 * t, 2 * t, 1] : [1, 2 - 2 * t, 2 - 2 * t];
    return [0.27 + t * 0.72, 0.0 + t * 0.9, 0.33 + (t < 0.5 ? t * 0.4 : 0.53 - (t - 0.5) * 0.9)];
  }
  // vertex normals (area-weighted) packed as normalized bytes
  function normals(pos, idx, n) {
    const acc = new Float32Array(3 * n);
    for (let t = 0; t < idx.length; t += 3) {
      const a = 3 * idx[t], b = 3 * idx[t + 1], c = 3 * idx[t + 2];
      const ux = pos[b] - pos[a], uy = pos[b + 1] - pos[a + 1], uz = pos[b + 2] - pos[a + 2];
      const vx = pos[c] - pos[a], vy = pos[c + 1] - pos[a + 1], vz = pos[c + 2] - pos[a + 2];
      const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      acc[a] += nx; acc[a + 1] += ny; acc[a + 2] += nz;
      acc[b] += nx; acc[b + 1] += ny; acc[b + 2] += nz;
      acc[c] += nx; acc[c + 1] += ny; acc[c + 2] += nz;
    }
    const out = new Int8Array(4 * n);
    for (let i = 0; i < n; i++) {
      const x = acc[3 * i], y = acc[3 * i + 1], z = acc[3 * i + 2], l = Math.hypot(x, y, z) || 1;
      out[4 * i] = Math.round(127 * x / l); out[4 * i + 1] = Math.round(127 * y / l); out[4 * i + 2] = Math.round(127 * z / l);
    }
    return out;
  }
  // one drawable: quantized positions, indices (u16 or u32), vertex values of the first property
  function geometry(L, q, idx, vals, mesh) {
    const n = q.length / 3, pos = new Float32Array(3 * n);
    for (let i = 0; i < 3 * n; i += 3) for (let k = 0; k < 3; k++) pos[i + k] = L.min[k] + q[i + k] / 65535 * L.ext[k];
    let nrm;
    if (mesh) nrm = normals(pos, idx, n); else { nrm = new Int8Array(4 * n); nrm.fill(127); }
    const vao = gl.createVertexArray(); gl.bindVertexArray(vao);
    const buf = (data, loc, size, type, norm, stride) => { const b = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, b); gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW); gl.enableVertexAttribArray(loc); gl.vertexAttribPointer(loc, size, type, norm, stride || 0, 0); return b; };
    buf(q, 0, 3, gl.UNSIGNED_SHORT, true);
    buf(nrm, 1, 3, gl.BYTE, true, 4);
    const vbuf = buf(vals || new Float32Array(n), 2, 1, gl.FLOAT, false);
    let nidx = 0, itype = gl.UNSIGNED_INT;
    if (idx) { const b = gl.createBuffer(); gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, b); gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, idx, gl.STATIC_DRAW); nidx = idx.length; itype = idx instanceof Uint16Array ? gl.UNSIGNED_SHORT : gl.UNSIGNED_INT; }
    gl.bindVertexArray(null);
    return { pos, idx, vao, vbuf, nidx, itype, n };
  }
  const layers = [];
  let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const L of scene.layers) {
    const q = new Uint16Array(blob(L.pos).buffer);
    for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], L.min[k]); hi[k] = Math.max(hi[k], L.min[k] + L.ext[k]); }
    if (L.kind === "volume") {
      // a volume: three movable slices (slices.js)
      const vol = morphoVolume(gl, L.volume, blob(L.volume.data), scene.cmaps, SP);
      layers.push({ L, vol, pos: null, idx: null, props: [], full: null, proxy: null, n: 0, prop: -1, visible: !L.hidden });
      continue;
    }
    const idx = L.idx !== undefined ? new Uint32Array(blob(L.idx).buffer) : null;
    const props = (L.props || []).map((p) => ({ name: p.name, min: p.min, max: p.max, v: new Float32Array(blob(p.blob).buffer) }));
    const full = geometry(L, q, idx, props.length ? props[0].v : null, L.kind === "mesh");
    let proxy = null;
    if (L.lod) {
      const pi = L.lod.wide ? new Uint32Array(blob(L.lod.idx).buffer) : new Uint16Array(blob(L.lod.idx).buffer);
      const pv = L.lod.props.map((b) => new Float32Array(blob(b).buffer));
      proxy = geometry(L, new Uint16Array(blob(L.lod.pos).buffer), pi, pv.length ? pv[0] : null, true);
      proxy.vals = pv;
    }
    layers.push({ L, pos: full.pos, idx, props, full, proxy, n: full.n, prop: props.length ? 0 : -1, visible: !L.hidden });
  }
  const cam = { az: 0.5, el: 0.35, dist: 1, target: [0, 0, 0] };
  const diag = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
  cam.target = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2); cam.dist = 1.6 * diag;
  if (scene.flat) cam.el = Math.PI / 2 - 1e-3;
  function eye() { const c = Math.cos(cam.el); return [0, 1, 2].map((k) => cam.target[k] + cam.dist * [c * Math.cos(cam.az), c * Math.sin(cam.az), Math.sin(cam.el)][k]); }
  function mvp() {
    const e = eye(), f = [0, 1, 2].map((k) => (cam.target[k] - e[k]) / cam.dist);
    const up = [-Math.sin(cam.el) * Math.cos(cam.az), -Math.sin(cam.el) * Math.sin(cam.az), Math.cos(cam.el)];
    const r = [f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]];
    const a = W / H, th = 1 / Math.tan(0.35), near = cam.dist * 0.01, far = cam.dist + 2 * diag;
    const V = [r, up, [-f[0], -f[1], -f[2]]], t = V.map((row) => -(row[0] * e[0] + row[1] * e[1] + row[2] * e[2]));
    const Pm = [th / a, th, -(far + near) / (far - near), -2 * far * near / (far - near)];
    const M = new Float32Array(16);
    for (let c = 0; c < 4; c++) {
      const col = c < 3 ? [V[0][c], V[1][c], V[2][c]] : t;
      M[4 * c] = Pm[0] * col[0]; M[4 * c + 1] = Pm[1] * col[1]; M[4 * c + 2] = Pm[2] * col[2] + (c === 3 ? Pm[3] : 0); M[4 * c + 3] = -col[2];
    }
    return { M, e, r, up, f };
  }
  let lastM = null;
  function setup(m, w, h) {
    lastM = m.M;
    gl.viewport(0, 0, w, h);
    gl.clearColor(0.96, 0.96, 0.96, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST); gl.useProgram(P);
    gl.uniformMatrix4fv(U.uMVP, false, m.M); gl.uniform3fv(U.uEye, m.e); gl.uniform1f(U.uPS, 4 * w / W);
  }
  // draws triangles [t0, t1) of the layer's geometry g (all of a non-mesh layer)
  function drawLayer(l, g, t0, t1) {
    if (l.vol) { l.vol.draw(lastM); gl.useProgram(P); return; }
    gl.bindVertexArray(g.vao);
    gl.uniform3fv(U.uOff, l.L.min); gl.uniform3fv(U.uScl, l.L.ext); gl.uniform3fv(U.uColor, [0.8, 0.75, 0.6]);
    const p = l.prop >= 0 ? l.props[l.prop] : null;
    gl.uniform1i(U.uMode, p ? 1 : 0);
    if (p) { const s = Math.min(p.min, 0) < 0 && p.max > 0; const mm = s ? Math.max(-p.min, p.max) : 0; gl.uniform2fv(U.uRange, s ? [-mm, mm] : [p.min, p.max]); }
    gl.uniform1i(U.uLit, l.L.kind === "mesh" ? 1 : 0);
    const size = g.itype === gl.UNSIGNED_SHORT ? 2 : 4;
    if (l.L.kind === "mesh") { const a = 3 * t0, b = Math.min(3 * t1, g.nidx); if (b > a) gl.drawElements(gl.TRIANGLES, b - a, g.itype, a * size); }
    else if (l.L.kind === "lines") gl.drawElements(gl.LINES, g.nidx, g.itype, 0);
    else gl.drawArrays(gl.POINTS, 0, g.n);
  }
  // one frame on the screen: the proxies when `lod` (the camera moves), else every triangle
  function frame(lod, scale) {
    refine = null;
    resolution(lod ? (scale === undefined ? MOVING_SCALE : scale) : 1);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    setup(mvp(), canvas.width, canvas.height);
    for (const l of layers) if (l.visible) drawLayer(l, lod && l.proxy ? l.proxy : l.full, 0, Infinity);
    shown = lod && layers.some((l) => l.visible && l.proxy) ? "proxy" : "full";
  }
  function draw() { frame(false); legend(); }
  // refinement at rest: the full meshes drawn CHUNK triangles per animation frame into an
  // offscreen framebuffer, copied to the screen when complete; any camera move cancels it
  const CHUNK = 150000;
  let refine = null, fbo = null, shown = "full", fullAt = null, idle = null;
  function offscreen() {
    if (fbo) return fbo.f;
    const f = gl.createFramebuffer(); gl.bindFramebuffer(gl.FRAMEBUFFER, f);
    for (const [fmt, at] of [[gl.RGBA8, gl.COLOR_ATTACHMENT0], [gl.DEPTH_COMPONENT24, gl.DEPTH_ATTACHMENT]]) {
      const r = gl.createRenderbuffer(); gl.bindRenderbuffer(gl.RENDERBUFFER, r);
      gl.renderbufferStorage(gl.RENDERBUFFER, fmt, W, H); gl.framebufferRenderbuffer(gl.FRAMEBUFFER, at, gl.RENDERBUFFER, r);
    }
    fbo = { f };
    return f;
  }
  function refineStep() {
    const job = refine;
    if (!job) return;
    gl.bindFramebuffer(gl.FRAMEBUFFER, offscreen());
    if (job.t === 0) setup(job.m, W, H);
    else { gl.viewport(0, 0, W, H); gl.enable(gl.DEPTH_TEST); gl.useProgram(P); }
    let more = false;
    for (const l of layers) {
      if (!l.visible) continue;
      if (!l.proxy) { if (job.t === 0) drawLayer(l, l.full, 0, Infinity); continue; }
      drawLayer(l, l.full, job.t, job.t + CHUNK);
      if (3 * (job.t + CHUNK) < l.full.nidx) more = true;
    }
    job.t += CHUNK;
    if (more) { requestAnimationFrame(refineStep); return; }
    resolution(1); // in the same task as the copy: no blank frame reaches the screen
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, fbo.f); gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
    gl.blitFramebuffer(0, 0, W, H, 0, 0, W, H, gl.COLOR_BUFFER_BIT, gl.NEAREST);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    refine = null; shown = "full"; fullAt = performance.now();
    for (const w of waiters.splice(0)) w(fullAt);
  }
  const waiters = [];
  function rest() {
    if (!layers.some((l) => l.visible && l.proxy)) return;
    refine = { t: 0, m: mvp() };
    requestAnimationFrame(refineStep);
  }
  // a camera move: the proxy now, the full meshes once the camera rests for 250 ms
  let pending = false;
  function moved() {
    if (!pending) { pending = true; requestAnimationFrame(() => { pending = false; frame(true); }); }
    clearTimeout(idle); idle = setTimeout(rest, 250);
  }
  function legend() {
    const l = layers.find((l) => l.prop >= 0 && l.visible), el = document.getElementById("legend");
    const bar = (name, stops, a, b) => "<b>" + name + "</b><div style='height:12px;background:linear-gradient(to right," + stops.join(",") + ")'></div><span>" + a.toPrecision(4) + "</span><span style='float:right'>" + b.toPrecision(4) + "</span><div style='clear:both'></div>";
    let html = "";
    if (l) {
      const p = l.props[l.prop], s = p.min < 0 && p.max > 0, mm = Math.max(-p.min, p.max);
      const a = s ? -mm : p.min, b = s ? mm : p.max, stops = [];
      for (let i = 0; i <= 8; i++) stops.push("rgb(" + cmap(i / 8, s).map((x) => Math.round(255 * Math.min(1, Math.max(0, x)))).join(",") + ")");
      html += bar(p.name, stops, a, b);
    }
    // volumes: the slices' colour map over the value range (data units)
    for (const v of layers) {
      if (!v.vol || !v.visible) continue;
      const t = scene.cmaps[v.vol.cmap], stops = [];
      for (let i = 0; i <= 16; i++) { const k = 3 * Math.round(i * 255 / 16); stops.push("rgb(" + t[k] + "," + t[k + 1] + "," + t[k + 2] + ")"); }
      html += bar(v.L.name + " (value)", stops, v.vol.range[0], v.vol.range[1]);
    }
    el.style.display = html ? "" : "none";
    el.innerHTML = html;
  }
  // the colour-map shader uses the same ramp as the legend (uploaded as a uniform-free formula)
  function pixels() { const w = canvas.width, h = canvas.height, px = new Uint8Array(4 * w * h); gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px); return px; }
  // foreground: the share of pixels off the background; colours: distinct colours (4 bits a channel)
  function stats(px) { let fg = 0, s = 0; const seen = new Set(); for (let i = 0; i < px.length; i += 4) { if (Math.abs(px[i] - 245) > 6 || Math.abs(px[i + 2] - 245) > 6) fg++; s += px[i]; seen.add((px[i] >> 4) << 8 | (px[i + 1] >> 4) << 4 | px[i + 2] >> 4); } return { foreground: fg / (px.length / 4), mean: s / (px.length / 4), colours: seen.size }; }
  function pick(cx, cy) {
    const m = mvp(), a = W / H, t = Math.tan(0.35);
    const dx = (2 * cx / W - 1) * t * a, dy = (1 - 2 * cy / H) * t;
    const d = [0, 1, 2].map((k) => m.f[k] + dx * m.r[k] + dy * m.up[k]), o = m.e;
    let best = { t: Infinity };
    layers.forEach((l, li) => {
      if (!l.visible || l.L.kind !== "mesh") return;
      const P = l.pos, I = l.idx;
      for (let i = 0; i < I.length; i += 3) {
        const a = 3 * I[i], b = 3 * I[i + 1], c = 3 * I[i + 2];
        const e1 = [P[b] - P[a], P[b + 1] - P[a + 1], P[b + 2] - P[a + 2]], e2 = [P[c] - P[a], P[c + 1] - P[a + 1], P[c + 2] - P[a + 2]];
        const h = [d[1] * e2[2] - d[2] * e2[1], d[2] * e2[0] - d[0] * e2[2], d[0] * e2[1] - d[1] * e2[0]];
        const det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2]; if (Math.abs(det) < 1e-20) continue;
        const s = [o[0] - P[a], o[1] - P[a + 1], o[2] - P[a + 2]], u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / det; if (u < 0 || u > 1) continue;
        const qv = [s[1] * e1[2] - s[2] * e1[1], s[2] * e1[0] - s[0] * e1[2], s[0] * e1[1] - s[1] * e1[0]];
        const v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det; if (v < 0 || u + v > 1) continue;
        const tt = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
        if (tt > 0 && tt < best.t) { const w = [1 - u - v, u, v], k = w.indexOf(Math.max(...w)); best = { t: tt, layer: li, vertex: I[i + k] }; }
      }
    });
    // slices of volumes: the nearest hit along the same ray wins
    layers.forEach((l, li) => {
      if (!l.visible || !l.vol) return;
      const h = l.vol.pick(o, d);
      if (h && h.t < best.t) best = { t: h.t, layer: li, slice: h };
    });
    if (best.layer === undefined) return null;
    if (best.slice) {
      const h = best.slice, out = { layer: best.layer, slice: h.slice, index: h.index, point: h.point, fractional: h.fractional, value: h.value, sample: h.sample };
      document.getElementById("pick").textContent = "xyz"[h.slice] + " slice " + h.index + " at (" + h.point.map((x) => x.toPrecision(4)).join(", ") + "): value " + h.value.toPrecision(5) + " (nearest sample " + JSON.stringify(h.sample.index) + ": " + h.sample.value.toPrecision(5) + ")";
      return out;
    }
    const l = layers[best.layer], out = { layer: best.layer, vertex: best.vertex, values: {} };
    for (const p of l.props) out.values[p.name] = p.v[best.vertex];
    document.getElementById("pick").textContent = "vertex " + best.vertex + " " + JSON.stringify(out.values);
    return out;
  }
  // interaction: drag orbits, shift-drag pans, wheel zooms, click picks
  let drag = null;
  canvas.addEventListener("mousedown", (e) => { drag = { x: e.clientX, y: e.clientY, moved: false }; });
  window.addEventListener("mouseup", (e) => { if (drag && !drag.moved) pick(e.clientX, e.clientY); drag = null; });
  window.addEventListener("mousemove", (e) => {
    if (!drag) return; const dx = e.clientX - drag.x, dy = e.clientY - drag.y; drag.x = e.clientX; drag.y = e.clientY; drag.moved = true;
    if (e.shiftKey) { const m = mvp(), s = cam.dist / H; for (let k = 0; k < 3; k++) cam.target[k] += s * (-dx * m.r[k] + dy * m.up[k]); }
    else { cam.az -= dx * 0.01; cam.el = Math.max(-1.57, Math.min(1.57, cam.el + dy * 0.01)); }
    moved();
  });
  canvas.addEventListener("wheel", (e) => { cam.dist *= Math.exp(e.deltaY * 0.001); e.preventDefault(); moved(); }, { passive: false });
  // panel: layers, colour property, figures
  const panel = document.getElementById("layers");
  layers.forEach((l) => {
    const d = document.createElement("div"), cb = document.createElement("input"); cb.type = "checkbox"; cb.checked = l.visible;
    cb.onchange = () => { l.visible = cb.checked; legend(); moved(); }; d.append(cb, " " + l.L.name + " ");
    if (l.props.length) {
      const s = document.createElement("select");
      s.innerHTML = "<option value='-1'>plain</option>" + l.props.map((p, i) => "<option value='" + i + "'>" + p.name + "</option>").join("");
      s.value = String(l.prop);
      s.onchange = () => {
        l.prop = +s.value;
        if (l.prop >= 0) {
          gl.bindBuffer(gl.ARRAY_BUFFER, l.full.vbuf); gl.bufferData(gl.ARRAY_BUFFER, l.props[l.prop].v, gl.STATIC_DRAW);
          if (l.proxy) { gl.bindBuffer(gl.ARRAY_BUFFER, l.proxy.vbuf); gl.bufferData(gl.ARRAY_BUFFER, l.proxy.vals[l.prop], gl.STATIC_DRAW); }
        }
        legend(); moved();
      };
      d.append(s);
    }
    if (l.vol) {
      // the three slices: a slider each (grid plane index), and the colour map
      const v = l.vol, V = l.L.volume;
      for (let a = 0; a < 3; a++) {
        const row = document.createElement("div"), r = document.createElement("input"), lab = document.createElement("span");
        r.type = "range"; r.min = 0; r.max = V.dims[a] - 1; r.step = 1; r.value = v.index[a]; r.id = "slice" + a; r.style.width = "120px";
        const show = () => { lab.textContent = " " + "xyz"[a] + " = " + v.position(a).toPrecision(4) + " (" + v.index[a] + ")"; };
        r.oninput = () => { v.set(a, +r.value); show(); moved(); };
        show(); row.append(r, lab); d.append(row);
        l["slider" + a] = { r, show };
      }
      const s = document.createElement("select");
      s.innerHTML = Object.keys(scene.cmaps).map((k) => "<option>" + k + "</option>").join("");
      s.value = v.cmap;
      s.onchange = () => { v.setMap(s.value); legend(); moved(); };
      d.append("colours ", s);
    }
    for (const t of l.L.notes || []) { const e = document.createElement("div"); e.style.color = "#a40"; e.textContent = "note: " + t; d.append(e); }
    panel.append(d);
  });
  // first frame: the proxies (fast), then the full meshes chunk by chunk
  pixels.one = () => { const px = new Uint8Array(4); gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px); };
  frame(true, 1); legend();
  pixels.one();
  const ready = performance.now();
  if (shown === "proxy") rest(); else fullAt = ready;
  let renderer = gl.getParameter(gl.RENDERER);
  const dbg = gl.getExtension("WEBGL_debug_renderer_info");
  if (dbg) renderer = gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL);
  function report(extra) {
    const r = Object.assign({ ready_ms: typeof ready === "number" ? ready : null, full_ms: fullAt, renderer, shown, errors }, extra || {});
    document.getElementById("morpho-selftest").textContent = JSON.stringify(r);
    return r;
  }
  // a scripted orbit timed by requestAnimationFrame for `sec` seconds, drawing the proxies
  // (`lod`, what a drag draws) or every triangle
  function orbitFps(sec, lod, scale) {
    clearTimeout(idle); refine = null;
    return new Promise((done) => {
      const t = [];
      function step() {
        const now = performance.now();
        t.push(now);
        if (now - t[0] >= 1000 * sec) {
          const d = []; for (let i = 1; i < t.length; i++) d.push(t[i] - t[i - 1]);
          d.sort((a, b) => a - b);
          done({ scale: lod ? scale : 1, fps: (t.length - 1) / ((now - t[0]) / 1000), frames: t.length - 1, seconds: (now - t[0]) / 1000, median_ms: d[d.length >> 1], p95_ms: d[Math.floor(0.95 * (d.length - 1))], max_ms: d[d.length - 1] });
          return;
        }
        cam.az += 0.03; frame(lod, scale);
        requestAnimationFrame(step);
      }
      requestAnimationFrame(step);
    });
  }
  // test hook: page.html#selftest=orbit,pick:123,bench:60 (synchronous: the result is in the
  // DOM when the load ends) and fps:SECONDS, fpsfullres:SECONDS, fpsfull:SECONDS, full
  // (asynchronous: see
  // window.morphoSelftest)
  async function selftest(steps) {
    const res = {};
    for (const step of steps) {
      const [what, arg] = step.split(":");
      if (what === "orbit") { draw(); const a = pixels(); res.before = stats(a); cam.az += 0.7; draw(); const b = pixels(); let ch = 0; for (let i = 0; i < a.length; i += 4) if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2]) ch++; res.after = stats(b); res.changed = ch / (a.length / 4); }
      if (what === "pick") {
        const l = layers[0], v = +arg, n = [0, 0, 0];
        const I = l.idx; for (let t = 0; t < I.length; t += 3) if (I[t] === v || I[t + 1] === v || I[t + 2] === v) { const P = l.pos, A = 3 * I[t], B = 3 * I[t + 1], C = 3 * I[t + 2]; const u = [0, 1, 2].map((k) => P[B + k] - P[A + k]), w = [0, 1, 2].map((k) => P[C + k] - P[A + k]); n[0] += u[1] * w[2] - u[2] * w[1]; n[1] += u[2] * w[0] - u[0] * w[2]; n[2] += u[0] * w[1] - u[1] * w[0]; }
        const len = Math.hypot(...n) || 1; cam.target = [0, 1, 2].map((k) => l.pos[3 * v + k]); cam.az = Math.atan2(n[1], n[0]); cam.el = Math.asin(Math.max(-1, Math.min(1, n[2] / len))); cam.dist = 0.8 * diag;
        draw(); res.pick = pick(W / 2, H / 2);
      }
      // frames drawn back to back, each waited for (readPixels of one pixel)
      if (what === "bench") { const N = +arg || 30, t0 = performance.now(); for (let i = 0; i < N; i++) { cam.az += 0.05; frame(true); pixels.one(); } res.fps = N / ((performance.now() - t0) / 1000); }
      // volumes: move slice A of the first volume to grid plane I (and measure what changed),
      // pick at the fraction (X, Y) of the canvas, show or hide layer N
      if (what === "slice") {
        const [, a, i] = step.split(":"), l = layers.find((l) => l.vol);
        draw(); const pa = pixels(); l.vol.set(+a, +i); draw(); const pb = pixels();
        let ch = 0; for (let k = 0; k < pa.length; k += 4) if (pa[k] !== pb[k] || pa[k + 1] !== pb[k + 1] || pa[k + 2] !== pb[k + 2]) ch++;
        (res.slices = res.slices || []).push({ axis: +a, index: l.vol.index[+a], position: l.vol.position(+a), changed: ch / (pa.length / 4), stats: stats(pb) });
      }
      if (what === "vpick") { const [, x, y] = step.split(":"); draw(); (res.vpick = res.vpick || []).push(pick(+x * W, +y * H)); }
      if (what === "show" || what === "hide") { layers[+arg].visible = what === "show"; draw(); res.stats = stats(pixels()); }
      if (what === "full") { if (fullAt === null) await new Promise((w) => waiters.push(w)); res.full_ms = fullAt; res.full_stats = stats(pixels()); }
      if (what === "fps") res.orbit = await orbitFps(+arg || 3, true, MOVING_SCALE);
      if (what === "fpsfullres") res.orbit_fullres = await orbitFps(+arg || 3, true, 1);
      if (what === "fpsfull") res.orbit_full = await orbitFps(+arg || 3, false);
    }
    return report(res);
  }
  const m = /selftest=([^&]*)/.exec(location.hash);
  window.morphoSelftest = m ? selftest(m[1].split(",")) : Promise.resolve(report());
})();
