// Images for a person to look at when a check fails: an RGB PNG (8-bit, already encoded) with the
// compared regions outlined in magenta. Shared by check.mjs and html_check.mjs.
import { writeFileSync } from 'node:fs';
import zlib from 'node:zlib';

// `rgb`: size * size * 3 bytes, row 0 at the top; `boxes`: [x0, y0, x1, y1] in pixels.
export function writeDebugPng(file, size, rgb, boxes) {
  for (const [x0, y0, x1, y1] of boxes)
    for (let y = y0 - 1; y <= y1; ++y)
      for (let x = x0 - 1; x <= x1; ++x)
        if (y === y0 - 1 || y === y1 || x === x0 - 1 || x === x1) rgb.set([255, 0, 255], (y * size + x) * 3);
  const rows = [];
  for (let y = 0; y < size; ++y) rows.push(Buffer.from([0]), rgb.subarray(y * size * 3, (y + 1) * size * 3));
  const chunk = (type, data) => {
    const b = Buffer.alloc(12 + data.length);
    b.writeUInt32BE(data.length, 0);
    b.write(type, 4, 'ascii');
    data.copy(b, 8);
    b.writeUInt32BE(zlib.crc32(b.subarray(4, 8 + data.length)), 8 + data.length);
    return b;
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(size, 0);
  ihdr.writeUInt32BE(size, 4);
  ihdr.set([8, 2, 0, 0, 0], 8);
  writeFileSync(file, Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
    chunk('IDAT', zlib.deflateSync(Buffer.concat(rows))), chunk('IEND', Buffer.alloc(0))]));
}
