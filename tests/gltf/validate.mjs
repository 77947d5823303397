// Validates glTF files with the Khronos glTF-Validator (npm package `gltf-validator`,
// which .ci/run installs under target/gltf-validator): prints each file's counts and
// every message, and exits 1 when any file has an error or a warning, 2 when the
// validator is missing. Usage: node tests/gltf/validate.mjs FILE.glb|FILE.gltf...
import { createRequire } from 'node:module';
import { readFile } from 'node:fs/promises';
import path from 'node:path';

const require = createRequire(import.meta.url);
let validator;
try {
  const folder = process.env.GLTF_VALIDATOR;
  validator = require(folder ? path.resolve(folder) : 'gltf-validator');
} catch (error) {
  console.error(`gltf-validator is not installed (${error.message}); .ci/run installs it`);
  process.exit(2);
}

let failed = false;
for (const file of process.argv.slice(2)) {
  const folder = path.dirname(file);
  const report = await validator.validateBytes(new Uint8Array(await readFile(file)), {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      readFile(path.join(folder, decodeURIComponent(uri))).then((bytes) => new Uint8Array(bytes)),
  });
  const issues = report.issues;
  console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos, ${issues.numHints} hints`);
  for (const message of issues.messages) {
    const severity = ['error', 'warning', 'info', 'hint'][message.severity];
    console.log(`  ${severity} ${message.code} ${message.pointer ?? ''}: ${message.message}`);
  }
  if (issues.numErrors > 0 || issues.numWarnings > 0) failed = true;
}
process.exit(failed ? 1 : 0);
