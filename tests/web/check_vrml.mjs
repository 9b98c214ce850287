// Parses VRML97 files with three.js's VRMLLoader (an independent parser) and
// prints, per file, what it built: one record per mesh with its vertex and
// face counts, distinct positions, whether it has uv and normals, its side
// and colour. Used by tests/io/vrml/test_web.cpp.
//
//   node check_vrml.mjs a.wrl b.wrl   ->   [{"file":"a.wrl","ok":true,"meshes":[...]}, ...]
//
// three's lexer matches node names in list order, so "CoordinateInterpolator"
// lexes as "Coordinate" + an identifier and the parser stops (three.js PR
// #19417: "not able to parse the Interpolator syntax"). When a file fails that
// way it is parsed again by the same loader with one change: node names
// matched longest first. The record then says "lexer_fix": true.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';
import { VRMLLoader } from 'three/examples/jsm/loaders/VRMLLoader.js';

// The same loader with node names matched longest first (a copy beside the original, imports made absolute).
async function fixedLoader() {
  const src = createRequire(import.meta.url).resolve('three/examples/jsm/loaders/VRMLLoader.js');
  let text = fs.readFileSync(src, 'utf8');
  const before = "new RegExp( nodeTypes.join( '|' ) )";
  if (!text.includes(before)) return null;
  text = text.replace(before, "new RegExp( [ ...nodeTypes ].sort( ( a, b ) => b.length - a.length ).join( '|' ) )");
  text = text.replace(/from '(\.[^']+)'/g, (m, rel) => `from '${pathToFileURL(path.resolve(path.dirname(src), rel)).href}'`);
  text = text.replace(/from 'three'/g, `from '${import.meta.resolve('three')}'`);
  const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'vgd-vrmlloader-'));
  const file = path.join(tmp, 'VRMLLoader.mjs');
  fs.writeFileSync(file, text);
  try {
    return (await import(pathToFileURL(file).href)).VRMLLoader;
  } finally {
    fs.rmSync(tmp, { recursive: true, force: true });
  }
}

// ImageTexture asks for an <img>; under node no image is loaded, so a stand-in is enough.
if (!globalThis.document) {
  globalThis.document = {
    createElementNS: () => ({ addEventListener() {}, removeEventListener() {}, setAttribute() {}, style: {} }),
  };
}

const results = [];
for (const file of process.argv.slice(2)) {
  const record = { file, ok: false, meshes: [] };
  try {
    const text = fs.readFileSync(file, 'utf8');
    let scene;
    const errors = console.error;
    try {
      console.error = () => {};  // the loader prints the parser's exceptions before throwing
      scene = new VRMLLoader().parse(text, '');
    } catch (e) {
      const Fixed = /(Coordinate|Color|Normal)Interpolator/.test(text) ? await fixedLoader() : null;
      if (!Fixed) throw e;
      scene = new Fixed().parse(text, '');
      record.lexer_fix = true;
    } finally {
      console.error = errors;
    }
    scene.traverse((o) => {
      if (!o.isMesh) return;
      const g = o.geometry;
      const pos = g.attributes.position;
      const distinct = new Set();
      for (let i = 0; i < pos.count; i++)
        distinct.add(`${pos.getX(i).toFixed(4)} ${pos.getY(i).toFixed(4)} ${pos.getZ(i).toFixed(4)}`);
      const uv = g.attributes.uv;
      let uvMin = null, uvMax = null;
      if (uv) {
        uvMin = [Infinity, Infinity], uvMax = [-Infinity, -Infinity];
        for (let i = 0; i < uv.count; i++) {
          uvMin = [Math.min(uvMin[0], uv.getX(i)), Math.min(uvMin[1], uv.getY(i))];
          uvMax = [Math.max(uvMax[0], uv.getX(i)), Math.max(uvMax[1], uv.getY(i))];
        }
      }
      const c = o.material && o.material.color;
      record.meshes.push({
        name: o.name,
        vertices: pos.count,
        distinct_vertices: distinct.size,
        faces: g.index ? g.index.count / 3 : pos.count / 3,
        uv: !!uv,
        uv_min: uvMin,
        uv_max: uvMax,
        normal: !!g.attributes.normal,
        double_sided: o.material ? o.material.side === 2 : false,
        color: c ? [c.r, c.g, c.b] : null,
      });
    });
    record.ok = true;
  } catch (e) {
    record.error = String((e && e.message) || e);
  }
  results.push(record);
}
console.log(JSON.stringify(results));
