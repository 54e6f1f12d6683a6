// Runs the Khronos glTF validator (npm gltf-validator, installed in .tools/ by `make tools`)
// on each file given; prints one JSON object per file: {file, errors, warnings, messages}.
const path = require("path");
const fs = require("fs");
const validator = require(path.resolve(process.env.GLTF_VALIDATOR_DIR, "gltf-validator"));

async function main() {
  for (const file of process.argv.slice(2)) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      externalResourceFunction: (uri) =>
        new Promise((resolve, reject) => {
          try {
            resolve(new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(uri)))));
          } catch (err) {
            reject(err.toString());
          }
        }),
    });
    console.log(JSON.stringify({
      file,
      errors: report.issues.numErrors,
      warnings: report.issues.numWarnings,
      messages: report.issues.messages,
    }));
  }
}
main().catch((err) => { console.error(String(err)); process.exit(1); });
