// Images for a person to look at when a check fails: an RGB PNG (8-bit, already encoded) with the
// compared regions outlined in magenta. Shared by check.mjs, html_check.mjs and
// directional_check.mjs (which also writes its scene's normal map with writePng).
import { writeFileSync } from 'node:fs';
import zlib from 'node:zlib';

// `rgb`: size * size * 3 bytes, row 0 at the top; `boxes`: [x0, y0, x1, y1] in pixels.
export function writeDebugPng(file, size, rgb, boxes) {
  for (const [x0, y0, x1, y1] of boxes)
    for (let y = y0 - 1; y <= y1; ++y)
      for (let x = x0 - 1; x <= x1; ++x)
        if (y === y0 - 1 || y === y1 || x === x0 - 1 || x === x1) rgb.set([255, 0, 255], (y * size + x) * 3);
  writePng(file, size, size, rgb);
}

// An 8-bit RGB PNG of `rgb` (width * height * 3 bytes, row 0 at the top), as it is.
export function writePng(file, width, height, rgb) {
  const rows = [];
  for (let y = 0; y < height; ++y) rows.push(Buffer.from([0]), rgb.subarray(y * width * 3, (y + 1) * width * 3));
  const chunk = (type, data) => {
    const b = Buffer.alloc(12 + data.length);
    b.writeUInt32BE(data.length, 0);
    b.write(type, 4, 'ascii');
    data.copy(b, 8);
    b.writeUInt32BE(zlib.crc32(b.subarray(4, 8 + data.length)), 8 + data.length);
    return b;
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr.set([8, 2, 0, 0, 0], 8);
  writeFileSync(file, Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
    chunk('IDAT', zlib.deflateSync(Buffer.concat(rows))), chunk('IEND', Buffer.alloc(0))]));
}
