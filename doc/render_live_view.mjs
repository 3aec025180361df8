// The README's picture of the live view: Jeffrey's muscle run with --view
// (its own grasping tool pulls one end), its page opened in headless
// Chromium, coloured by the von Mises stress, at t = 0.3.
//
//   node doc/render_live_view.mjs build/tissuefem doc/figures/live_view_muscle.png
//
// (needs tests/browser/install.sh's Chromium and puppeteer-core).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {spawn} from 'node:child_process';
import {createRequire} from 'node:module';

const here = path.dirname(new URL(import.meta.url).pathname);
const require = createRequire(path.join(here, '../tests/browser/package.json'));
const puppeteer = require('puppeteer-core');
const [exe, out] = process.argv.slice(2);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'live-view-picture-'));

const run = spawn(path.resolve(exe), [path.join(here, '../parameters/jeffrey_muscle.prm'), '--view',
  '--set', 'Output/Directory=results', '--set', 'Output/VTU/Interval=0',
  '--set', 'Output/Live view/Wait for page=60'],
  {cwd: work, stdio: 'ignore'});
const file = path.join(work, 'results', 'live_view');
for (let k = 0; k < 600 && !fs.existsSync(file); ++k) await sleep(50);
const browser = await puppeteer.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
  args: ['--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
try {
  const page = await browser.newPage();
  await page.setViewport({width: 1280, height: 800});
  await page.goto(fs.readFileSync(file, 'utf8').trim());
  await page.select('#field', 'von Mises');
  // The scene's tool has pulled the end of the muscle for 0.3 s.
  await page.waitForFunction(() => window.tissuefem.lastStep >= 6000, {timeout: 120000});
  await page.screenshot({path: out});
} finally {
  await browser.close();
  run.kill();
}
console.log('wrote %s', out);
