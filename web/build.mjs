// Builds the browser front end: `node build.mjs <outdir>` bundles and minifies src/ into
// <outdir>: index.html (catalogue), design.html (design page), inverse.html (inverse design),
// graded.html (graded sheets), app.js, design.js, inverse.js, graded.js, style.css, graded.css.
// Every URL in them is relative, so the files work under `isogami serve` and from any
// static host or sub-path. Called by crates/isogami-web's build.rs after `npm ci`.

import { build } from 'esbuild';
import { copyFile, mkdir, readdir } from 'node:fs/promises';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const src = join(here, 'src');
const outArg = process.argv[2];
if (!outArg) {
  console.error('usage: node build.mjs <outdir>');
  process.exit(2);
}
const outdir = resolve(outArg);
await mkdir(outdir, { recursive: true });

const common = {
  bundle: true,
  minify: true,
  format: 'esm',
  target: ['es2022'],
  legalComments: 'none',
  logLevel: 'warning',
  charset: 'utf8',
};

await build({
  ...common,
  entryPoints: {
    app: join(src, 'catalogue.js'),
    design: join(src, 'design.js'),
    inverse: join(src, 'inverse.js'),
    graded: join(src, 'graded.js'),
  },
  outdir,
});
await build({ ...common, entryPoints: [join(src, 'style.css')], outfile: join(outdir, 'style.css') });
await build({ ...common, entryPoints: [join(src, 'graded.css')], outfile: join(outdir, 'graded.css') });
for (const name of await readdir(src)) {
  if (name.endsWith('.html')) await copyFile(join(src, name), join(outdir, name));
}
console.log(`built isogami web front end into ${outdir}`);
