// PSNR of RGB over the pixels two renders both cover (alpha >= 128 in
// each): mvr's view against a reference's (scripts/threejs-pbr).
//   node scripts/image-psnr.js OURS.png REFERENCE.png    prints "PSNR_DB COVERED_PIXELS"
'use strict';
const { readPng } = require('./png.js');

function psnr(a, b) {
  if (a.width !== b.width || a.height !== b.height) throw new Error('the images differ in size');
  let sum = 0, n = 0;
  const alpha = (img, i) => (img.channels === 4 ? img.pixels[i * 4 + 3] : img.channels === 2 ? img.pixels[i * 2 + 1] : 255);
  const rgb = (img, i, k) => img.pixels[i * img.channels + (img.channels >= 3 ? k : 0)];
  for (let i = 0; i < a.width * a.height; ++i) {
    if (alpha(a, i) < 128 || alpha(b, i) < 128) continue;
    for (let k = 0; k < 3; ++k) sum += (rgb(a, i, k) - rgb(b, i, k)) ** 2;
    ++n;
  }
  const mse = n ? sum / (3 * n) : 0;
  return [mse > 0 ? 10 * Math.log10(255 * 255 / mse) : Infinity, n];
}

const [ours, reference] = process.argv.slice(2);
const [db, n] = psnr(readPng(ours), readPng(reference));
console.log(db.toFixed(2) + ' ' + n);
