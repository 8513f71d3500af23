// Copies the library's data module (web/biref_data.js, made by `biref gl-data` and checked
// against the library by tests/cli/web.sh) into the package: the GLSL source of
// shaders/biref_analytic.glsl, the look-up table and the coherent regime's sample plans. The
// package carries the same bytes; nothing here computes physics. Run by `npm install`/`npm ci`
// (prepare) and before `npm pack` (prepack).
import { copyFileSync, existsSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const from = join(here, '..', '..', 'biref_data.js');
const to = join(here, '..', 'src', 'biref_data.js');
if (!existsSync(from)) {
  console.error(`build-data: ${from} is missing (make it with: biref gl-data -o web/biref_data.js examples/*.json)`);
  process.exit(1);
}
copyFileSync(from, to);
