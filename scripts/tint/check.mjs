// Gives WGSL modules to Tint, Dawn's WGSL compiler (the one Chrome ships),
// through the npm package `webgpu` (Dawn for Node), and reports every error
// and warning with its file, line and column and the line's text.
//
//   node check.mjs DIR_OR_FILE...
//
// Every `*.wgsl` file of a directory is checked. Prints one line per
// message, then `tint: N modules checked, M rejected` and the adapter;
// exits 1 if any module has an error or a warning, 2 if there is no
// adapter or no module. tests/tests/tint.rs runs it.
import { create, globals } from 'webgpu';
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join } from 'node:path';

Object.assign(globalThis, globals);

function modules(args) {
  const files = [];
  for (const a of args) {
    if (statSync(a).isDirectory()) {
      for (const f of readdirSync(a).sort()) {
        if (f.endsWith('.wgsl')) files.push(join(a, f));
      }
    } else {
      files.push(a);
    }
  }
  return files;
}

const files = modules(process.argv.slice(2));
if (files.length === 0) {
  console.error('tint: no .wgsl files given');
  process.exit(2);
}
// Shader-module creation runs Tint's parser and resolver whichever backend
// Dawn picks; Vulkan is the one this machine has (lavapipe).
const gpu = create(['backend=vulkan']);
const adapter = await gpu.requestAdapter();
if (!adapter) {
  console.error('tint: Dawn found no adapter (backend=vulkan)');
  process.exit(2);
}
const device = await adapter.requestDevice();
let rejected = 0;
for (const file of files) {
  const code = readFileSync(file, 'utf8');
  const lines = code.split('\n');
  device.pushErrorScope('validation');
  const module = device.createShaderModule({ code });
  const info = await module.getCompilationInfo();
  const scoped = await device.popErrorScope();
  const bad = info.messages.filter((m) => m.type === 'error' || m.type === 'warning');
  for (const m of bad) {
    console.log(`${file}:${m.lineNum}:${m.linePos}: ${m.type}: ${m.message}`);
    console.log(`    ${lines[m.lineNum - 1] ?? ''}`);
  }
  if (bad.length === 0 && scoped) {
    console.log(`${file}: error: ${scoped.message}`);
  }
  if (bad.length > 0 || scoped) rejected += 1;
}
console.log(`tint: ${files.length} modules checked, ${rejected} rejected (Dawn on ${adapter.info.description})`);
device.destroy();
process.exit(rejected === 0 ? 0 : 1);
