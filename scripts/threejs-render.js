// three.js's own rendering of a glTF at mvr's cameras (issue 66's
// reference): Debian's chromium, driven headless by playwright-core, draws
// the file with three.js r187's GLTFLoader and MeshStandardMaterial at
// every view's K and V from an mvr manifest (times from_file), with mvr's
// ambient light added (its colour A is three.js's AmbientLight of
// intensity pi A), the tone map named (default none) and sRGB output, no
// anti-aliasing. --exposure EV multiplies the lights and emission by 2^EV.
// --environment FILE.exr: scene.environment, an equirectangular map
// (EquirectangularReflectionMapping, PMREM'd by three.js), of intensity
// --environment-intensity K times 2^EV, turned --environment-rotation DEG
// about +y.
// Writes OUT/view_NNNN.png, one per manifest view.
//
//   node scripts/threejs-render.js MODEL MANIFEST OUT [--ambient A] [--exposure EV] [--default-light 1]
//                                  [--tonemap none|aces|agx|neutral] [--environment FILE.exr]
//                                  [--environment-intensity K] [--environment-rotation DEG]
// (--default-light 1: mvr's light for a file that has none, added too)
// THREE_NODE_MODULES: a folder holding three and playwright-core
// (scripts/threejs-pbr installs them).
'use strict';
const fs = require('fs');
const http = require('http');
const path = require('path');

const modules = process.env.THREE_NODE_MODULES;
const { chromium } = require(path.join(modules, 'playwright-core'));

function options(args) {
  const [model, manifest, out, ...rest] = args;
  const o = { model, manifest, out, ambient: 0.15, exposure: 0, 'default-light': 0, tonemap: 'none',
             environment: '', 'environment-intensity': 1, 'environment-rotation': 0 };
  for (let i = 0; i < rest.length; i += 2) {
    const key = rest[i].replace(/^--/, '');
    o[key] = key === 'tonemap' || key === 'environment' ? rest[i + 1] : Number(rest[i + 1]);
  }
  return o;
}

// The page: three.js as modules, a render function the driver calls.
const page = `<!doctype html><html><body style="margin:0">
<script type="importmap">{"imports": {"three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/"}}</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { EXRLoader } from 'three/addons/loaders/EXRLoader.js';
window.renderViews = async (o) => {
  const gltf = await new GLTFLoader().loadAsync('/model/' + o.modelName);
  const scene = new THREE.Scene(), k = Math.pow(2, o.exposure);
  scene.add(gltf.scene);
  scene.traverse((n) => {
    if (n.isLight) n.intensity *= k;
    if (n.isMesh) for (const m of [].concat(n.material)) if (m.emissiveIntensity !== undefined) m.emissiveIntensity *= k;
  });
  scene.add(new THREE.AmbientLight(0xffffff, Math.PI * o.ambient * k));
  if (o.environment) {
    const map = await new EXRLoader().loadAsync('/environment/' + o.environment);
    map.mapping = THREE.EquirectangularReflectionMapping;
    scene.environment = map;
    scene.environmentIntensity = o.environmentIntensity * k;
    scene.environmentRotation.y = o.environmentRotation * Math.PI / 180;
  }
  if (o.defaultLight) {  // mvr's light for a file without lights: colour 0.85 down (-0.4, -0.6, -1)
    const sun = new THREE.DirectionalLight(0xffffff, Math.PI * 0.85 * k);
    sun.position.set(0.4, 0.6, 1.0);
    scene.add(sun);
  }
  const canvas = document.createElement('canvas');
  document.body.appendChild(canvas);
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, alpha: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(o.width, o.height, false);
  renderer.setClearColor(0x000000, 0);
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.toneMapping = { none: THREE.NoToneMapping, aces: THREE.ACESFilmicToneMapping, agx: THREE.AgXToneMapping,
                           neutral: THREE.NeutralToneMapping }[o.tonemap];
  const bounds = new THREE.Box3().setFromObject(scene), sphere = bounds.getBoundingSphere(new THREE.Sphere());
  const camera = new THREE.PerspectiveCamera();
  camera.matrixAutoUpdate = false;
  const F = new THREE.Matrix4();
  if (o.fromFile) F.set(...o.fromFile.flat());
  const images = [];
  for (const view of o.views) {
    // OpenCV's camera axes (y down, z ahead) to GL's (y up, z behind).
    const V = new THREE.Matrix4().set(...view.V.flat());
    const toCamera = new THREE.Matrix4().makeScale(1, -1, -1).multiply(V).multiply(F);
    camera.matrix.copy(toCamera).invert();
    camera.updateMatrixWorld(true);
    const centre = sphere.center.clone().applyMatrix4(toCamera);
    const near = Math.max(-centre.z - 2 * sphere.radius, 1e-3 * sphere.radius), far = -centre.z + 2 * sphere.radius;
    const [[fx, s, cx], [, fy, cy]] = view.K, w = o.width, h = o.height;
    camera.projectionMatrix.set(2 * fx / w, -2 * s / w, 1 - 2 * cx / w, 0,
                                0, 2 * fy / h, 2 * cy / h - 1, 0,
                                0, 0, (far + near) / (near - far), 2 * far * near / (near - far),
                                0, 0, -1, 0);
    camera.projectionMatrixInverse.copy(camera.projectionMatrix).invert();
    renderer.render(scene, camera);
    images.push(canvas.toDataURL('image/png'));
  }
  return images;
};
window.ready = true;
</script></body></html>`;

