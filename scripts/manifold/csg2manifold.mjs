// Reads an OpenSCAD CSG export (`openscad -o x.csg`), builds the same solid
// with Manifold (the manifold-3d WebAssembly package) and writes it as a
// binary STL. A comparator for scripts/bench-export.sh, not part of strata:
// nothing in the build or the tests uses it.
//
//   node scripts/manifold/csg2manifold.mjs [--module PATH/manifold.js] IN.csg OUT.stl
//
// The module path defaults to $MANIFOLD_JS, then to a plain `manifold-3d`
// import. Curved leaves are cut as OpenSCAD 2021.01 cuts them (sphere rings,
// cylinder and circle fragments, linear_extrude slices and their diagonals,
// rotate_extrude rings, offset arcs as Clipper 6 steps them), so that both
// programs work on the same polyhedra. On success one JSON line goes to
// stderr: the seconds spent loading the module, parsing, building the
// Manifold tree (primitives, 2D work, hulls), evaluating it (the booleans,
// forced by getMesh) and writing, with the triangles and Manifold's volume.
// What it cannot read ends it with status 2 and one line `file:line: what`.

import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

class Refusal extends Error {}

let SOURCE = '<input>';
function refuse(line, what) {
  throw new Refusal(`${SOURCE}:${line}: ${what}`);
}

// ---------------------------------------------------------------- parsing

