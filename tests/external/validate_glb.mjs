// Validates a .glb with the Khronos glTF validator (npm package gltf-validator).
// Usage: node validate_glb.mjs path/to/city.glb
// Prints the report's counts and every issue; exits 1 on any error (or a file it cannot
// read), 0 otherwise. Warnings and infos are printed but do not fail the check.
import { readFile } from "node:fs/promises";
import { createRequire } from "node:module";
import path from "node:path";

// Resolve gltf-validator from NODE_PATH as well (ES modules ignore NODE_PATH).
const require = createRequire(path.join(process.cwd(), "noop.js"));
const validator = require("gltf-validator");

const file = process.argv[2];
if (!file) {
  console.error("usage: node validate_glb.mjs FILE.glb");
  process.exit(2);
}

try {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0, // report all
    // External resources are not allowed: a .glb must be self-contained.
    externalResourceFunction: (uri) =>
      Promise.reject(new Error(`unexpected external resource ${uri}`)),
  });
  const { numErrors, numWarnings, numInfos, numHints, messages } = report.issues;
  const info = report.info || {};
  console.log(
    `${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ` +
      `${numHints} hints; ${info.drawCallCount ?? "?"} draw calls, ` +
      `${info.totalVertexCount ?? "?"} vertices, ${info.totalTriangleCount ?? "?"} triangles, ` +
      `${(info.resources || []).filter((r) => r.storage === "buffer-view" && r.mimeType).length} embedded images`,
  );
  const names = ["error", "warning", "info", "hint"];
  for (const m of messages) {
    console.log(`  ${names[m.severity] ?? m.severity} ${m.code} at ${m.pointer ?? m.offset ?? ""}: ${m.message}`);
  }
  process.exit(numErrors > 0 ? 1 : 0);
} catch (e) {
  console.error(`${file}: validation failed: ${e.message ?? e}`);
  process.exit(1);
}
