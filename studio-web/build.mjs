// Builds the studio front end into matloom/studio/static/ (shipped inside the Python package).
// Deterministic: same sources + same pinned toolchain (package-lock.json) -> same bytes.
// `make studio-build` runs this; tests/studio/test_assets.py fails when the shipped assets are
// stale against these sources (it compares the source hash recorded in build-info.json).
import { build } from "esbuild";
import { createHash } from "node:crypto";
import { readFileSync, readdirSync, statSync, writeFileSync, mkdirSync, copyFileSync } from "node:fs";
import { join, relative } from "node:path";

const here = new URL(".", import.meta.url).pathname;
const out = join(here, "..", "matloom", "studio", "static");
mkdirSync(out, { recursive: true });

function files(dir) {
  return readdirSync(dir).sort().flatMap((name) => {
    const p = join(dir, name);
    return statSync(p).isDirectory() ? files(p) : [p];
  });
}

// The source hash: every file under src/ plus the lock file, by relative path and content.
export function sourceHash() {
  const h = createHash("sha256");
  for (const p of [...files(join(here, "src")), join(here, "package-lock.json"), join(here, "build.mjs")]) {
    h.update(relative(here, p).replaceAll("\\", "/") + "\0");
    h.update(readFileSync(p));
    h.update("\0");
  }
  return h.digest("hex");
}

await build({
  entryPoints: [join(here, "src", "main.ts")],
  bundle: true,
  format: "esm",
  target: "es2022",
  minify: true,
  legalComments: "linked",
  sourcemap: false,
  outfile: join(out, "app.js"),
  logLevel: "warning",
});
copyFileSync(join(here, "src", "index.html"), join(out, "index.html"));
copyFileSync(join(here, "src", "app.css"), join(out, "app.css"));
writeFileSync(
  join(out, "build-info.json"),
  JSON.stringify({ source_sha256: sourceHash(), esbuild: "0.28.2" }, null, 2) + "\n",
);
console.log("studio assets written to", relative(process.cwd(), out));
