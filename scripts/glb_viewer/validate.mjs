// Validates a .glb with the Khronos glTF validator; prints its counts and exits 1 on any error.
import { readFileSync } from "node:fs";
import validator from "gltf-validator";

const file = process.argv[2];
const report = await validator.validateBytes(new Uint8Array(readFileSync(file)));
const { numErrors, numWarnings, numInfos, messages } = report.issues;
for (const m of messages.filter((m) => m.severity <= 1)) {
  console.log(`${m.severity === 0 ? "error" : "warning"}: ${m.code} ${m.pointer ?? ""}: ${m.message}`);
}
const info = report.info ?? {};
console.log(
  `${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos; ` +
    `${info.drawCallCount} draw calls, ${info.totalVertexCount} vertices, ${info.animationCount} animations`,
);
process.exit(numErrors > 0 ? 1 : 0);
