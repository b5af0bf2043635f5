// Validates a glTF/GLB file with the Khronos glTF validator (npm package `gltf-validator`, installed
// into ./node_modules by scripts/install-test-deps.sh) and prints the validation report as JSON.
// Usage: node scripts/validate-gltf.js FILE.glb   (exit 0 with the report; exit 2 when it cannot run)
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require(path.join(__dirname, '..', 'node_modules', 'gltf-validator'));
} catch (e) {
  console.error('gltf-validator is not installed: run scripts/install-test-deps.sh (npm ci). ' + e.message);
  process.exit(2);
}
const file = process.argv[2];
if (!file) {
  console.error('usage: node scripts/validate-gltf.js FILE.glb');
  process.exit(2);
}
const bytes = new Uint8Array(fs.readFileSync(file));
validator
  .validateBytes(bytes, { uri: path.basename(file), maxIssues: 0 })
  .then((report) => {
    process.stdout.write(JSON.stringify(report));
  })
  .catch((error) => {
    console.error('validation failed to run: ' + error);
    process.exit(2);
  });
