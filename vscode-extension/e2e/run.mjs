// End-to-end test of the packaged extension inside a real VS Code (code-server), driven by headless
// Chromium through playwright-core. Started by ../scripts/e2e.sh, which installs code-server and the
// .vsix, writes the workspace and settings, starts code-server and passes these variables:
//
//   E2E_URL        the code-server address (http://127.0.0.1:PORT)
//   E2E_WORKSPACE  the folder to open; it holds scene.openplx
//   E2E_LOGS       code-server's log folder (the OpenPLX output channel is written there)
//   E2E_PLX        the plx the extension must have found
//   E2E_ARTIFACTS  where screenshots of a failure go
//   E2E_CHROMIUM   the browser (default /usr/bin/chromium)
//
// Each step prints its time; the first failure takes a screenshot and exits 1.
import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { chromium } from 'playwright-core';

const env = (name, fallback) => {
  const v = process.env[name] ?? fallback;
  if (v === undefined) {
    console.error(`e2e: ${name} is not set (run scripts/e2e.sh)`);
    process.exit(2);
  }
  return v;
};
const URL = env('E2E_URL');
const WORKSPACE = env('E2E_WORKSPACE');
const LOGS = env('E2E_LOGS');
const PLX = env('E2E_PLX');
const ARTIFACTS = env('E2E_ARTIFACTS');
const CHROMIUM = env('E2E_CHROMIUM', '/usr/bin/chromium');

const SERVER_TIMEOUT = 60_000; // the first diagnostics wait for the server and the bundle program
const UI_TIMEOUT = 30_000;

const started = Date.now();
const secs = () => ((Date.now() - started) / 1000).toFixed(1);
let page;
let preview; // the frame of the 3D preview page
let stepName = 'start';

async function step(name, fn) {
  stepName = name;
  const t0 = Date.now();
  await fn();
  console.log(`  ok  ${name} (${((Date.now() - t0) / 1000).toFixed(1)} s, at ${secs()} s)`);
}

/** The OpenPLX output channel, as code-server wrote it to its log folder ('' while there is none). */
function extensionLog() {
  const found = [];
  const walk = (dir) => {
    for (const e of fs.existsSync(dir) ? fs.readdirSync(dir, { withFileTypes: true }) : []) {
      const p = path.join(dir, e.name);
      if (e.isDirectory()) walk(p);
      else if (e.name === 'OpenPLX.log') found.push(p);
    }
  };
  walk(LOGS);
  return found.map((f) => fs.readFileSync(f, 'utf8')).join('\n');
}