function serve(o) {
  const roots = { '/three/': path.join(modules, 'three') + '/', '/model/': path.dirname(path.resolve(o.model)) + '/' };
  if (o.environment) roots['/environment/'] = path.dirname(path.resolve(o.environment)) + '/';
  const types = { '.js': 'text/javascript', '.html': 'text/html', '.png': 'image/png', '.jpg': 'image/jpeg' };
  return http.createServer((req, res) => {
    const url = decodeURIComponent(req.url.split('?')[0]);
    if (url === '/') return res.end(page);
    const root = Object.keys(roots).find((r) => url.startsWith(r));
    const file = root && path.join(roots[root], url.slice(root.length));
    if (!file || !file.startsWith(roots[root]) || !fs.existsSync(file)) {
      res.statusCode = 404;
      return res.end();
    }
    res.setHeader('Content-Type', types[path.extname(file)] || 'application/octet-stream');
    fs.createReadStream(file).pipe(res);
  });
}

async function main() {
  const o = options(process.argv.slice(2));
  const manifest = JSON.parse(fs.readFileSync(o.manifest, 'utf8'));
  const server = serve(o);
  await new Promise((r) => server.listen(0, '127.0.0.1', r));
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  try {
    const tab = await browser.newPage();
    tab.on('pageerror', (e) => console.error('threejs-render: page: ' + e.message));
    await tab.goto('http://127.0.0.1:' + server.address().port + '/');
    await tab.waitForFunction(() => window.ready === true);
    const images = await tab.evaluate((args) => window.renderViews(args), {
      modelName: path.basename(o.model), width: manifest.width, height: manifest.height, views: manifest.cameras.views,
      fromFile: manifest.cameras.from_file, ambient: o.ambient, exposure: o.exposure, defaultLight: o['default-light'] > 0, tonemap: o.tonemap,
      environment: o.environment && path.basename(o.environment), environmentIntensity: o['environment-intensity'],
      environmentRotation: o['environment-rotation'],
    });
    fs.mkdirSync(o.out, { recursive: true });
    images.forEach((url, i) => fs.writeFileSync(path.join(o.out, 'view_' + String(i).padStart(4, '0') + '.png'),
      Buffer.from(url.slice(url.indexOf(',') + 1), 'base64')));
  } finally {
    await browser.close();
    server.close();
  }
}

main().catch((e) => { console.error('threejs-render: ' + e.message); process.exit(1); });
