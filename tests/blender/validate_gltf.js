// Runs the Khronos glTF validator (npm package gltf-validator) on one .gltf/.glb and prints its
// issue counts and messages; exit status 1 when it reports any error.
//   node validate_gltf.js NODE_MODULES_DIR FILE
const fs = require("fs");
const path = require("path");
const validator = require(path.join(process.argv[2], "gltf-validator"));

const file = process.argv[3];
const folder = path.dirname(file);
validator
  .validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    maxIssues: 0,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        const resolved = path.resolve(folder, decodeURIComponent(uri));
        if (!resolved.startsWith(path.resolve(folder) + path.sep)) return reject("outside");
        fs.readFile(resolved, (err, data) => (err ? reject(err.toString()) : resolve(data)));
      }),
  })
  .then((report) => {
    const i = report.issues;
    console.log(`validator ${report.validatorVersion}: ${i.numErrors} errors, ${i.numWarnings} ` +
                `warnings, ${i.numInfos} infos, ${i.numHints} hints`);
    for (const m of i.messages) console.log(`  ${m.severity} ${m.code} ${m.pointer || ""}: ${m.message}`);
    process.exit(i.numErrors > 0 ? 1 : 0);
  })
  .catch((e) => {
    console.error(`validator failed: ${e}`);
    process.exit(2);
  });
