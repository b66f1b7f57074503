#!/usr/bin/env node
// Every glTF file in the folders or files given, through the Khronos glTF
// validator (npm's gltf-validator, which tools/setup.sh installs into .node/):
// prints each file's errors, warnings and infos, and the errors and warnings
// themselves; exits 1 if any file has an error, 2 if the validator is missing.
//   node tools/gltf_validate.js build/bin/assets/meshes
const fs = require('fs');
const path = require('path');
let validator;
try {
  validator = require(path.join(__dirname, '..', '.node', 'node_modules', 'gltf-validator'));
} catch (e) {
  console.error('gltf_validate.js: the Khronos glTF validator is not installed (tools/setup.sh installs it into .node/)');
  process.exit(2);
}
const files = [];
for (const arg of process.argv.slice(2)) {
  if (fs.statSync(arg).isDirectory()) {
    for (const name of fs.readdirSync(arg).sort())
      if (/\.(gltf|glb)$/i.test(name)) files.push(path.join(arg, name));
  } else {
    files.push(arg);
  }
}
(async () => {
  let failed = files.length === 0;
  if (failed) console.error('gltf_validate.js: no .gltf or .glb file given');
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      // a .gltf's .bin and images, beside it
      externalResourceFunction: (uri) => new Promise((resolve, reject) => {
        try {
          resolve(new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(uri)))));
        } catch (e) {
          reject(e.toString());
        }
      }),
    });
    const issues = report.issues;
    console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos`);
    for (const m of issues.messages)
      if (m.severity <= 1) console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer || ''}: ${m.message}`);
    failed = failed || issues.numErrors > 0;
  }
  process.exit(failed ? 1 : 0);
})();
