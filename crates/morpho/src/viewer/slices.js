"use strict";
// morpho viewer: a volume as three movable orthogonal slices (Hamann 1991 §2.3; see
// viewer/volume.rs for the encoding). V is the layer's `volume` descriptor, bytes its codes,
// cmaps the colour tables (256 RGB entries each), prog the compiled slice program.
function morphoVolume(gl, V, bytes, cmaps, prog) {
  const [nx, ny, nz] = V.dims, n = nx * ny * nz;
  const codes = V.bits === 8 ? new Uint16Array(bytes) : new Uint16Array(bytes.buffer, bytes.byteOffset, n);
  const nan = V.bits === 16 ? 65535 : -1;
  const maxCode = V.step > 0 ? Math.round((V.range[1] - V.range[0]) / V.step) : 0;
  const value = (c) => (c === nan ? NaN : V.lo + c * V.step);
  const at = (i, j, k) => codes[i + nx * (j + ny * k)];
  // grid frame -> world: pivot + sum_a (g_a - pivot_a) dir[a]; and back (the inverse matrix)
  const D = V.directions, P = V.pivot;
  let Inv = null;
  if (D) {
    // M[b][a] = D[a][b]; Inv = M^-1
    const M = [0, 1, 2].map((b) => [0, 1, 2].map((a) => D[a][b]));
    const c = (r, s) => M[(r + 1) % 3][(s + 1) % 3] * M[(r + 2) % 3][(s + 2) % 3] - M[(r + 1) % 3][(s + 2) % 3] * M[(r + 2) % 3][(s + 1) % 3];
    const det = M[0][0] * c(0, 0) + M[0][1] * c(0, 1) + M[0][2] * c(0, 2);
    Inv = [0, 1, 2].map((r) => [0, 1, 2].map((s) => c(s, r) / det));
  }
  const toWorld = (g) => D ? [0, 1, 2].map((b) => P[b] + (g[0] - P[0]) * D[0][b] + (g[1] - P[1]) * D[1][b] + (g[2] - P[2]) * D[2][b]) : g;
  const toGrid = (w) => Inv ? [0, 1, 2].map((r) => P[r] + Inv[r][0] * (w[0] - P[0]) + Inv[r][1] * (w[1] - P[1]) + Inv[r][2] * (w[2] - P[2])) : w;
  const dirToGrid = (d) => Inv ? [0, 1, 2].map((r) => Inv[r][0] * d[0] + Inv[r][1] * d[1] + Inv[r][2] * d[2]) : d;
  const C = V.coords, last = (k) => C[k][C[k].length - 1];
  // the indices where an axis' spacing changes: the slice mesh needs vertices only there
  function breaks(k) {
    const c = C[k], out = [0], tol = 1e-9 * Math.abs(last(k) - c[0]);
    for (let i = 1; i + 1 < c.length; i++) if (Math.abs((c[i + 1] - c[i]) - (c[i] - c[i - 1])) > tol) out.push(i);
    if (c.length > 1) out.push(c.length - 1);
    return out;
  }
  const B = [breaks(0), breaks(1), breaks(2)];
  const inplane = (a) => (a === 0 ? [1, 2] : a === 1 ? [0, 2] : [0, 1]);
  const index = [Math.floor(nx / 2), Math.floor(ny / 2), Math.floor(nz / 2)];
  // the colour map texture
  const lutTex = gl.createTexture();
  function setMap(name) {
    const t = cmaps[name], rgba = new Uint8Array(1024);
    for (let i = 0; i < 256; i++) { rgba[4 * i] = t[3 * i]; rgba[4 * i + 1] = t[3 * i + 1]; rgba[4 * i + 2] = t[3 * i + 2]; rgba[4 * i + 3] = 255; }
    gl.bindTexture(gl.TEXTURE_2D, lutTex);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, 256, 1, 0, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR); gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE); gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    vol.cmap = name;
  }
  // one slice per axis: texture of its codes, vertex grid over the break points, outline
  const slices = [0, 1, 2].map((a) => {
    const [b, c] = inplane(a), flat = C[b].length < 2 || C[c].length < 2;
    const tex = gl.createTexture(), vao = gl.createVertexArray(), pbuf = gl.createBuffer(), ibuf = gl.createBuffer(), ebuf = gl.createBuffer();
    const Bb = B[b], Bc = B[c], nv = Bb.length * Bc.length, idx = new Float32Array(2 * nv), tri = [];
    for (let j = 0; j < Bc.length; j++) for (let i = 0; i < Bb.length; i++) { idx[2 * (i + Bb.length * j)] = Bb[i]; idx[2 * (i + Bb.length * j) + 1] = Bc[j]; }
    for (let j = 0; j + 1 < Bc.length; j++) for (let i = 0; i + 1 < Bb.length; i++) {
      const p = i + Bb.length * j; tri.push(p, p + 1, p + 1 + Bb.length, p, p + 1 + Bb.length, p + Bb.length);
    }
    gl.bindVertexArray(vao);
    gl.bindBuffer(gl.ARRAY_BUFFER, pbuf); gl.bufferData(gl.ARRAY_BUFFER, 12 * nv, gl.DYNAMIC_DRAW); gl.enableVertexAttribArray(0); gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 0, 0);
    gl.bindBuffer(gl.ARRAY_BUFFER, ibuf); gl.bufferData(gl.ARRAY_BUFFER, idx, gl.STATIC_DRAW); gl.enableVertexAttribArray(1); gl.vertexAttribPointer(1, 2, gl.FLOAT, false, 0, 0);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ebuf); gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, new Uint32Array(tri), gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    return { a, b, c, flat, tex, vao, pbuf, nv, ntri: tri.length, outline: null, visible: true };
  });
  function upload(s) {
    const { a, b, c } = s, w = V.dims[b], h = V.dims[c], t = new Uint16Array(w * h), ijk = [0, 0, 0];
    ijk[a] = index[a];
    for (let j = 0; j < h; j++) { ijk[c] = j; for (let i = 0; i < w; i++) { ijk[b] = i; t[i + w * j] = at(ijk[0], ijk[1], ijk[2]); } }
    gl.bindTexture(gl.TEXTURE_2D, s.tex);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.R16UI, w, h, 0, gl.RED_INTEGER, gl.UNSIGNED_SHORT, t);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST); gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    // vertices: the break points of the two in-plane axes at the slice's grid plane
    const Bb = B[b], Bc = B[c], pos = new Float32Array(3 * s.nv), g = [0, 0, 0];
    g[a] = C[a][index[a]];
    for (let j = 0; j < Bc.length; j++) for (let i = 0; i < Bb.length; i++) {
      g[b] = C[b][Bb[i]]; g[c] = C[c][Bc[j]];
      const w3 = toWorld(g), p = 3 * (i + Bb.length * j); pos[p] = w3[0]; pos[p + 1] = w3[1]; pos[p + 2] = w3[2];
    }
    gl.bindBuffer(gl.ARRAY_BUFFER, s.pbuf); gl.bufferSubData(gl.ARRAY_BUFFER, 0, pos);
    const corner = (hb, hc) => { const q = [0, 0, 0]; q[a] = g[a]; q[b] = hb ? last(b) : C[b][0]; q[c] = hc ? last(c) : C[c][0]; return toWorld(q); };
    s.outline = [corner(0, 0), corner(1, 0), corner(1, 0), corner(1, 1), corner(1, 1), corner(0, 1), corner(0, 1), corner(0, 0)];
  }
  // the box: 12 edges
  const box = [];
  for (let k = 0; k < 3; k++) for (let m = 0; m < 4; m++) {
    const e = [0, 1, 2].filter((x) => x !== k), p = [0, 0, 0], q = [0, 0, 0];
    for (const [t, u] of [[p, 0], [q, 1]]) { t[k] = u ? last(k) : C[k][0]; t[e[0]] = m & 1 ? last(e[0]) : C[e[0]][0]; t[e[1]] = m & 2 ? last(e[1]) : C[e[1]][0]; }
    box.push(toWorld(p), toWorld(q));
  }
  const lineVao = gl.createVertexArray(), lineBuf = gl.createBuffer();
  gl.bindVertexArray(lineVao); gl.bindBuffer(gl.ARRAY_BUFFER, lineBuf); gl.enableVertexAttribArray(0); gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 0, 0);
  gl.disableVertexAttribArray(1); gl.vertexAttrib2f(1, 0, 0); gl.bindVertexArray(null);
  const U = {};
  for (const u of ["uMVP", "uTex", "uLut", "uMax", "uNan", "uMode", "uColor"]) U[u] = gl.getUniformLocation(prog, u);
  const vol = {
    index, cmap: "viridis", range: V.range, nan, maxCode,
    draw(M) {
      gl.useProgram(prog);
      gl.uniformMatrix4fv(U.uMVP, false, M);
      gl.uniform1i(U.uMode, 0); gl.uniform1f(U.uMax, maxCode); gl.uniform1i(U.uNan, nan);
      gl.activeTexture(gl.TEXTURE1); gl.bindTexture(gl.TEXTURE_2D, lutTex); gl.uniform1i(U.uLut, 1);
      gl.activeTexture(gl.TEXTURE0); gl.uniform1i(U.uTex, 0);
      const lines = box.slice();
      for (const s of slices) {
        if (!s.visible) continue;
        for (const p of s.outline) lines.push(p);
        if (s.flat) continue;
        gl.bindTexture(gl.TEXTURE_2D, s.tex); gl.bindVertexArray(s.vao);
        gl.drawElements(gl.TRIANGLES, s.ntri, gl.UNSIGNED_INT, 0);
      }
      gl.uniform1i(U.uMode, 1); gl.uniform3fv(U.uColor, [0.2, 0.2, 0.2]);
      gl.bindVertexArray(lineVao); gl.bindBuffer(gl.ARRAY_BUFFER, lineBuf);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(lines.flat()), gl.DYNAMIC_DRAW);
      gl.drawArrays(gl.LINES, 0, lines.length);
      gl.bindVertexArray(null);
    },
    // moves slice `a` to grid plane `i` (clamped)
    set(a, i) { index[a] = Math.max(0, Math.min(V.dims[a] - 1, Math.round(i))); upload(slices[a]); },
    position(a) { return C[a][index[a]]; },
    show(a, on) { slices[a].visible = on; },
    setMap,
    // the nearest slice hit by the world ray o + t d (t > 0): the slice, the point, its
    // fractional sample indices and the value there (bilinear in the slice's grid plane, as drawn)
    pick(o, d) {
      const og = toGrid(o), dg = dirToGrid(d);
      let best = null;
      for (const s of slices) {
        if (!s.visible || s.flat || dg[s.a] === 0) continue;
        const t = (C[s.a][index[s.a]] - og[s.a]) / dg[s.a];
        if (!(t > 0) || (best && t >= best.t)) continue;
        const g = [0, 1, 2].map((k) => og[k] + t * dg[k]);
        const f = [0, 0, 0];
        f[s.a] = index[s.a];
        let inside = true;
        for (const k of [s.b, s.c]) {
          const c = C[k], x = g[k];
          if (!(x >= c[0] && x <= last(k))) { inside = false; break; }
          let lo = 0, hi = c.length - 1;
          while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (c[mid] <= x) lo = mid; else hi = mid; }
          f[k] = lo + (hi > lo ? (x - c[lo]) / (c[hi] - c[lo]) : 0);
        }
        if (!inside) continue;
        g[s.a] = C[s.a][index[s.a]];
        best = { t, slice: s.a, index: index[s.a], grid: g, point: toWorld(g), fractional: f };
      }
      if (!best) return null;
      const f = best.fractional, a = best.slice, [b, c] = inplane(a);
      const i0 = [0, 0, 0];
      for (let k = 0; k < 3; k++) i0[k] = Math.min(Math.floor(f[k]), V.dims[k] - 1);
      const tb = f[b] - i0[b], tc = f[c] - i0[c];
      let v = 0;
      for (const [db, dc, w] of [[0, 0, (1 - tb) * (1 - tc)], [1, 0, tb * (1 - tc)], [0, 1, (1 - tb) * tc], [1, 1, tb * tc]]) {
        const q = i0.slice(); q[b] = Math.min(q[b] + db, V.dims[b] - 1); q[c] = Math.min(q[c] + dc, V.dims[c] - 1);
        const code = at(q[0], q[1], q[2]);
        v = code === nan ? NaN : v + w * value(code);
      }
      const near = f.map((x) => Math.round(x));
      best.value = v;
      best.sample = { index: near, value: value(at(near[0], near[1], near[2])) };
      return best;
    },
  };
  setMap("viridis");
  for (const s of slices) upload(s);
  return vol;
}
