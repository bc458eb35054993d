// An independent pose and silhouette of a glTF at time t (issue 56's
// check): three.js (Debian's libjs-three) loads the file, its
// AnimationMixer plays every clip to t, and each mesh's vertices are
// morphed and skinned as three's vertex shader does; the triangles are
// projected with a view's K and V from an mvr manifest and filled at the
// pixel centres. Prints, per view, the IoU of that silhouette against
// the alpha (>= 128) of mvr's view image.
//
//   node scripts/threejs-silhouette.js MODEL TIME MANIFEST VIEW_PNG...
//   (VIEW_PNG i is the manifest's view i)
'use strict';
const fs = require('fs');
const path = require('path');
const vm = require('vm');
const zlib = require('zlib');
const { readPng } = require('./png.js');

const threeDir = process.env.THREE_DIR || '/usr/share/javascript/three';
global.THREE = require(path.join(threeDir, 'three.js'));
vm.runInThisContext(fs.readFileSync(path.join(threeDir, 'examples/js/loaders/GLTFLoader.js'), 'utf8'));

// No XMLHttpRequest or DOM here: buffers come from the file system and
// images are left empty (a silhouette needs no texels).
THREE.FileLoader.prototype.load = function (url, onLoad, onProgress, onError) {
  try {
    const bytes = url.startsWith('data:') ? Buffer.from(url.slice(url.indexOf(',') + 1), 'base64')
      : fs.readFileSync(decodeURIComponent(url));
    const data = this.responseType === 'arraybuffer'
      ? bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length) : bytes.toString('utf8');
    setImmediate(() => onLoad(data));
  } catch (e) {
    if (onError) onError(e); else throw e;
  }
};
THREE.ImageLoader.prototype.load = function (url, onLoad) {
  const image = { width: 1, height: 1 };
  setImmediate(() => onLoad && onLoad(image));
  return image;
};

// Component k of vertex i as the GPU reads it (r111's getX does not
// undo a normalized integer attribute), interleaved or not.
function component(attribute, i, k) {
  const a = attribute.array, value = attribute.isInterleavedBufferAttribute
    ? a[i * attribute.data.stride + attribute.offset + k] : a[i * attribute.itemSize + k];
  if (!attribute.normalized) return value;
  const max = { Uint8Array: 255, Uint16Array: 65535, Int8Array: 127, Int16Array: 32767 }[a.constructor.name] || 1;
  return Math.max(value / max, -1);
}

// World positions of a mesh's vertices as three draws them.
function posedPositions(mesh) {
  const g = mesh.geometry, base = g.attributes.position, n = base.count;
  const influences = mesh.morphTargetInfluences || [];
  const morphs = (g.morphAttributes.position || []);
  const out = new Float32Array(3 * n), v = new THREE.Vector3(), d = new THREE.Vector3();
  const skinned = mesh.isSkinnedMesh, s = new THREE.Vector4(), sum = new THREE.Vector4(), t = new THREE.Vector4();
  const bone = new THREE.Matrix4();
  for (let i = 0; i < n; ++i) {
    v.fromBufferAttribute(base, i);
    for (let k = 0; k < morphs.length; ++k) {
      if (!influences[k]) continue;
      d.fromBufferAttribute(morphs[k], i);
      if (!g.morphTargetsRelative) d.sub(new THREE.Vector3().fromBufferAttribute(base, i));
      v.addScaledVector(d, influences[k]);
    }
    if (skinned) {
      s.set(v.x, v.y, v.z, 1).applyMatrix4(mesh.bindMatrix);
      sum.set(0, 0, 0, 0);
      for (let k = 0; k < 4; ++k) {
        const w = component(g.attributes.skinWeight, i, k);
        if (w === 0) continue;
        bone.fromArray(mesh.skeleton.boneMatrices, 16 * component(g.attributes.skinIndex, i, k));
        sum.addScaledVector(t.copy(s).applyMatrix4(bone), w);
      }
      sum.applyMatrix4(mesh.bindMatrixInverse);
      v.set(sum.x, sum.y, sum.z);
    }
    v.applyMatrix4(mesh.matrixWorld);
    out.set([v.x, v.y, v.z], 3 * i);
  }
  return out;
}

// Fills the triangles (world positions) into a width x height mask at
// the pixel centres, by K and V times from_file (OpenCV's axes, mvr's
// manifest: the file's coordinates to the view's).
function silhouette(meshes, view, fromFile, width, height) {
  const K = view.K, mask = new Uint8Array(width * height);
  const V = [0, 1, 2, 3].map(r => [0, 1, 2, 3].map(c => [0, 1, 2, 3].reduce((sum, k) => sum + view.V[r][k] * fromFile[k][c], 0)));
  for (const { positions, index } of meshes) {
    const n = positions.length / 3, px = new Float64Array(2 * n);
    let behind = false;
    for (let i = 0; i < n; ++i) {
      const p = [positions[3 * i], positions[3 * i + 1], positions[3 * i + 2], 1];
      const c = [0, 1, 2].map(r => V[r][0] * p[0] + V[r][1] * p[1] + V[r][2] * p[2] + V[r][3]);
      if (c[2] <= 0) behind = true;
      px[2 * i] = K[0][0] * c[0] / c[2] + K[0][1] * c[1] / c[2] + K[0][2];
      px[2 * i + 1] = K[1][1] * c[1] / c[2] + K[1][2];
    }
    if (behind) throw new Error('a vertex is behind the camera');
    const triangles = index ? index.length / 3 : n / 3;
    for (let t = 0; t < triangles; ++t) {
      const [a, b, c] = [0, 1, 2].map(k => index ? index[3 * t + k] : 3 * t + k);
      fillTriangle(mask, width, height, px[2 * a], px[2 * a + 1], px[2 * b], px[2 * b + 1], px[2 * c], px[2 * c + 1]);
    }
  }
  return mask;
}