function tokenize(text) {
  const tokens = [];
  let i = 0;
  let line = 1;
  const n = text.length;
  while (i < n) {
    const c = text[i];
    if (c === '\n') { line++; i++; continue; }
    if (c === ' ' || c === '\t' || c === '\r') { i++; continue; }
    if (c === '/' && text[i + 1] === '/') {
      while (i < n && text[i] !== '\n') i++;
      continue;
    }
    if (c === '/' && text[i + 1] === '*') {
      i += 2;
      while (i < n && !(text[i] === '*' && text[i + 1] === '/')) { if (text[i] === '\n') line++; i++; }
      i += 2;
      continue;
    }
    if (/[0-9.]/.test(c) && (c !== '.' || /[0-9]/.test(text[i + 1] ?? ''))) {
      const m = /^(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?/.exec(text.slice(i, i + 64));
      tokens.push({ t: 'num', v: Number(m[0]), line });
      i += m[0].length;
      continue;
    }
    if (/[A-Za-z_$]/.test(c)) {
      let j = i + 1;
      while (j < n && /[A-Za-z0-9_$]/.test(text[j])) j++;
      tokens.push({ t: 'id', v: text.slice(i, j), line });
      i = j;
      continue;
    }
    if (c === '"') {
      let s = '';
      let j = i + 1;
      while (j < n && text[j] !== '"') {
        if (text[j] === '\\' && j + 1 < n) {
          const e = text[j + 1];
          s += e === 'n' ? '\n' : e === 't' ? '\t' : e === 'r' ? '\r' : e;
          j += 2;
        } else {
          if (text[j] === '\n') line++;
          s += text[j++];
        }
      }
      if (j >= n) refuse(line, 'unterminated string');
      tokens.push({ t: 'str', v: s, line });
      i = j + 1;
      continue;
    }
    if ('()[]{};,=-+%#!*:'.includes(c)) {
      tokens.push({ t: c, line });
      i++;
      continue;
    }
    refuse(line, `unexpected character '${c}'`);
  }
  tokens.push({ t: 'eof', line });
  return tokens;
}

class Parser {
  constructor(tokens) { this.tokens = tokens; this.k = 0; }
  peek() { return this.tokens[this.k]; }
  next() { return this.tokens[this.k++]; }
  expect(t) {
    const tok = this.next();
    if (tok.t !== t) refuse(tok.line, `expected '${t}', found ${describe(tok)}`);
    return tok;
  }

  statements(until) {
    const list = [];
    while (this.peek().t !== until) {
      const s = this.statement();
      if (s) list.push(s);
    }
    return list;
  }

  statement() {
    const tok = this.peek();
    if (tok.t === ';') { this.next(); return null; }
    if (tok.t === '{') {
      this.next();
      const children = this.statements('}');
      this.next();
      return { name: 'group', args: { pos: [], named: {} }, children, line: tok.line, modifier: '' };
    }
    let modifier = '';
    while ('%#!*'.includes(this.peek().t)) modifier += this.next().t;
    const id = this.expect('id');
    this.expect('(');
    const args = this.arguments();
    let children = [];
    const after = this.peek();
    if (after.t === ';') this.next();
    else if (after.t === '{') {
      this.next();
      children = this.statements('}');
      this.next();
    } else {
      const s = this.statement();
      if (s) children = [s];
    }
    return { name: id.v, args, children, line: id.line, modifier };
  }

  arguments() {
    const args = { pos: [], named: {} };
    if (this.peek().t === ')') { this.next(); return args; }
    for (;;) {
      const a = this.peek();
      const b = this.tokens[this.k + 1];
      if (a.t === 'id' && b.t === '=') {
        this.k += 2;
        args.named[a.v] = this.value();
      } else {
        args.pos.push(this.value());
      }
      const sep = this.next();
      if (sep.t === ')') return args;
      if (sep.t !== ',') refuse(sep.line, `expected ',' or ')', found ${describe(sep)}`);
    }
  }

  value() {
    const tok = this.next();
    switch (tok.t) {
      case '-': return negate(this.value(), tok.line);
      case '+': return this.value();
      case 'num': return tok.v;
      case 'str': return tok.v;
      case 'id':
        if (tok.v === 'true') return true;
        if (tok.v === 'false') return false;
        if (tok.v === 'undef') return undefined;
        if (tok.v === 'inf') return Infinity;
        if (tok.v === 'nan') return NaN;
        return refuse(tok.line, `the expression '${tok.v}' (only literal values are read)`);
      case '[': {
        const list = [];
        if (this.peek().t === ']') { this.next(); return list; }
        for (;;) {
          list.push(this.value());
          const sep = this.next();
          if (sep.t === ']') return list;
          if (sep.t === ':') refuse(sep.line, 'a range');
          if (sep.t !== ',') refuse(sep.line, `expected ',' or ']', found ${describe(sep)}`);
        }
      }
      default:
        return refuse(tok.line, `unexpected ${describe(tok)}`);
    }
  }
}

function describe(tok) {
  if (tok.t === 'eof') return 'the end of the file';
  if (tok.t === 'id' || tok.t === 'num') return `'${tok.v}'`;
  if (tok.t === 'str') return 'a string';
  return `'${tok.t}'`;
}

function negate(v, line) {
  if (typeof v === 'number') return -v;
  if (Array.isArray(v)) return v.map((x) => negate(x, line));
  return refuse(line, 'a minus sign before a value that is not a number');
}

// ------------------------------------------------- OpenSCAD's arithmetic

// Degree trigonometry exact at multiples of 30 and 45 degrees, as
// OpenSCAD 2021.01's degree_trig does it.
const SQRT3_4 = Math.sqrt(3) / 2;
function sinD(x) {
  if (!(x < 360 && x >= 0)) x -= 360 * Math.floor(x / 360);
  const oppose = x >= 180;
  if (oppose) x -= 180;
  if (x > 90) x = 180 - x;
  let r;
  if (x < 45) r = x === 30 ? 0.5 : Math.sin(x * Math.PI / 180);
  else if (x === 45) r = Math.SQRT1_2;
  else if (x === 60) r = SQRT3_4;
  else r = Math.cos((90 - x) * Math.PI / 180);
  return oppose ? -r : r;
}
function cosD(x) {
  if (!(x < 360 && x >= 0)) x -= 360 * Math.floor(x / 360);
  let oppose = x >= 180;
  if (oppose) x -= 180;
  if (x > 90) { x = 180 - x; oppose = !oppose; }
  let r;
  if (x > 45) r = x === 60 ? 0.5 : Math.sin((90 - x) * Math.PI / 180);
  else if (x === 45) r = Math.SQRT1_2;
  else if (x === 30) r = SQRT3_4;
  else r = Math.cos(x * Math.PI / 180);
  return oppose ? -r : r;
}

const GRID_FINE = 0.00000095367431640625;
function fragments(r, fn, fs, fa) {
  if (r < GRID_FINE || !Number.isFinite(fn)) return 3;
  if (fn > 0) return Math.trunc(fn >= 3 ? fn : 3);
  return Math.trunc(Math.ceil(Math.max(Math.min(360 / fa, r * 2 * Math.PI / fs), 5)));
}

function circlePoints(r, n) {
  const pts = [];
  for (let i = 0; i < n; i++) {
    const phi = (360 * i) / n;
    pts.push([r * cosD(phi), r * sinD(phi)]);
  }
  return pts;
}

function helixSlices(rSqr, height, twist, fn, fs, fa) {
  twist = Math.abs(twist);
  const minSlices = Math.max(Math.trunc(Math.ceil(twist / 120)), 1);
  if (Math.sqrt(rSqr) < GRID_FINE || !Number.isFinite(fn)) return minSlices;
  if (fn > 0) return Math.max(Math.trunc(Math.ceil((twist / 360) * fn)), minSlices);
  const t = twist * Math.PI / 180;
  const c = height / t;
  const arc = t * Math.sqrt(rSqr + c * c);
  const faSlices = Math.trunc(Math.ceil(twist / fa));
  const fsSlices = Math.trunc(Math.ceil(arc / fs));
  return Math.max(Math.min(faSlices, fsSlices), minSlices);
}

function conicalHelixSlices(rSqr, height, twist, scale, fn, fs, fa) {
  twist = Math.abs(twist);
  const r = Math.sqrt(rSqr);
  const minSlices = Math.max(Math.trunc(Math.ceil(twist / 120)), 1);
  if (r < GRID_FINE || !Number.isFinite(fn)) return minSlices;
  if (fn > 0) return Math.max(Math.trunc(Math.ceil((twist * fn) / 360)), minSlices);
  const rads = twist * Math.PI / 180;
  const end = scale > 1 ? rads * scale / (scale - 1) : rads / (1 - scale);
  const start = end - rads;
  const a = r / end;
  const spiral = (th) => 0.5 * a * (th * Math.sqrt(1 + th * th) + Math.asinh(th));
  const flat = spiral(end) - spiral(start);
  const total = Math.sqrt(flat * flat + height * height);
  const fsSlices = Math.trunc(Math.ceil(total / fs));
  const faSlices = Math.trunc(Math.ceil(twist / fa));
  return Math.max(Math.min(faSlices, fsSlices), minSlices);
}

function diagonalSlices(deltaSqr, height, fn, fs) {
  if (Math.sqrt(deltaSqr) < GRID_FINE || !Number.isFinite(fn)) return 1;
  if (fn > 0) return Math.max(Math.trunc(fn), 1);
  return Math.max(Math.trunc(Math.ceil(Math.sqrt(deltaSqr + height * height) / fs)), 1);
}

// OpenSCAD hands 2D shapes to Clipper 6 on a grid of 1/65536, truncating.
const CLIPPER_SCALE = 65536;
const toGrid = (v) => Math.trunc(v * CLIPPER_SCALE);

function signedArea(path) {
  let a = 0;
  for (let i = 0, j = path.length - 1; i < path.length; j = i++) {
    a += (path[j][0] + path[i][0]) * (path[j][1] - path[i][1]);
  }
  return -a / 2;
}

// ------------------------------------------------------------- geometry

let M; // the manifold-3d module, once loaded

// Triangles over welded vertices; becomes a Manifold. Positions pass
// through the 32-bit Mesh and are put back to their doubles by a warp.
class MeshBuilder {
  constructor() { this.index = new Map(); this.xyz = []; this.tris = []; }
  vertex(x, y, z) {
    x += 0; y += 0; z += 0; // -0 and 0 are one vertex
    const key = `${x},${y},${z}`;
    let i = this.index.get(key);
    if (i === undefined) {
      i = this.xyz.length / 3;
      this.index.set(key, i);
      this.xyz.push(x, y, z);
    }
    return i;
  }
  triangle(a, b, c) {
    if (a !== b && b !== c && a !== c) this.tris.push(a, b, c);
  }
  fan(ring, reversed) {
    for (let k = 1; k + 1 < ring.length; k++) {
      if (reversed) this.triangle(ring[0], ring[k + 1], ring[k]);
      else this.triangle(ring[0], ring[k], ring[k + 1]);
    }
  }
  volume() {
    const p = this.xyz;
    let v = 0;
    for (let t = 0; t < this.tris.length; t += 3) {
      const a = 3 * this.tris[t], b = 3 * this.tris[t + 1], c = 3 * this.tris[t + 2];
      v += p[a] * (p[b + 1] * p[c + 2] - p[b + 2] * p[c + 1])
        - p[a + 1] * (p[b] * p[c + 2] - p[b + 2] * p[c])
        + p[a + 2] * (p[b] * p[c + 1] - p[b + 1] * p[c]);
    }
    return v / 6;
  }
  manifold(line, what) {
    if (this.tris.length === 0) return new M.Manifold(new M.Mesh({ numProp: 3, vertProperties: new Float32Array(0), triVerts: new Uint32Array(0) }));
    if (this.volume() < 0) {
      for (let t = 0; t < this.tris.length; t += 3) {
        const s = this.tris[t + 1];
        this.tris[t + 1] = this.tris[t + 2];
        this.tris[t + 2] = s;
      }
    }
    const f32 = new Float32Array(this.xyz);
    let m;
    try {
      m = new M.Manifold(new M.Mesh({ numProp: 3, vertProperties: f32, triVerts: new Uint32Array(this.tris) }));
    } catch (e) {
      return refuse(line, `${what}: Manifold refused the mesh (${e.message ?? e})`);
    }
    let exact = true;
    for (let i = 0; i < f32.length; i++) if (f32[i] !== this.xyz[i]) { exact = false; break; }
    if (exact) return m;
    const back = new Map();
    for (let i = 0; i < f32.length; i += 3) back.set(`${f32[i]},${f32[i + 1]},${f32[i + 2]}`, i);
    const xyz = this.xyz;
    return m.warpBatch((v, count) => {
      for (let i = 0; i < 3 * count; i += 3) {
        const j = back.get(`${v[i]},${v[i + 1]},${v[i + 2]}`);
        if (j !== undefined) { v[i] = xyz[j]; v[i + 1] = xyz[j + 1]; v[i + 2] = xyz[j + 2]; }
      }
    });
  }
}

const solid = (m) => ({ dim: 3, m });
const shape = (cs) => ({ dim: 2, cs });
const emptySolid = () => solid(new MeshBuilder().manifold());

function sphere(r, fn, fs, fa, line) {
  if (!(r > 0) || !Number.isFinite(r)) return emptySolid();
  const n = fragments(r, fn, fs, fa);
  const rings = Math.trunc((n + 1) / 2);
  const mb = new MeshBuilder();
  const ring = [];
  for (let i = 0; i < rings; i++) {
    const phi = (180 * (i + 0.5)) / rings;
    const rr = r * sinD(phi);
    const z = r * cosD(phi);
    ring.push(circlePoints(rr, n).map(([x, y]) => mb.vertex(x, y, z)));
  }
  mb.fan(ring[0], false);
  for (let i = 0; i + 1 < rings; i++) {
    const up = ring[i], lo = ring[i + 1];
    for (let j = 0; j < n; j++) {
      const k = (j + 1) % n;
      mb.triangle(up[j], lo[j], lo[k]);
      mb.triangle(up[j], lo[k], up[k]);
    }
  }
  mb.fan(ring[rings - 1], true);
  return solid(mb.manifold(line, 'sphere'));
}

function cylinder(h, r1, r2, center, fn, fs, fa, line) {
  if (!(h > 0) || !Number.isFinite(h) || !(r1 >= 0) || !(r2 >= 0) || !(r1 > 0 || r2 > 0) ||
      !Number.isFinite(r1) || !Number.isFinite(r2)) return emptySolid();
  const n = fragments(Math.max(r1, r2), fn, fs, fa);
  const z1 = center ? -h / 2 : 0;
  const z2 = center ? h / 2 : h;
  const mb = new MeshBuilder();
  const lo = circlePoints(r1, n).map(([x, y]) => mb.vertex(x, y, z1));
  const up = circlePoints(r2, n).map(([x, y]) => mb.vertex(x, y, z2));
  for (let i = 0; i < n; i++) {
    const j = (i + 1) % n;
    // OpenSCAD's diagonal: from the bottom's next point to the top's point.
    mb.triangle(lo[i], lo[j], up[i]);
    mb.triangle(lo[j], up[j], up[i]);
  }
  mb.fan(lo, true);
  mb.fan(up, false);
  return solid(mb.manifold(line, 'cylinder'));
}

function cube(size, center) {
  const [x, y, z] = size;
  if (!(x > 0 && y > 0 && z > 0) || ![x, y, z].every(Number.isFinite)) return emptySolid();
  return solid(M.Manifold.cube([x, y, z], center));
}

// A planar face of any size, triangulated in its own plane (counter-clockwise
// about its normal, Newell's).
function triangulateFace(mb, face, pts) {
  if (face.length === 3) { mb.triangle(face[0], face[1], face[2]); return; }
  let nx = 0, ny = 0, nz = 0;
  for (let i = 0; i < face.length; i++) {
    const a = pts[face[i]], b = pts[face[(i + 1) % face.length]];
    nx += (a[1] - b[1]) * (a[2] + b[2]);
    ny += (a[2] - b[2]) * (a[0] + b[0]);
    nz += (a[0] - b[0]) * (a[1] + b[1]);
  }
  const len = Math.hypot(nx, ny, nz);
  if (len === 0) return;
  nx /= len; ny /= len; nz /= len;
  // u perpendicular to n, v = n x u.
  let ux, uy, uz;
  if (Math.abs(nx) < 0.9) { ux = 0; uy = nz; uz = -ny; } else { ux = -nz; uy = 0; uz = nx; }
  const ul = Math.hypot(ux, uy, uz);
  ux /= ul; uy /= ul; uz /= ul;
  const vx = ny * uz - nz * uy, vy = nz * ux - nx * uz, vz = nx * uy - ny * ux;
  const flat = face.map((i) => {
    const p = pts[i];
    return [p[0] * ux + p[1] * uy + p[2] * uz, p[0] * vx + p[1] * vy + p[2] * vz];
  });
  for (const [a, b, c] of M.triangulate([flat], -1)) mb.triangle(face[a], face[b], face[c]);
}

function polyhedron(points, faces, line) {
  const mb = new MeshBuilder();
  const pts = points.map((p, i) => {
    if (!Array.isArray(p) || p.length < 3 || !p.slice(0, 3).every(Number.isFinite)) refuse(line, `polyhedron point ${i} is not a 3D vector`);
    return p;
  });
  const ids = pts.map((p) => mb.vertex(p[0], p[1], p[2]));
  for (const f of faces) {
    // OpenSCAD lists a face's points clockwise seen from outside.
    const face = f.filter((i) => i >= 0 && i < pts.length).reverse();
    const local = face.map((i) => ids[i]);
    const lp = [];
    for (const i of face) lp[ids[i]] = pts[i];
    triangulateFace(mb, local, lp);
  }
  return solid(mb.manifold(line, 'polyhedron'));
}

function readMeshFile(file, line) {
  let data;
  try { data = readFileSync(file); } catch (e) { return refuse(line, `import(): cannot read ${file}`); }
  const mb = new MeshBuilder();
  const lower = file.toLowerCase();
  if (lower.endsWith('.stl')) {
    const head = data.subarray(0, 512).toString('latin1');
    const count = data.length >= 84 ? data.readUInt32LE(80) : -1;
    if (/^\s*solid/.test(head) && /facet|endsolid/.test(data.toString('latin1')) && data.length !== 84 + 50 * count) {
      const v = [...data.toString('latin1').matchAll(/vertex\s+(\S+)\s+(\S+)\s+(\S+)/g)].map((m) => mb.vertex(+m[1], +m[2], +m[3]));
      for (let i = 0; i + 2 < v.length; i += 3) mb.triangle(v[i], v[i + 1], v[i + 2]);
    } else {
      for (let t = 0; t < count; t++) {
        const o = 84 + 50 * t + 12;
        const v = [0, 1, 2].map((k) => mb.vertex(data.readFloatLE(o + 12 * k), data.readFloatLE(o + 12 * k + 4), data.readFloatLE(o + 12 * k + 8)));
        mb.triangle(v[0], v[1], v[2]);
      }
    }
  } else if (lower.endsWith('.off')) {
    const words = data.toString('latin1').replace(/#[^\n]*/g, '').split(/\s+/).filter(Boolean);
    let k = 0;
    if (/^C?N?4?n?OFF$/.test(words[0])) k++;
    const nv = +words[k++], nf = +words[k++];
    k++;
    const pts = [];
    for (let i = 0; i < nv; i++) { pts.push([+words[k], +words[k + 1], +words[k + 2]]); k += 3; }
    const ids = pts.map((p) => mb.vertex(p[0], p[1], p[2]));
    for (let i = 0; i < nf; i++) {
      const c = +words[k++];
      const face = words.slice(k, k + c).map(Number);
      k += c;
      const lp = [];
      for (const j of face) lp[ids[j]] = pts[j];
      triangulateFace(mb, face.map((j) => ids[j]), lp);
    }
  } else {
    return refuse(line, `import() of ${file.split('.').pop()} files`);
  }
  return solid(mb.manifold(line, `import("${file}")`));
}

// ------------------------------------------------------------------ 2D

function polygon2d(points, paths, line) {
  if (!Array.isArray(points)) return shape(new M.CrossSection([], 'EvenOdd'));
  const pts = points.map((p, i) => {
    if (!Array.isArray(p) || p.length < 2 || !Number.isFinite(p[0]) || !Number.isFinite(p[1])) refuse(line, `polygon point ${i} is not a 2D vector`);
    return [toGrid(p[0]) / CLIPPER_SCALE, toGrid(p[1]) / CLIPPER_SCALE];
  });
  let outlines;
  if (!Array.isArray(paths) || paths.length === 0) outlines = pts.length > 2 ? [pts] : [];
  else outlines = paths.map((path) => path.filter((i) => i >= 0 && i < pts.length).map((i) => pts[Math.trunc(i)]));
  return shape(new M.CrossSection(outlines, 'EvenOdd'));
}

// Clipper 6's ClipperOffset on OpenSCAD's integer grid: its own arc steps
// (rounded, where Clipper 2 takes the ceiling), then a union that keeps
// positive winding, as Clipper does for either sign of delta.
function offset2d(cs, delta, join, arcTolerance, miterLimit) {
  const src = [];
  let lowest = null;
  for (const outline of cs.toPolygons()) {
    const path = [];
    for (const [x, y] of outline) {
      const p = [toGrid(x), toGrid(y)];
      if (path.length === 0 || path[path.length - 1][0] !== p[0] || path[path.length - 1][1] !== p[1]) path.push(p);
    }
    while (path.length > 1 && path[0][0] === path[path.length - 1][0] && path[0][1] === path[path.length - 1][1]) path.pop();
    if (path.length < 3) continue;
    for (let k = 0; k < path.length; k++) {
      const p = path[k];
      if (!lowest || p[1] > lowest.p[1] || (p[1] === lowest.p[1] && p[0] < lowest.p[0])) lowest = { p, path };
    }
    src.push(path);
  }
  if (lowest && signedArea(lowest.path) < 0) for (const p of src) p.reverse();
  const d = delta * CLIPPER_SCALE;
  if (Math.abs(d) < 1e-20) return cs;
  const round = (v) => (v < 0 ? Math.trunc(v - 0.5) : Math.trunc(v + 0.5));
  let tol = arcTolerance * CLIPPER_SCALE;
  if (tol <= 0) tol = 0.25;
  else if (tol > Math.abs(d) * 0.25) tol = Math.abs(d) * 0.25;
  let steps = Math.PI / Math.acos(1 - tol / Math.abs(d));
  if (steps > Math.abs(d) * Math.PI) steps = Math.abs(d) * Math.PI;
  let sin = Math.sin(2 * Math.PI / steps);
  const cos = Math.cos(2 * Math.PI / steps);
  const stepsPerRad = steps / (2 * Math.PI);
  if (d < 0) sin = -sin;
  const miterLim = miterLimit > 2 ? 2 / (miterLimit * miterLimit) : 0.5;
  const out = [];
  for (const p of src) {
    const n = p.length;
    const normal = [];
    for (let j = 0; j < n; j++) {
      const a = p[j], b = p[(j + 1) % n];
      const dx = b[0] - a[0], dy = b[1] - a[1];
      const f = 1 / Math.sqrt(dx * dx + dy * dy);
      normal.push([dy * f, -dx * f]);
    }
    const dest = [];
    const push = (x, y) => dest.push([round(x) / CLIPPER_SCALE, round(y) / CLIPPER_SCALE]);
    let k = n - 1;
    for (let j = 0; j < n; j++) {
      const [px, py] = p[j];
      const nk = normal[k], nj = normal[j];
      let sinA = nk[0] * nj[1] - nj[0] * nk[1];
      const cosA = nk[0] * nj[0] + nk[1] * nj[1];
      if (Math.abs(sinA * d) < 1 && cosA > 0) {
        // Nearly straight on: one point, and the previous edge stays the
        // reference (Clipper returns here without advancing it).
        push(px + nk[0] * d, py + nk[1] * d);
        continue;
      }
      if (sinA > 1) sinA = 1;
      else if (sinA < -1) sinA = -1;
      if (sinA * d < 0) {
        push(px + nk[0] * d, py + nk[1] * d);
        dest.push([px / CLIPPER_SCALE, py / CLIPPER_SCALE]);
        push(px + nj[0] * d, py + nj[1] * d);
      } else if (join === 'round') {
        const a = Math.atan2(sinA, cosA);
        const count = Math.max(round(stepsPerRad * Math.abs(a)), 1);
        let x = nk[0], y = nk[1];
        for (let i = 0; i < count; i++) {
          push(px + x * d, py + y * d);
          const x2 = x;
          x = x * cos - sin * y;
          y = x2 * sin + y * cos;
        }
        push(px + nj[0] * d, py + nj[1] * d);
      } else {
        const r = 1 + cosA;
        if (join === 'miter' && r >= miterLim) {
          const q = d / r;
          push(px + (nk[0] + nj[0]) * q, py + (nk[1] + nj[1]) * q);
        } else {
          const dx = Math.tan(Math.atan2(sinA, cosA) / 4);
          push(px + d * (nk[0] - nk[1] * dx), py + d * (nk[1] + nk[0] * dx));
          push(px + d * (nj[0] + nj[1] * dx), py + d * (nj[1] - nj[0] * dx));
        }
      }
      k = j;
    }
    out.push(dest);
  }
  return new M.CrossSection(out, 'Positive');
}

// The outlines of a 2D shape, each marked positive (counter-clockwise) or
// a hole, as OpenSCAD's Polygon2d holds them after Clipper.
function outlinesOf(cs) {
  return cs.toPolygons().filter((o) => o.length >= 3).map((o) => ({ v: o, positive: signedArea(o) > 0 }));
}

// Triangles of a 2D shape: [outline, vertex] pairs, counter-clockwise.
function tessellate(outlines) {
  const flat = [];
  for (let o = 0; o < outlines.length; o++) for (let i = 0; i < outlines[o].v.length; i++) flat.push([o, i]);
  return M.triangulate(outlines.map((o) => o.v), -1).map((t) => t.map((k) => flat[k]));
}

// OpenSCAD's linear_extrude: the same slices, rings and split diagonals.
function linearExtrude(cs, a, line) {
  const height = a.height;
  if (!(height > 0)) return emptySolid();
  const h1 = a.center ? -height / 2 : 0;
  const h2 = a.center ? height / 2 : height;
  const [sx, sy] = a.scale;
  const twist = a.twist;
  const outlines = outlinesOf(cs);
  let slices;
  if (a.slices > 0) slices = a.slices;
  else if (twist !== 0) {
    let rSqr = 0;
    for (const o of outlines) for (const [x, y] of o.v) rSqr = Math.max(rSqr, x * x + y * y);
    slices = (sx === 1 && sy === 1) || sx !== sy
      ? helixSlices(rSqr, height, twist, a.fn, a.fs, a.fa)
      : conicalHelixSlices(rSqr, height, twist, sx, a.fn, a.fs, a.fa);
  } else if (sx !== sy) {
    let dSqr = 0;
    for (const o of outlines) for (const [x, y] of o.v) dSqr = Math.max(dSqr, (x - x * sx) ** 2 + (y - y * sy) ** 2);
    slices = diagonalSlices(dSqr, height, a.fn, a.fs);
  } else slices = 1;

  const mb = new MeshBuilder();
  // level[k][o][i]: the 2D point and the vertex of outline o's point i at slice level k.
  const level = [];
  for (let k = 0; k <= slices; k++) {
    const rot = (twist * k) / slices;
    const h = h1 + ((h2 - h1) * k) / slices;
    const scx = 1 - ((1 - sx) * k) / slices;
    const scy = 1 - ((1 - sy) * k) / slices;
    const c = cosD(-rot), s = sinD(-rot);
    level.push({
      rot, scx, scy,
      rings: outlines.map((o) => o.v.map(([x, y]) => {
        const px = scx * (c * x - s * y), py = scy * (s * x + c * y);
        return { x: px, y: py, id: mb.vertex(px, py, h) };
      })),
    });
  }
  const caps = tessellate(outlines);
  for (const [p, q, r] of caps) {
    const ring = level[0].rings;
    mb.triangle(ring[r[0]][r[1]].id, ring[q[0]][q[1]].id, ring[p[0]][p[1]].id);
  }
  if (sx > 0 && sy > 0) {
    for (const [p, q, r] of caps) {
      const ring = level[slices].rings;
      mb.triangle(ring[p[0]][p[1]].id, ring[q[0]][q[1]].id, ring[r[0]][r[1]].id);
    }
  }
  const norm = (x, y) => Math.sqrt(x * x + y * y);
  for (let k = 0; k < slices; k++) {
    const b = level[k], t = level[k + 1];
    const anyZero = t.scx === 0 || t.scy === 0;
    const anyNonZero = t.scx !== 0 || t.scy !== 0;
    const backTwist = t.rot <= b.rot;
    outlines.forEach((o, oi) => {
      const n = o.v.length;
      const flip = !o.positive !== backTwist;
      for (let i = 1; i <= n; i++) {
        const prev1 = b.rings[oi][i - 1], curr1 = b.rings[oi][i % n];
        const prev2 = t.rings[oi][i - 1], curr2 = t.rings[oi][i % n];
        const l1 = norm(prev1.x - curr2.x, prev1.y - curr2.y);
        const l2 = norm(curr1.x - prev2.x, curr1.y - prev2.y);
        const sign = 2 * Math.abs(l1 - l2) * 1e5 > l1 + l2 ? (l1 < l2 ? -1 : 1) : 0;
        const splitFirst = sign === -1 || (sign === 0 && !flip);
        const second = !anyZero || (anyNonZero && (prev2.x !== curr2.x || prev2.y !== curr2.y));
        if (splitFirst !== anyZero) {
          mb.triangle(curr1.id, curr2.id, prev1.id);
          if (second) mb.triangle(prev2.id, prev1.id, curr2.id);
        } else {
          mb.triangle(curr1.id, prev2.id, prev1.id);
          if (second) mb.triangle(curr1.id, curr2.id, prev2.id);
        }
      }
    });
  }
  return solid(mb.manifold(line, 'linear_extrude'));
}

// OpenSCAD's rotate_extrude: rings from sin/cos in degrees, the same
// starting angle, fragments and faces.
function rotateExtrude(cs, a, line) {
  let angle = a.angle;
  if (angle <= -360 || angle > 360) angle = 360;
  if (angle === 0) return null;
  const outlines = outlinesOf(cs);
  let minX = 0, maxX = 0;
  for (const o of outlines) {
    for (const [x] of o.v) {
      minX = Math.min(minX, x);
      maxX = Math.max(maxX, x);
      if (maxX - minX > maxX && maxX - minX > Math.abs(minX)) refuse(line, 'rotate_extrude() of a shape on both sides of the axis');
    }
  }
  const frags = Math.trunc(Math.max((fragments(maxX - minX, a.fn, a.fs, a.fa) * Math.abs(angle)) / 360, 1));
  const flip = (minX >= 0 && angle > 0 && angle !== 360) || (minX < 0 && (angle < 0 || angle === 360));
  const mb = new MeshBuilder();
  const ringAt = (deg) => outlines.map((o) => {
    const l = o.v.length - 1;
    return o.v.map((_, i) => {
      const [x, y] = o.v[flip ? l - i : i];
      return mb.vertex(x * sinD(deg), x * cosD(deg), y);
    });
  });
  const rings = [ringAt(angle === 360 ? -90 : 90)];
  for (let j = 0; j < frags; j++) {
    const deg = angle === 360 ? -90 + (((j + 1) % frags) * 360) / frags : 90 - ((j + 1) * angle) / frags;
    rings.push(ringAt(deg));
  }
  if (angle !== 360) {
    const at = (ring, [o, i]) => ring[o][flip ? outlines[o].v.length - 1 - i : i];
    for (const tri of tessellate(outlines)) {
      const s = tri.map((v) => at(rings[0], v));
      const e = tri.map((v) => at(rings[frags], v));
      if (flip) { mb.triangle(s[0], s[1], s[2]); mb.triangle(e[2], e[1], e[0]); }
      else { mb.triangle(s[2], s[1], s[0]); mb.triangle(e[0], e[1], e[2]); }
    }
  }
  outlines.forEach((o, oi) => {
    const n = o.v.length;
    for (let j = 0; j < frags; j++) {
      const r0 = rings[j][oi], r1 = rings[j + 1][oi];
      for (let i = 0; i < n; i++) {
        const i1 = (i + 1) % n;
        mb.triangle(r0[i1], r1[i1], r0[i]);
        mb.triangle(r1[i1], r1[i], r0[i]);
      }
    }
  });
  return solid(mb.manifold(line, 'rotate_extrude'));
}

// ------------------------------------------------------------- the tree

const num = (v, d) => (typeof v === 'number' ? v : d);
const bool = (v, d) => (typeof v === 'boolean' ? v : d);
function arg(node, name, position) {
  if (name in node.args.named) return node.args.named[name];
  return position === undefined ? undefined : node.args.pos[position];
}
function specials(node) {
  return { fn: num(arg(node, '$fn'), 0), fa: num(arg(node, '$fa'), 12), fs: num(arg(node, '$fs'), 2) };
}

// Children evaluated; the dimension is the first child's, others ignored
// (OpenSCAD warns and leaves them out).
function childResults(node) {
  const results = [];
  let dim = 0;
  for (const c of node.children) {
    const r = evaluate(c);
    if (!r) { results.push(null); continue; }
    if (!dim) dim = r.dim;
    results.push(r.dim === dim ? r : null);
  }
  return { dim, results };
}

function combine(node, op) {
  const { dim, results } = childResults(node);
  if (!dim) return null;
  const items = results.filter(Boolean).map((r) => (dim === 3 ? r.m : r.cs));
  const cls = dim === 3 ? M.Manifold : M.CrossSection;
  const wrap = dim === 3 ? solid : shape;
  if (op === 'union') {
    if (items.length === 1) return wrap(items[0]);
    return wrap(cls.union(items));
  }
  // A missing operand (2D among 3D, nothing at all) empties an intersection
  // and, in the first place, a difference.
  if (results.length === 1) return results[0] ? wrap(items[0]) : null;
  if (op === 'intersection') {
    if (results.some((r) => !r)) return wrap(dim === 3 ? new MeshBuilder().manifold() : new M.CrossSection([], 'Positive'));
    return wrap(cls.intersection(items));
  }
  if (!results[0]) return wrap(dim === 3 ? new MeshBuilder().manifold() : new M.CrossSection([], 'Positive'));
  if (items.length === 1) return wrap(items[0]);
  return wrap(cls.difference(items));
}

function evaluate(node) {
  if (node.modifier.includes('%') || node.modifier.includes('*')) return null;
  if (node.modifier.includes('!')) refuse(node.line, "the root modifier '!'");
  const a = node.args;
  switch (node.name) {
    case 'group': case 'union': case 'render': case 'color':
      return combine(node, 'union');
    case 'difference':
      return combine(node, 'difference');
    case 'intersection':
      return combine(node, 'intersection');
    case 'multmatrix': {
      const m = arg(node, 'm', 0);
      if (!Array.isArray(m) || m.length < 3 || !m.flat().every(Number.isFinite)) return null;
      const r = combine(node, 'union');
      if (!r) return null;
      const e = (i, j) => num(m[i]?.[j], i === j ? 1 : 0);
      if (r.dim === 3) {
        return solid(r.m.transform([e(0, 0), e(1, 0), e(2, 0), 0, e(0, 1), e(1, 1), e(2, 1), 0,
          e(0, 2), e(1, 2), e(2, 2), 0, e(0, 3), e(1, 3), e(2, 3), 1]));
      }
      return shape(r.cs.transform([e(0, 0), e(1, 0), 0, e(0, 1), e(1, 1), 0, e(0, 3), e(1, 3), 1]));
    }
    case 'cube': {
      let size = arg(node, 'size', 0);
      if (typeof size === 'number') size = [size, size, size];
      if (!Array.isArray(size)) size = [1, 1, 1];
      return cube(size.map((v) => num(v, 1)), bool(arg(node, 'center', 1), false));
    }
    case 'sphere': {
      const s = specials(node);
      let r = num(arg(node, 'r', 0), undefined);
      if (r === undefined) r = typeof arg(node, 'd') === 'number' ? arg(node, 'd') / 2 : 1;
      return sphere(r, s.fn, s.fs, s.fa, node.line);
    }
    case 'cylinder': {
      const s = specials(node);
      const r = num(arg(node, 'r'), 1);
      const r1 = num(arg(node, 'r1', 1), r);
      const r2 = num(arg(node, 'r2', 2), r);
      return cylinder(num(arg(node, 'h', 0), 1), r1, r2, bool(arg(node, 'center', 3), false), s.fn, s.fs, s.fa, node.line);
    }
    case 'polyhedron': {
      const points = arg(node, 'points', 0);
      const faces = arg(node, 'faces', 1) ?? arg(node, 'triangles');
      if (!Array.isArray(points) || !Array.isArray(faces)) refuse(node.line, 'polyhedron() without points and faces');
      return polyhedron(points, faces, node.line);
    }
    case 'import': {
      const file = arg(node, 'file', 0);
      if (typeof file !== 'string') refuse(node.line, 'import() without a file');
      return readMeshFile(resolve(dirname(SOURCE), file), node.line);
    }
    case 'square': {
      let size = arg(node, 'size', 0);
      if (typeof size === 'number') size = [size, size];
      if (!Array.isArray(size)) size = [1, 1];
      const [x, y] = size.map((v) => num(v, 1));
      if (!(x > 0 && y > 0) || !Number.isFinite(x) || !Number.isFinite(y)) return shape(new M.CrossSection([], 'Positive'));
      const c = bool(arg(node, 'center', 1), false);
      const x1 = c ? -x / 2 : 0, y1 = c ? -y / 2 : 0;
      return shape(new M.CrossSection([[[x1, y1], [x1 + x, y1], [x1 + x, y1 + y], [x1, y1 + y]]], 'Positive'));
    }
    case 'circle': {
      const s = specials(node);
      let r = num(arg(node, 'r', 0), undefined);
      if (r === undefined) r = typeof arg(node, 'd') === 'number' ? arg(node, 'd') / 2 : 1;
      if (!(r > 0) || !Number.isFinite(r)) return shape(new M.CrossSection([], 'Positive'));
      return shape(new M.CrossSection([circlePoints(r, fragments(r, s.fn, s.fs, s.fa))], 'Positive'));
    }
    case 'polygon':
      return polygon2d(arg(node, 'points', 0), arg(node, 'paths', 1), node.line);
    case 'offset': {
      const r = combine(node, 'union');
      if (!r) return null;
      if (r.dim !== 2) return null;
      const s = specials(node);
      let delta = 1, join = 'round';
      if (typeof arg(node, 'r', 0) === 'number') delta = arg(node, 'r', 0);
      else if (typeof arg(node, 'delta') === 'number') {
        delta = arg(node, 'delta');
        join = arg(node, 'chamfer') === true ? 'square' : 'miter';
      }
      const n = fragments(Math.abs(delta), s.fn, s.fs, s.fa);
      return shape(offset2d(r.cs, delta, join, Math.abs(delta) * (1 - cosD(180 / n)), 1000000));
    }
    case 'linear_extrude': {
      if (arg(node, 'file') !== undefined) refuse(node.line, 'linear_extrude() of a file');
      const r = combine(node, 'union');
      if (!r || r.dim !== 2) return null;
      let scale = arg(node, 'scale');
      if (typeof scale === 'number') scale = [scale, scale];
      if (!Array.isArray(scale)) scale = [1, 1];
      const s = specials(node);
      return linearExtrude(r.cs, {
        height: num(arg(node, 'height', 0), 100),
        center: bool(arg(node, 'center'), false),
        twist: num(arg(node, 'twist'), 0),
        slices: Math.trunc(num(arg(node, 'slices'), 0)),
        scale: scale.map((v) => Math.max(num(v, 1), 0)),
        ...s,
      }, node.line);
    }
    case 'rotate_extrude': {
      if (arg(node, 'file') !== undefined) refuse(node.line, 'rotate_extrude() of a file');
      const r = combine(node, 'union');
      if (!r || r.dim !== 2) return null;
      return rotateExtrude(r.cs, { angle: num(arg(node, 'angle'), 360), ...specials(node) }, node.line);
    }
    case 'hull': {
      const { dim, results } = childResults(node);
      const items = results.filter(Boolean);
      if (!dim || items.length === 0) return null;
      return dim === 3 ? solid(M.Manifold.hull(items.map((r) => r.m))) : shape(M.CrossSection.hull(items.map((r) => r.cs)));
    }
    case 'minkowski': {
      const { dim, results } = childResults(node);
      if (!dim) return null;
      if (dim === 2) refuse(node.line, 'minkowski() of 2D shapes (Manifold has no 2D Minkowski sum)');
      const items = results.filter((r) => r && !r.m.isEmpty()).map((r) => r.m);
      if (items.length === 0) return null;
      return solid(items.slice(1).reduce((acc, m) => acc.minkowskiSum(m), items[0]));
    }
    default:
      return refuse(node.line, `${node.name}()`);
  }
}

// ------------------------------------------------------------------ main

function writeStl(file, mesh) {
  const n = mesh.triVerts.length / 3;
  const buf = Buffer.alloc(84 + 50 * n);
  buf.write('binary STL from csg2manifold (Manifold)', 0, 'latin1');
  buf.writeUInt32LE(n, 80);
  const p = mesh.vertProperties, s = mesh.numProp, tv = mesh.triVerts;
  let o = 84;
  for (let t = 0; t < n; t++) {
    const a = s * tv[3 * t], b = s * tv[3 * t + 1], c = s * tv[3 * t + 2];
    const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
    const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
    let nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const len = Math.hypot(nx, ny, nz) || 1;
    nx /= len; ny /= len; nz /= len;
    for (const v of [nx, ny, nz, p[a], p[a + 1], p[a + 2], p[b], p[b + 1], p[b + 2], p[c], p[c + 1], p[c + 2]]) {
      buf.writeFloatLE(v, o);
      o += 4;
    }
    o += 2;
  }
  writeFileSync(file, buf);
}

async function main() {
  const argv = process.argv.slice(2);
  let modulePath = process.env.MANIFOLD_JS;
  const files = [];
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === '--module') modulePath = argv[++i];
    else files.push(argv[i]);
  }
  if (files.length !== 2) {
    process.stderr.write('usage: node csg2manifold.mjs [--module PATH/manifold.js] IN.csg OUT.stl\n');
    process.exit(64);
  }
  const [input, output] = files;
  SOURCE = input;
  const secs = (t) => Number(((performance.now() - t) / 1000).toFixed(4));

  let t = performance.now();
  const wasm = await import(modulePath ? pathToFileURL(resolve(modulePath)).href : 'manifold-3d');
  M = await wasm.default();
  M.setup();
  const load = secs(t);

  t = performance.now();
  const text = readFileSync(input, 'utf8');
  const root = { name: 'group', args: { pos: [], named: {} }, children: new Parser(tokenize(text)).statements('eof'), line: 1, modifier: '' };
  const parse = secs(t);

  t = performance.now();
  const result = evaluate(root);
  if (result && result.dim === 2) refuse(1, 'a 2D result (an STL needs a solid)');
  const m = result ? result.m : new MeshBuilder().manifold();
  const build = secs(t);

  t = performance.now();
  const mesh = m.getMesh();
  const status = m.status();
  const evaluated = secs(t);
  if (status !== 'NoError') throw new Error(`Manifold: ${status}`);

  t = performance.now();
  writeStl(output, mesh);
  const write = secs(t);

  process.stderr.write(JSON.stringify({
    load_s: load, parse_s: parse, build_s: build, evaluate_s: evaluated, write_s: write,
    triangles: mesh.triVerts.length / 3, volume: m.volume(),
  }) + '\n');
}

main().catch((e) => {
  if (e instanceof Refusal) {
    process.stderr.write(e.message + '\n');
    process.exit(2);
  }
  process.stderr.write(`${SOURCE}: ${e?.message ?? e}\n`);
  process.exit(1);
});
