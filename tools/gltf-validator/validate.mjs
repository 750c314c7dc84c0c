// Runs the Khronos glTF validator (npm package gltf-validator) on one .glb or .gltf file, prints
// the validation report as JSON on stdout and exits 0 when it has no errors, 1 when it has, 2 when
// the file cannot be read. Warnings and infos do not fail. Usage: node validate.mjs FILE
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const file = process.argv[2];
if (!file) {
  console.error('usage: node validate.mjs FILE.glb');
  process.exit(2);
}
let bytes;
try {
  bytes = new Uint8Array(await readFile(file));
} catch (e) {
  console.error(`validate.mjs: ${file}: ${e.message}`);
  process.exit(2);
}
const report = await validator.validateBytes(bytes, {
  uri: path.basename(file),
  maxIssues: 0,  // unlimited: a truncated report would leave the counts short
  writeTimestamp: false,
  // External resources (a .gltf with separate .bin or images) are read beside the file.
  externalResourceFunction: (uri) =>
    readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
});
console.log(JSON.stringify(report, null, 2));
// exitCode, not exit(): stdout to a pipe is written asynchronously, and exit() would cut a long
// report short.
process.exitCode = report.issues.numErrors > 0 ? 1 : 0;
