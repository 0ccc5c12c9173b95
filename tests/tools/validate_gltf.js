#!/usr/bin/env node
// Validates a .gltf or .glb with the Khronos glTF validator (npm package `gltf-validator`) and prints the
// report. Exit status: 0 when the report has no errors, 1 when it has, 2 when the validator cannot run.
//
// Usage: node validate_gltf.js <file> [<folder holding node_modules/gltf-validator>]
// The folder defaults to $PDEFACE_GLTF_VALIDATOR_DIR; install with
//   npm install --prefix <folder> gltf-validator
'use strict';
const fs = require('fs');
const path = require('path');

function fail(message) {
  console.error(`validate_gltf: ${message}`);
  process.exit(2);
}

const [file, folder = process.env.PDEFACE_GLTF_VALIDATOR_DIR] = process.argv.slice(2);
if (!file) fail('usage: node validate_gltf.js <file> [<validator folder>]');

let validator;
try {
  validator = require(folder ? path.resolve(folder, 'node_modules', 'gltf-validator') : 'gltf-validator');
} catch (e) {
  fail(`cannot load gltf-validator (${e.message}); install it with npm install --prefix <folder> gltf-validator`);
}

let bytes;
try {
  bytes = new Uint8Array(fs.readFileSync(file));
} catch (e) {
  fail(`cannot read ${file}: ${e.message}`);
}

// External resources are not loaded: our writer embeds every buffer, so a reference to a file is itself a
// problem the report should show.
validator.validateBytes(bytes, {uri: path.basename(file), maxIssues: 0, writeTimestamp: false})
  .then((report) => {
    console.log(JSON.stringify(report, null, 2));
    process.exit(report.issues.numErrors > 0 ? 1 : 0);
  })
  .catch((error) => fail(`the validator could not read ${file}: ${error}`));
