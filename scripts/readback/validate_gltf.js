// Validates each .glb named on the command line with the Khronos glTF validator and prints one
// JSON line per file: {"file", "errors", "warnings", "infos", "messages": [first 10 issues]}.
const fs = require("fs");
const path = require("path");
const validator = require("gltf-validator");

async function main() {
  let failed = false;
  for (const file of process.argv.slice(2)) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(bytes, { uri: path.basename(file) });
    const issues = report.issues;
    const messages = issues.messages.slice(0, 10).map((m) => `${m.code} ${m.pointer || ""}: ${m.message}`);
    console.log(JSON.stringify({
      file: path.basename(file),
      errors: issues.numErrors,
      warnings: issues.numWarnings,
      infos: issues.numInfos,
      generator: (report.info || {}).generator,
      messages,
    }));
    failed = failed || issues.numErrors > 0;
  }
  process.exit(failed ? 1 : 0);
}

main().catch((e) => {
  console.error(`validator: ${e}`);
  process.exit(2);
});
