// Validates glTF files (.glb or .gltf with external buffers) with the Khronos glTF validator
// (npm package gltf-validator, resolved through NODE_PATH). Prints the counts for every file and
// exits non-zero if any file has errors or cannot be read.
// Usage: NODE_PATH=<dir>/node_modules node .ci/gltf_validate.js FILE...
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const dir = path.dirname(file);
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 50,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        try {
          resolve(new Uint8Array(fs.readFileSync(path.join(dir, decodeURIComponent(uri)))));
        } catch (e) {
          reject(e.toString());
        }
      }),
  });
  const n = report.issues;
  console.log(`${file}: ${n.numErrors} errors, ${n.numWarnings} warnings, ${n.numInfos} infos, ` +
    `${n.numHints} hints (validator ${report.validatorVersion})`);
  for (const m of n.messages) {
    if (m.severity <= 1) console.log(`  [${m.severity === 0 ? 'error' : 'warning'}] ${m.code} ${m.pointer || ''}: ${m.message}`);
  }
  return n.numErrors;
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: node .ci/gltf_validate.js FILE...');
    process.exit(2);
  }
  let errors = 0;
  for (const f of files) {
    try {
      errors += await validate(f);
    } catch (e) {
      console.log(`${f}: cannot validate: ${e}`);
      errors += 1;
    }
  }
  console.log(`gltf-validator: ${files.length} file(s), ${errors} error(s)`);
  process.exit(errors > 0 ? 1 : 0);
})();
