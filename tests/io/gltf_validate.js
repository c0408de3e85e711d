// Validates a glTF / glb file with Khronos' glTF-Validator (the npm package gltf-validator,
// installed by scripts/setup-debian.sh under tools/node/): prints the report's counts and
// every error, warning and info message, and exits 1 when there is an error or a warning.
// Usage: node gltf_validate.js VALIDATOR_MODULE_DIR FILE
const fs = require("fs");
const validator = require(require("path").resolve(process.argv[2]));
const bytes = new Uint8Array(fs.readFileSync(process.argv[3]));
validator
  .validateBytes(bytes, { maxIssues: 0 })
  .then((report) => {
    const issues = report.issues;
    console.log(
      `${process.argv[3]}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
        `${issues.numInfos} infos, ${issues.numHints} hints`
    );
    for (const message of issues.messages.slice(0, 20)) {
      console.log(`  ${message.severity} ${message.code} ${message.pointer || ""}: ${message.message}`);
    }
    process.exit(issues.numErrors + issues.numWarnings > 0 ? 1 : 0);
  })
  .catch((error) => {
    console.log(`validator failed: ${error}`);
    process.exit(1);
  });
