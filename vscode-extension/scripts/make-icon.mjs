// Draws images/icon.png (128x128 RGBA): a small box truck, a chassis box on two wheels, on a
// rounded dark-blue tile. No dependencies: shapes are sampled 4x4 per pixel and written with zlib.
//   node scripts/make-icon.mjs
import { writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { deflateSync } from 'node:zlib';

const SIZE = 128;
const SS = 4; // samples per axis per pixel
const OUT = join(dirname(fileURLToPath(import.meta.url)), '..', 'images', 'icon.png');

const TILE = [24, 39, 64];
const BODY = [242, 140, 40];
const WINDOW = [24, 39, 64];
const WHEEL = [236, 240, 245];
const HUB = [24, 39, 64];
const GROUND = [90, 190, 200];

function roundedRect(x, y, x0, y0, x1, y1, r) {
  const cx = Math.min(Math.max(x, x0 + r), x1 - r);
  const cy = Math.min(Math.max(y, y0 + r), y1 - r);
  return (x - cx) ** 2 + (y - cy) ** 2 <= r * r && x >= x0 && x <= x1 && y >= y0 && y <= y1;
}
const disc = (x, y, cx, cy, r) => (x - cx) ** 2 + (y - cy) ** 2 <= r * r;

/** Colour at a point, or null (transparent). Later shapes paint over earlier ones. */
function sample(x, y) {
  let c = null;
  if (roundedRect(x, y, 0, 0, SIZE, SIZE, 22)) c = TILE;
  if (roundedRect(x, y, 14, 96, 114, 102, 3)) c = GROUND; // the ground line
  if (roundedRect(x, y, 18, 34, 82, 80, 6)) c = BODY; // cargo box
  if (roundedRect(x, y, 84, 50, 110, 80, 6)) c = BODY; // cab
  if (roundedRect(x, y, 90, 55, 104, 66, 3)) c = WINDOW; // cab window
  for (const cx of [38, 94]) {
    if (disc(x, y, cx, 82, 14)) c = WHEEL;
    if (disc(x, y, cx, 82, 5)) c = HUB;
  }
  return c;
}

const raw = Buffer.alloc(SIZE * (1 + SIZE * 4));
for (let py = 0; py < SIZE; py++) {
  const row = py * (1 + SIZE * 4);
  raw[row] = 0; // filter: none
  for (let px = 0; px < SIZE; px++) {
    let r = 0, g = 0, b = 0, a = 0;
    for (let sy = 0; sy < SS; sy++) {
      for (let sx = 0; sx < SS; sx++) {
        const c = sample(px + (sx + 0.5) / SS, py + (sy + 0.5) / SS);
        if (c) {
          r += c[0]; g += c[1]; b += c[2]; a += 1;
        }
      }
    }
    const o = row + 1 + px * 4;
    if (a > 0) {
      raw[o] = Math.round(r / a);
      raw[o + 1] = Math.round(g / a);
      raw[o + 2] = Math.round(b / a);
    }
    raw[o + 3] = Math.round((255 * a) / (SS * SS));
  }
}

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(buf) {
  let c = 0xffffffff;
  for (const byte of buf) c = CRC_TABLE[(c ^ byte) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}
function chunk(type, data) {
  const len = Buffer.alloc(4);
  len.writeUInt32BE(data.length);
  const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
  const crc = Buffer.alloc(4);
  crc.writeUInt32BE(crc32(body));
  return Buffer.concat([len, body, crc]);
}

const ihdr = Buffer.alloc(13);
ihdr.writeUInt32BE(SIZE, 0);
ihdr.writeUInt32BE(SIZE, 4);
ihdr[8] = 8; // bit depth
ihdr[9] = 6; // colour type RGBA
const png = Buffer.concat([
  Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
  chunk('IHDR', ihdr),
  chunk('IDAT', deflateSync(raw, { level: 9 })),
  chunk('IEND', Buffer.alloc(0)),
]);
writeFileSync(OUT, png);
console.log(`icon: wrote ${OUT} (${png.length} bytes)`);
