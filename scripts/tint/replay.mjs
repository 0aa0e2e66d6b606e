// Replays a launch rt-runtime captured (rt-runtime/src/backend/wgpu/capture.rs)
// on Dawn, Chrome's WebGPU implementation, through the npm package
// `webgpu`: the same kernel, bindings, uniforms and dispatches, then the
// output buffers' words and the rays traced are read back.
//
//   node replay.mjs CAPTURE_DIR
//
// Writes CAPTURE_DIR/dawn_outputs.bin (the outputs' words, in the order of
// launch.json) and prints `replay: rays N, adapter ...`. Exits 1 on any
// Dawn error (shader, pipeline, validation, device loss), 2 without an
// adapter. tests/tests/dawn_replay.rs runs it and compares with wgpu.
import { create, globals } from 'webgpu';
import { readFileSync, writeFileSync, existsSync } from 'node:fs';
import { join } from 'node:path';

Object.assign(globalThis, globals);

const dir = process.argv[2];
const launch = JSON.parse(readFileSync(join(dir, 'launch.json'), 'utf8'));
const code = readFileSync(join(dir, 'kernel.wgsl'), 'utf8');

const gpu = create(['backend=vulkan']);
const adapter = await gpu.requestAdapter();
if (!adapter) {
  console.error('replay: Dawn found no adapter (backend=vulkan)');
  process.exit(2);
}
const requiredLimits = {};
for (const k of ['maxStorageBuffersPerShaderStage', 'maxStorageBufferBindingSize', 'maxBufferSize',
  'maxComputeInvocationsPerWorkgroup', 'maxComputeWorkgroupSizeX', 'maxComputeWorkgroupSizeY']) {
  requiredLimits[k] = adapter.limits[k];
}
const device = await adapter.requestDevice({ requiredLimits });
let failed = null;
device.addEventListener('uncapturederror', (e) => { failed ??= e.error.message; });
device.lost.then((info) => { failed ??= `device lost: ${info.message}`; });

// The bindings the kernel declares, with their address space.
const declared = new Map();
for (const m of code.matchAll(/@group\(0\) @binding\((\d+)\) var<([a-z_, ]+)>/g)) {
  declared.set(Number(m[1]), m[2].replace(/\s/g, ''));
}
const entriesLayout = [];
const buffers = new Map();
for (const [binding, space] of [...declared].sort((a, b) => a[0] - b[0])) {
  if (space === 'uniform') {
    entriesLayout.push({ binding, visibility: GPUShaderStage.COMPUTE, buffer: { type: 'uniform' } });
    continue;
  }
  const type = space === 'storage,read' ? 'read-only-storage' : 'storage';
  entriesLayout.push({ binding, visibility: GPUShaderStage.COMPUTE, buffer: { type } });
  const file = join(dir, `binding${binding}.bin`);
  const bytes = existsSync(file) ? readFileSync(file) : Buffer.alloc(0);
  const size = Math.max(16, Math.ceil(bytes.length / 16) * 16);
  const buffer = device.createBuffer({
    size,
    usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC | GPUBufferUsage.COPY_DST,
    mappedAtCreation: true,
  });
  new Uint8Array(buffer.getMappedRange()).set(bytes);
  buffer.unmap();
  buffers.set(binding, buffer);
}
const layout = device.createBindGroupLayout({ entries: entriesLayout });
device.pushErrorScope('validation');
const module = device.createShaderModule({ code });
const info = await module.getCompilationInfo();
for (const m of info.messages.filter((m) => m.type !== 'info')) {
  console.error(`kernel.wgsl:${m.lineNum}:${m.linePos}: ${m.type}: ${m.message}`);
  failed ??= m.message;
}
const pipeline = await device.createComputePipelineAsync({
  layout: device.createPipelineLayout({ bindGroupLayouts: [layout] }),
  compute: { module },
}).catch((e) => { failed ??= `pipeline: ${e.message}`; return null; });
const scoped = await device.popErrorScope();
if (scoped) failed ??= scoped.message;
if (failed || !pipeline) {
  console.error(`replay: ${failed}`);
  process.exit(1);
}

const encoder = device.createCommandEncoder();
const pass = encoder.beginComputePass();
pass.setPipeline(pipeline);
const uniforms = [];
for (const [words, gx, gy] of launch.tiles) {
  const u = device.createBuffer({ size: Math.max(16, words.length * 4), usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  device.queue.writeBuffer(u, 0, new Uint32Array(words));
  uniforms.push(u);
  const entries = entriesLayout.map(({ binding }) => ({
    binding,
    resource: { buffer: buffers.get(binding) ?? u },
  }));
  pass.setBindGroup(0, device.createBindGroup({ layout, entries }));
  pass.dispatchWorkgroups(gx, gy, 1);
}
pass.end();
// Read back: each output's words from the heap (binding 0), then the log's
// header (binding 2).
const total = launch.outputs.reduce((s, [, n]) => s + n, 0) + 4;
const staging = device.createBuffer({ size: total * 4, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
let at = 0;
for (const [offset, n] of launch.outputs) {
  if (n > 0) encoder.copyBufferToBuffer(buffers.get(0), offset * 4, staging, at * 4, n * 4);
  at += n;
}
encoder.copyBufferToBuffer(buffers.get(2), 0, staging, at * 4, 16);
device.queue.submit([encoder.finish()]);
await staging.mapAsync(GPUMapMode.READ);
const words = new Uint32Array(staging.getMappedRange().slice(0));
staging.unmap();
if (failed) {
  console.error(`replay: ${failed}`);
  process.exit(1);
}
writeFileSync(join(dir, 'dawn_outputs.bin'), Buffer.from(words.buffer, 0, at * 4));
console.log(`replay: rays ${words[at + 2]}, exceptions ${words[at]}, adapter ${adapter.info.description}`);
device.destroy();
process.exit(0);
