import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import type { PlxInvocation } from '../../src/serverDiscovery';
import { BUNDLE_PATH_ENV, checkArgs, plxCommand, serverLaunch, viewArgs } from '../../src/serverLaunch';

const plx: PlxInvocation = { command: '/venv/bin/plx', prefixArgs: [], source: 'PATH', description: 'plx' };
const module: PlxInvocation = {
  command: '/venv/bin/python',
  prefixArgs: ['-m', 'plxtools'],
  source: 'interpreter',
  description: 'python -m plxtools',
};

describe('serverLaunch', () => {
  it('runs `plx lsp` with the extra server args', () => {
    const launch = serverLaunch(plx, { env: { PATH: '/usr/bin' }, serverArgs: ['--log-level', 'debug'] });
    assert.equal(launch.command, '/venv/bin/plx');
    assert.deepEqual(launch.args, ['lsp', '--log-level', 'debug']);
    assert.equal(launch.env.PATH, '/usr/bin');
    assert.deepEqual(launch.initializationOptions, {});
    assert.ok(!(BUNDLE_PATH_ENV in launch.env));
  });

  it('runs `python -m plxtools lsp` for a module invocation', () => {
    const launch = serverLaunch(module, { env: {} });
    assert.equal(launch.command, '/venv/bin/python');
    assert.deepEqual(launch.args, ['-m', 'plxtools', 'lsp']);
  });

  it('passes openplx.bundlePath in initializationOptions and OPENPLX_BUNDLE_PATH', () => {
    const ws = path.resolve('/work/project');
    const launch = serverLaunch(plx, { env: { HOME: '/home/u' }, bundlePath: 'bundles', workspaceFolder: ws });
    const expected = path.join(ws, 'bundles');
    assert.deepEqual(launch.initializationOptions, { bundlePath: expected });
    assert.equal(launch.env[BUNDLE_PATH_ENV], expected);
    assert.equal(launch.env.HOME, '/home/u');
    assert.equal(launch.cwd, ws);
  });

  it('resolves each folder of a bundle path list', () => {
    const launch = serverLaunch(plx, { env: {}, bundlePath: 'a: /abs/b :', workspaceFolder: '/ws', platform: 'linux' });
    assert.equal(launch.env[BUNDLE_PATH_ENV], `${path.resolve('/ws', 'a')}:/abs/b`);
    assert.deepEqual(launch.initializationOptions, { bundlePath: `${path.resolve('/ws', 'a')}:/abs/b` });
  });

  it('keeps an inherited OPENPLX_BUNDLE_PATH when the setting is empty', () => {
    const launch = serverLaunch(plx, { env: { [BUNDLE_PATH_ENV]: '/from/env' }, bundlePath: '  ' });
    assert.equal(launch.env[BUNDLE_PATH_ENV], '/from/env');
    assert.deepEqual(launch.initializationOptions, {});
  });

  it('does not modify the environment it is given and drops undefined values', () => {
    const env: Record<string, string | undefined> = { A: '1', B: undefined };
    const launch = serverLaunch(plx, { env, bundlePath: '/b' });
    assert.deepEqual(env, { A: '1', B: undefined });
    assert.deepEqual(Object.keys(launch.env).sort(), ['A', BUNDLE_PATH_ENV]);
  });

  it('ignores empty extra args', () => {
    const launch = serverLaunch(plx, { env: {}, serverArgs: ['', '--x'] });
    assert.deepEqual(launch.args, ['lsp', '--x']);
  });
});

describe('check commands', () => {
  it('builds `plx check FILE` and `plx check --simulate FILE`', () => {
    assert.deepEqual(checkArgs('/m/scene.openplx', false), ['check', '/m/scene.openplx']);
    assert.deepEqual(checkArgs('/m/scene.openplx', true), ['check', '--simulate', '/m/scene.openplx']);
  });

  it('builds `plx view FILE` for "View scene"', () => {
    assert.deepEqual(viewArgs('/m/a b.openplx'), ['view', '/m/a b.openplx']);
    assert.deepEqual(plxCommand(module, viewArgs('/m/s.openplx'), { env: {} }).args, ['-m', 'plxtools', 'view', '/m/s.openplx']);
  });

  it('prefixes `-m plxtools` for a module invocation and sets the bundle path', () => {
    const spec = plxCommand(module, checkArgs('/m/a b.openplx', true), { env: {}, bundlePath: '/bundles' });
    assert.deepEqual(spec.args, ['-m', 'plxtools', 'check', '--simulate', '/m/a b.openplx']);
    assert.equal(spec.env[BUNDLE_PATH_ENV], '/bundles');
  });
});

describe('module boundaries', () => {
  it('discovery and launch code do not import vscode (they run under plain Node)', () => {
    for (const name of ['serverDiscovery.ts', 'serverLaunch.ts', 'previewClient.ts']) {
      const source = fs.readFileSync(path.join(__dirname, '..', '..', '..', 'src', name), 'utf8');
      assert.ok(!/from ['"]vscode['"]|require\(['"]vscode['"]\)/.test(source), `${name} imports vscode`);
    }
  });
});