function fillTriangle(mask, width, height, ax, ay, bx, by, cx, cy) {
  const area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  if (area === 0) return;
  const x0 = Math.max(0, Math.floor(Math.min(ax, bx, cx))), x1 = Math.min(width - 1, Math.ceil(Math.max(ax, bx, cx)));
  const y0 = Math.max(0, Math.floor(Math.min(ay, by, cy))), y1 = Math.min(height - 1, Math.ceil(Math.max(ay, by, cy)));
  for (let y = y0; y <= y1; ++y)
    for (let x = x0; x <= x1; ++x) {
      const px = x + 0.5, py = y + 0.5;
      const e0 = ((bx - ax) * (py - ay) - (by - ay) * (px - ax)) / area;
      const e1 = ((cx - bx) * (py - by) - (cy - by) * (px - bx)) / area;
      const e2 = ((ax - cx) * (py - cy) - (ay - cy) * (px - cx)) / area;
      if (e0 >= 0 && e1 >= 0 && e2 >= 0) mask[y * width + x] = 1;
    }
}

// Writes an RGB PNG: red ours only, green mvr's only, white both (for a look).
function writeComparison(file, width, height, ours, theirs) {
  const raw = Buffer.alloc((3 * width + 1) * height);
  for (let y = 0; y < height; ++y)
    for (let x = 0; x < width; ++x) {
      const p = y * width + x, at = y * (3 * width + 1) + 1 + 3 * x;
      raw[at] = ours[p] ? 255 : 0, raw[at + 1] = theirs[p] ? 255 : 0, raw[at + 2] = ours[p] && theirs[p] ? 255 : 0;
    }
  const crcTable = Array.from({ length: 256 }, (_, n) => {
    for (let k = 0; k < 8; ++k) n = n & 1 ? 0xedb88320 ^ (n >>> 1) : n >>> 1;
    return n >>> 0;
  });
  const chunk = (name, body) => {
    const head = Buffer.alloc(8);
    head.writeUInt32BE(body.length, 0), head.write(name, 4, 'latin1');
    let crc = 0xffffffff;
    for (const b of Buffer.concat([head.subarray(4), body])) crc = crcTable[(crc ^ b) & 255] ^ (crc >>> 8);
    const tail = Buffer.alloc(4);
    tail.writeUInt32BE((crc ^ 0xffffffff) >>> 0, 0);
    return Buffer.concat([head, body, tail]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0), ihdr.writeUInt32BE(height, 4), ihdr[8] = 8, ihdr[9] = 2;
  fs.writeFileSync(file, Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
    chunk('IDAT', zlib.deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]));
}

function main() {
  const [model, time, manifestFile, ...pngs] = process.argv.slice(2);
  const manifest = JSON.parse(fs.readFileSync(manifestFile, 'utf8'));
  const bytes = fs.readFileSync(model);
  const data = model.endsWith('.glb') ? bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length) : bytes.toString('utf8');
  new THREE.GLTFLoader().parse(data, path.dirname(path.resolve(model)) + '/', gltf => {
    const mixer = new THREE.AnimationMixer(gltf.scene);
    for (const clip of gltf.animations) mixer.clipAction(clip).play();
    mixer.setTime(Number(time));
    gltf.scene.updateMatrixWorld(true);
    const meshes = [];
    gltf.scene.traverse(o => {
      if (!o.isMesh || !o.visible) return;
      if (o.isSkinnedMesh) o.skeleton.update();
      meshes.push({ positions: posedPositions(o), index: o.geometry.index && o.geometry.index.array });
    });
    const { width, height } = manifest;
    const fromFile = manifest.cameras.from_file || [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]];
    pngs.forEach((png, i) => {
      const image = readPng(png), ours = silhouette(meshes, manifest.cameras.views[i], fromFile, width, height);
      if (image.width !== width || image.height !== height) throw new Error(png + ': not the manifest\'s size');
      if (image.channels % 2) throw new Error(png + ': no alpha channel');
      const theirs = new Uint8Array(width * height);
      let both = 0, either = 0;
      for (let p = 0; p < width * height; ++p) {
        theirs[p] = image.pixels[p * image.channels + image.channels - 1] >= 128 ? 1 : 0;
        both += theirs[p] & ours[p], either += theirs[p] | ours[p];
      }
      if (process.env.COMPARISON_DIR)
        writeComparison(path.join(process.env.COMPARISON_DIR, 'iou_' + path.basename(png)), width, height, ours, theirs);
      console.log(`${path.basename(png)} iou ${(either ? both / either : 1).toFixed(4)} (${both} of ${either} pixels)`);
    });
  }, e => { console.error(model + ': ' + e.message); process.exit(1); });
}

main();