async function waitFor(what, predicate, timeout = UI_TIMEOUT) {
  const end = Date.now() + timeout;
  let last;
  for (;;) {
    last = await predicate();
    if (last) return last;
    if (Date.now() > end) throw new Error(`timed out after ${timeout / 1000} s waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 250));
  }
}

/** The text of each rendered line of the active editor, with the class of every token span. */
async function renderedTokens() {
  return page.$$eval('.editor-group-container.active .monaco-editor .view-lines .view-line', (lines) =>
    lines
      .map((line) => ({
        top: parseFloat(line.style.top),
        tokens: [...line.querySelectorAll(':scope > span > span')].map((s) => ({ text: s.textContent.replace(/\u00a0/g, ' '), cls: s.className })),
      }))
      .sort((a, b) => a.top - b.top)
      .map((l) => l.tokens),
  );
}

function tokenClass(lines, lineText, tokenText) {
  const line = lines.find((l) => l.map((t) => t.text).join('').trimEnd() === lineText);
  assert.ok(line, `line ${JSON.stringify(lineText)} is not rendered; rendered: ${JSON.stringify(lines.map((l) => l.map((t) => t.text).join('')))}`);
  const token = line.find((t) => t.text.trim() === tokenText);
  assert.ok(token, `no token ${JSON.stringify(tokenText)} in ${JSON.stringify(line)}`);
  return token.cls.split(/\s+/).find((c) => /^mtk\d+$/.test(c));
}

/** Runs a command from the command palette (F1), by its title. */
async function runCommand(title) {
  await page.keyboard.press('F1');
  const input = page.locator('.quick-input-widget input');
  await input.waitFor({ state: 'visible', timeout: UI_TIMEOUT });
  await input.fill(`>${title}`);
  await page.locator('.quick-input-list .monaco-list-row', { hasText: title }).first().waitFor({ timeout: UI_TIMEOUT });
  await page.keyboard.press('Enter');
}

/** Moves the cursor to 1-based line and column of the active editor (Go to Line). */
async function goTo(line, column) {
  await page.keyboard.press('Control+G');
  const input = page.locator('.quick-input-widget input');
  await input.waitFor({ state: 'visible', timeout: UI_TIMEOUT });
  await input.fill(`:${line}:${column}`);
  await page.keyboard.press('Enter');
  await input.waitFor({ state: 'hidden', timeout: UI_TIMEOUT });
}

const editorArea = () => page.locator('.editor-group-container.active .monaco-editor').first();
/** The file name of the active editor tab. */
const activeTabName = () => page.locator('.editor-group-container.active .tab.active').first().getAttribute('data-resource-name');
/** The breadcrumbs of the active editor: the file's folders (all of them for a file outside the workspace). */
const breadcrumbs = () => page.locator('.editor-group-container.active .breadcrumbs-control').first().innerText();
const squiggles = (kind) => page.locator(`.editor-group-container.active .monaco-editor .squiggly-${kind}`).count();

async function main() {
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: [
      '--headless',
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
    ],
  });
  try {
    const context = await browser.newContext({ viewport: { width: 1400, height: 900 } });
    page = await context.newPage();
    const scene = path.join(WORKSPACE, 'scene.openplx');

    await step('code-server shows the workspace', async () => {
      await page.goto(`${URL}/?folder=${encodeURIComponent(WORKSPACE)}`);
      await page.locator('.explorer-folders-view .monaco-list-row', { hasText: 'scene.openplx' }).waitFor({ timeout: 90_000 });
    });

    await step('scene.openplx opens in an editor in language mode OpenPLX', async () => {
      await page.locator('.explorer-folders-view .monaco-list-row', { hasText: 'scene.openplx' }).click();
      await waitFor('the editor tab', async () => (await activeTabName()) === 'scene.openplx');
      await page.locator('.statusbar-item', { hasText: 'OpenPLX' }).first().waitFor({ timeout: UI_TIMEOUT });
    });

    await step(`the extension started the server with ${PLX}`, async () => {
      const found = await waitFor('discovery in the OpenPLX log', async () => /discovery \[[^\]]+\] \S+: found/.test(extensionLog()), SERVER_TIMEOUT);
      assert.ok(found);
      const log = extensionLog();
      const line = log.split('\n').find((l) => /discovery \[[^\]]+\] \S+: found/.test(l));
      assert.ok(line.includes(` ${PLX}: found`), `the extension found another plx:\n${log}`);
      assert.match(log, new RegExp(`Starting: ${PLX.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')} lsp`));
      console.log(`      ${line.replace(/^.*discovery /, 'discovery ')}`);
    });

    await step('syntax highlighting: TextMate token classes in the editor DOM', async () => {
      // Semantic highlighting is off in the settings, so every colour comes from the TextMate grammar.
      const lines = await waitFor('tokenized lines', async () => {
        const l = await renderedTokens();
        return l.some((t) => t.length > 3) ? l : undefined;
      });
      const comment = tokenClass(lines, '# a scene for the end-to-end test', '# a scene for the end-to-end test');
      const keyword = tokenClass(lines, 'Scene is Physics3D.System:', 'is');
      const typeName = tokenClass(lines, 'Scene is Physics3D.System:', 'System');
      const number = tokenClass(lines, '        inertia.mass: 10', '10');
      const plain = tokenClass(lines, '        inertia.mass: 10', ':');
      const classes = { comment, keyword, typeName, number, plain };
      assert.equal(new Set(Object.values(classes)).size, 5, `expected five different token classes, got ${JSON.stringify(classes)}`);
      console.log(`      ${JSON.stringify(classes)}`);
    });

    await step('the TextMate scopes of `is` (Developer: Inspect Editor Tokens and Scopes)', async () => {
      await goTo(2, 8);
      await runCommand('Developer: Inspect Editor Tokens and Scopes');
      const widget = page.locator('.token-inspect-widget');
      await widget.waitFor({ timeout: UI_TIMEOUT });
      const text = await waitFor('the scopes', async () => {
        const t = await widget.innerText();
        return /source\.openplx/.test(t) ? t : undefined;
      });
      assert.match(text, /keyword[\w.-]*\.openplx/, text);
      console.log(`      ${text.split('\n').filter((l) => /\.openplx/.test(l)).join(' | ')}`);
      await page.keyboard.press('Escape');
    });

    await step('no diagnostics for the correct file', async () => {
      await page.waitForTimeout(1000);
      assert.equal(await squiggles('error'), 0);
    });

    await step('a diagnostic appears after typing an error', async () => {
      await goTo(4, 100);
      await page.keyboard.press('End');
      await page.keyboard.press('Enter');
      await page.keyboard.type('inertia.mas: 5', { delay: 20 });
      await page.keyboard.press('Escape');
      await waitFor('an error squiggle', async () => (await squiggles('error')) > 0, SERVER_TIMEOUT);
      const status = await page.locator('#status\\.problems').first().getAttribute('aria-label');
      assert.match(status ?? '', /Errors: [1-9]/, `status bar problems: ${status}`);
      // Go to Next Problem (F8) shows the diagnostic's message under its line. While the line was
      // typed, the server may have reported the half-typed line: wait for the final diagnostic.
      const message = await waitFor('the unknown-attribute diagnostic (N002)', async () => {
        await goTo(1, 1);
        await page.keyboard.press('F8');
        const widget = page.locator('.marker-widget').first();
        await widget.waitFor({ timeout: UI_TIMEOUT });
        const text = await widget.innerText();
        await page.keyboard.press('Escape');
        return /plx\(N002\)/.test(text) ? text : undefined;
      }, SERVER_TIMEOUT);
      assert.match(message, /'mas' is not an attribute/, message);
      // F8 moved the cursor to the start of the diagnostic: `mas` on the typed line
      await goTo(1, 1);
      await page.keyboard.press('F8');
      await page.locator('.marker-widget').first().waitFor({ timeout: UI_TIMEOUT });
      const selection = page.locator('#status\\.editor\\.selection').first();
      await waitFor('the cursor on `mas` of the typed line (Ln 5, Col 17)', async () => (await selection.innerText()).trim() === 'Ln 5, Col 17', 5000);
      console.log(`      ${message.split('\n').filter(Boolean).join(' | ')}`);
      await page.keyboard.press('Escape');
    });

    await step('the diagnostic clears after fixing it', async () => {
      await goTo(5, 16);
      await page.keyboard.press('End');
      await page.keyboard.press('Shift+Home');
      // (not `inertia.mass: 5`: line 4 sets the mass already, and a value given twice is M010)
      await page.keyboard.type('is_dynamic: true', { delay: 20 });
      await page.keyboard.press('Escape');
      await waitFor('no error squiggle', async () => (await squiggles('error')) === 0, SERVER_TIMEOUT);
      await page.waitForTimeout(1500); // and it stays so
      assert.equal(await squiggles('error'), 0);
      const status = await page.locator('#status\\.problems').first().getAttribute('aria-label');
      assert.match(status ?? '', /No Problems|Errors: 0/, `status bar problems: ${status}`);
    });

    await step('completion offers an attribute of the body', async () => {
      await page.keyboard.press('End');
      await page.keyboard.press('Enter');
      await page.keyboard.type('kinem', { delay: 20 });
      await page.keyboard.press('Control+Space');
      const item = page.locator('.suggest-widget .monaco-list-row', { hasText: 'kinematics' }).first();
      await item.waitFor({ timeout: SERVER_TIMEOUT });
      const labels = await page.locator('.suggest-widget .monaco-list-row .label-name').allInnerTexts();
      console.log(`      suggestions: ${labels.slice(0, 5).join(', ')}`);
      await page.keyboard.press('Escape');
      await page.keyboard.press('Control+Z');
    });

    await step('go to definition opens the official bundle file', async () => {
      await goTo(3, 40); // on `RigidBody` in `Physics3D.Bodies.RigidBody`
      await page.keyboard.press('F12');
      await waitFor('a RigidBody.openplx tab', async () => (await activeTabName()) === 'RigidBody.openplx', SERVER_TIMEOUT);
      const title = (await breadcrumbs()).split(/\s*\n\s*/).filter(Boolean).join('/');
      assert.match(title, /openplxbundles\/Physics3D\/Bodies\/RigidBody\.openplx/, `breadcrumbs: ${title}`);
      const lines = await renderedTokens();
      assert.ok(lines.some((l) => l.map((t) => t.text).join('').startsWith('RigidBody is ')), 'the bundle file shows its declaration');
      console.log(`      ${title}`);
    });

    await step('OpenPLX: Open 3D Preview draws truck.openplx beside the editor', async () => {
      await page.keyboard.press('Control+P');
      const input = page.locator('.quick-input-widget input');
      await input.waitFor({ state: 'visible', timeout: UI_TIMEOUT });
      await input.fill('truck.openplx');
      await page.locator('.quick-input-list .monaco-list-row', { hasText: 'truck.openplx' }).first().waitFor({ timeout: UI_TIMEOUT });
      await page.keyboard.press('Enter');
      await waitFor('the truck.openplx tab', async () => (await activeTabName()) === 'truck.openplx');
      await runCommand('OpenPLX: Open 3D Preview');
      const frame = await waitFor('the preview page in a webview', async () =>
        page.frames().find((f) => /[?&]t=[\w-]+/.test(f.url()) && f.url().startsWith('http')), SERVER_TIMEOUT);
      console.log(`      the page: ${preview ? '' : frame.url().replace(/t=.*/, 't=...')}`);
      preview = frame;
      await waitFor('the truck drawn', () => frame.evaluate(() => window.plxPreview?.state.drawnGeneration >= 1).catch(() => false), SERVER_TIMEOUT);
      const chassis = await frame.evaluate(() => plxPreview.state.scene.geoms.find((g) => g.path === 'box_truck.chassis.geometry').size[0]);
      assert.equal(chassis, 1.65);
      fs.mkdirSync(ARTIFACTS, { recursive: true });
      await page.screenshot({ path: path.join(ARTIFACTS, 'preview.png') });
    });

    await step('typing in the editor (unsaved) changes the preview', async () => {
      const gen = await preview.evaluate(() => plxPreview.state.drawnGeneration);
      await goTo(52, 16); // in `x: 3.3` of the chassis' size
      await page.keyboard.press('End');
      await page.keyboard.press('Backspace');
      await page.keyboard.press('Backspace');
      await page.keyboard.press('Backspace');
      await page.keyboard.type('5.0');
      // each keystroke may give a scene of its own (x: 3, then x: 5...): wait for the last one, drawn
      await waitFor('the 5 m chassis drawn', () => preview.evaluate((g) => plxPreview.state.drawnGeneration > g &&
        plxPreview.state.scene.geoms.find((x) => x.path === 'box_truck.chassis.geometry').size[0] === 2.5, gen), SERVER_TIMEOUT);
      assert.ok(fs.readFileSync(path.join(WORKSPACE, 'truck.openplx'), 'utf8').includes('x: 3.3'), 'the edit is not saved');
    });

    await step('a click on the chassis in the preview reveals its declaration in the editor', async () => {
      const [x, y] = await preview.evaluate(() => plxPreview.screenOf('box_truck.chassis'));
      const box = await (await preview.frameElement()).boundingBox();
      await page.mouse.click(box.x + x, box.y + y);
      await waitFor('the selection in the page', () => preview.evaluate(() => plxPreview.selectedPath() === 'box_truck.chassis'));
      const line = fs.readFileSync(path.join(WORKSPACE, 'truck.openplx'), 'utf8').split('\n').indexOf('    chassis is Chassis:') + 1;
      await waitFor(`the cursor at line ${line}`, async () =>
        (await page.locator('#status\\.editor\\.selection').first().innerText().catch(() => '')).includes(`Ln ${line},`));
      await page.screenshot({ path: path.join(ARTIFACTS, 'preview-selected.png') });
      await page.keyboard.press('Control+Z'); // the edit above stays unsaved; undo it
    });

    assert.equal(fs.readFileSync(scene, 'utf8').includes('mas:'), false, 'the test does not save its edits');
    console.log(`e2e: all steps passed in ${secs()} s`);
  } catch (e) {
    fs.mkdirSync(ARTIFACTS, { recursive: true });
    const shot = path.join(ARTIFACTS, 'failure.png');
    await page?.screenshot({ path: shot }).catch(() => {});
    console.error(`e2e: FAILED at step "${stepName}" (${secs()} s): ${e?.stack ?? e}`);
    console.error(`--- screenshot: ${shot}\n--- OpenPLX log:\n${extensionLog() || '(none)'}`);
    process.exitCode = 1;
  } finally {
    await browser.close();
  }
}

await main();
