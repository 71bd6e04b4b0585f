// A headless Chromium for the Python tests, driven one JSON line at a time over stdin/stdout.
//
//   node driver.mjs            (CHROMIUM=/usr/bin/chromium by default)
//   > {"id": 1, "op": "goto", "url": "http://127.0.0.1:8765/?t=..."}
//   < {"id": 1, "ok": true, "result": null}
//
// ops: goto(url, width?, height?), evaluate(expr), waitFor(expr, timeout), click(x, y),
// press(key), screenshot(path), close. `expr` is a JavaScript expression evaluated in the page.
import { createInterface } from 'node:readline';
import { chromium } from 'playwright-core';

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking'],
});
let page = null;
const logs = [];

async function run(msg) {
  switch (msg.op) {
    case 'goto': {
      if (page) await page.close();
      // bypassCSP: waitForFunction evaluates its expression as a string, which the page's policy forbids
      page = await browser.newPage({ viewport: { width: msg.width || 800, height: msg.height || 600 }, bypassCSP: true });
      page.on('console', (m) => logs.push(`${m.type()}: ${m.text()}`));
      page.on('pageerror', (e) => logs.push(`pageerror: ${e.message}`));
      await page.goto(msg.url);
      return null;
    }
    case 'evaluate':
      return await page.evaluate(msg.expr);
    case 'waitFor':
      await page.waitForFunction(msg.expr, null, { timeout: msg.timeout || 10000, polling: 20 });
      return await page.evaluate(msg.expr);
    case 'click':
      await page.mouse.click(msg.x, msg.y);
      return null;
    case 'press':
      await page.keyboard.press(msg.key);
      return null;
    case 'screenshot':
      await page.screenshot({ path: msg.path });
      return msg.path;
    case 'logs':
      return logs.splice(0);
    case 'close':
      await browser.close();
      process.exit(0);
    default:
      throw new Error(`unknown op ${msg.op}`);
  }
}

process.stdout.write(JSON.stringify({ id: 0, ok: true, result: 'ready' }) + '\n');
const rl = createInterface({ input: process.stdin });
for await (const line of rl) {
  if (!line.trim()) continue;
  const msg = JSON.parse(line);
  try {
    const result = await run(msg);
    process.stdout.write(JSON.stringify({ id: msg.id, ok: true, result: result ?? null }) + '\n');
  } catch (e) {
    process.stdout.write(JSON.stringify({ id: msg.id, ok: false, error: String(e && e.message ? e.message : e), logs: logs.splice(0) }) + '\n');
  }
}
await browser.close();
