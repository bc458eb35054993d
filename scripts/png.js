// PNG reading for the reference scripts (scripts/threejs-*.js): 8-bit,
// non-interlaced, any colour type but palette.
'use strict';
const fs = require('fs');
const zlib = require('zlib');

// 8-bit non-interlaced PNG to {width, height, channels, pixels}.
function readPng(file) {
  const bytes = fs.readFileSync(file);
  let width = 0, height = 0, type = 0;
  const idat = [];
  for (let at = 8; at < bytes.length;) {
    const length = bytes.readUInt32BE(at), name = bytes.toString('latin1', at + 4, at + 8);
    const body = bytes.subarray(at + 8, at + 8 + length);
    if (name === 'IHDR') {
      width = body.readUInt32BE(0), height = body.readUInt32BE(4), type = body[9];
      if (body[8] !== 8 || body[12] !== 0) throw new Error(file + ': only 8-bit non-interlaced PNG');
    } else if (name === 'IDAT') idat.push(body);
    at += 12 + length;
  }
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[type];
  if (!channels) throw new Error(file + ': PNG colour type ' + type);
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels, pixels = Buffer.alloc(stride * height);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)], row = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; ++x) {
      const a = x >= channels ? pixels[y * stride + x - channels] : 0;
      const b = y > 0 ? pixels[(y - 1) * stride + x] : 0;
      const c = x >= channels && y > 0 ? pixels[(y - 1) * stride + x - channels] : 0;
      const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
      const predictor = [0, a, b, (a + b) >> 1, pa <= pb && pa <= pc ? a : pb <= pc ? b : c][filter];
      pixels[y * stride + x] = (row[x] + predictor) & 255;
    }
  }
  return { width, height, channels, pixels };
}

module.exports = { readPng };
