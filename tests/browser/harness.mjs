// What the browser tests share: checks, starting tissuefem with the live
// view and finding its address, launching Debian's Chromium headless with
// software WebGL, and the end of a test.
import fs from 'node:fs';
import path from 'node:path';
import {spawn} from 'node:child_process';
import puppeteer from 'puppeteer-core';

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// check(ok, what) prints and records a failure; failures lists them.
export const failures = [];
export const check = (ok, what) => {
  if (!ok) { failures.push(what); console.log('FAILED:', what); }
};

// Starts tissuefem on @p scene in @p directory with --set @p settings;
// returns {run, exited (a promise of the exit code), code() (null while
// it runs)}.
export function startRun(exe, scene, directory, settings) {
  fs.mkdirSync(directory, {recursive: true});
  const log = fs.openSync(path.join(directory, 'run.log'), 'w');
  const run = spawn(exe, [scene, ...settings.flatMap((s) => ['--set', s])],
                    {cwd: directory, stdio: ['ignore', log, log]});
  let code = null;
  const exited = new Promise((resolve) => run.on('exit', (c) => { code = c; resolve(c); }));
  return {run, exited, code: () => code};
}

// The page's address, from <directory>/results/live_view (30 s at most);
// exits with the run's log if the run ends or never writes it.
export async function liveAddress(directory, started) {
  const file = path.join(directory, 'results', 'live_view');
  for (let k = 0; k < 600 && !fs.existsSync(file) && started.code() === null; ++k) await sleep(50);
  if (!fs.existsSync(file)) {
    console.log(fs.readFileSync(path.join(directory, 'run.log'), 'utf8').slice(-3000));
    process.exit(1);
  }
  return fs.readFileSync(file, 'utf8').trim();
}

export function launchBrowser() {
  return puppeteer.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: ['--headless=new', '--no-sandbox', '--use-angle=swiftshader',
           '--enable-unsafe-swiftshader', '--window-size=1200,800'],
  });
}

// A page of @p browser at @p url, 1200 x 800, once it has drawn a frame;
// returns {page, errors (the page's script errors so far)}.
export async function openPage(browser, url) {
  const page = await browser.newPage();
  await page.setViewport({width: 1200, height: 800});
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(url);
  await page.waitForFunction(() => window.tissuefem.topology && window.tissuefem.lastStep >= 0,
                             {timeout: 20000});
  await sleep(300);
  return {page, errors};
}

// Exits 1 with the tail of @p log if a check failed, else prints that
// test @p name passed.
export function finish(name, log) {
  if (failures.length) {
    console.log(fs.readFileSync(log, 'utf8').slice(-3000));
    process.exit(1);
  }
  console.log('browser ' + name + ': all checks passed');
}
