/**
 * Smoke test of the shipped bundle (dist/extension.js) with a stand-in `vscode` module: activation
 * registers every contributed command, a missing server gives the not-found message, and the check
 * commands run `plx check [--simulate] FILE` as a task. VS Code itself cannot run here.
 */
import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { createVscodeStub, installVscodeStub, type Recorder, StubUri } from '../support/vscodeStub';

const ROOT = path.resolve(__dirname, '..', '..', '..');
const BUNDLE = path.join(ROOT, 'dist', 'extension.js');

interface ExtensionModule {
  activate(context: { subscriptions: Array<{ dispose(): unknown }> }): Promise<void>;
  deactivate(): Promise<void>;
}

async function until(condition: () => boolean, what: string, ms = 5000): Promise<void> {
  const end = Date.now() + ms;
  while (!condition()) {
    if (Date.now() > end) {
      throw new Error(`timed out waiting for ${what}`);
    }
    await new Promise((r) => setTimeout(r, 10));
  }
}

describe('extension bundle (with a stand-in vscode module)', () => {
  let tmp: string;
  let rec: Recorder;
  let uninstall: () => void;
  let ext: ExtensionModule;
  const context = { subscriptions: [] as Array<{ dispose(): unknown }> };

  before(async () => {
    assert.ok(fs.existsSync(BUNDLE), `${BUNDLE} is missing: run node scripts/build.mjs first`);
    tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'plx-ext-'));
    rec = {
      commands: new Map(),
      errors: [],
      warnings: [],
      tasks: [],
      logs: [],
      settings: { 'openplx.server.path': path.join(tmp, 'missing', 'plx') },
    };
    uninstall = installVscodeStub(createVscodeStub(rec));
    delete require.cache[BUNDLE];
    ext = require(BUNDLE) as ExtensionModule;
    await ext.activate(context);
    await until(() => rec.errors.length > 0, 'the not-found message');
  });

  after(async () => {
    await ext?.deactivate();
    context.subscriptions.forEach((d) => d.dispose());
    uninstall?.();
    fs.rmSync(tmp, { recursive: true, force: true });
  });

  it('registers every command contributed in package.json', () => {
    const pkg = JSON.parse(fs.readFileSync(path.join(ROOT, 'package.json'), 'utf8'));
    const contributed = pkg.contributes.commands.map((c: { command: string }) => c.command).sort();
    assert.deepEqual([...rec.commands.keys()].sort(), contributed);
  });

  it('shows what was tried and the install command when plx is missing', () => {
    assert.equal(rec.errors.length, 1);
    assert.ok(rec.errors[0].includes(path.join(tmp, 'missing', 'plx')), rec.errors[0]);
    assert.ok(rec.errors[0].includes('OpenPLX: Install plxtools'), rec.errors[0]);
    assert.ok(/pip install "(plxtools\[sim\] @ file:\/\/.*\.whl|<a plxtools wheel or checkout>)"/.test(rec.errors[0]), rec.errors[0]);
    assert.ok(rec.logs.some((l) => l.includes('discovery [server.path]')), rec.logs.join('\n'));
  });

  it('warns when a check is run without an .openplx file', async () => {
    rec.activeDocument = undefined;
    await rec.commands.get('openplx.checkScene')!();
    assert.match(rec.warnings.at(-1) ?? '', /Open an \.openplx file/);
  });

  it('saves the file and runs `plx check --simulate FILE` as a task, with the bundle path in its environment', async () => {
    const plx = path.join(tmp, 'bin', 'plx');
    fs.mkdirSync(path.dirname(plx), { recursive: true });
    fs.writeFileSync(plx, '#!/bin/sh\nexit 0\n', { mode: 0o755 });
    rec.settings['openplx.server.path'] = plx;
    rec.settings['openplx.bundlePath'] = path.join(tmp, 'bundles');
    const scene = path.join(tmp, 'scene.openplx');
    let saved = false;
    rec.activeDocument = {
      uri: StubUri.file(scene),
      languageId: 'openplx',
      isDirty: true,
      save: async () => (saved = true),
    };

    await rec.commands.get('openplx.simulateScene')!();
    await rec.commands.get('openplx.checkScene')!(StubUri.file(scene));

    assert.equal(rec.tasks.length, 2);
    const [simulate, check] = rec.tasks;
    assert.equal(simulate.execution.process, plx);
    assert.deepEqual(simulate.execution.args, ['check', '--simulate', scene]);
    assert.deepEqual(check.execution.args, ['check', scene]);
    assert.deepEqual(simulate.definition, { type: 'openplx', file: scene, simulate: true });
    assert.equal(simulate.execution.options?.env?.OPENPLX_BUNDLE_PATH, path.join(tmp, 'bundles'));
    assert.equal(saved, true, 'unsaved changes are saved before plx check reads the file');
  });

  it('"View scene" runs `plx view FILE` as its own background task', async () => {
    const scene = path.join(tmp, 'scene.openplx');
    const before = rec.tasks.length;
    await rec.commands.get('openplx.viewScene')!(StubUri.file(scene));
    assert.equal(rec.tasks.length, before + 1);
    const view = rec.tasks[before];
    assert.deepEqual(view.execution.args, ['view', scene]);
    assert.deepEqual(view.definition, { type: 'openplx', file: scene });
  });
});
