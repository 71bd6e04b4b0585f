import * as assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import {
  type DiscoveryInput,
  type DiscoveryResult,
  discoverPlx,
  findBundledWheel,
  findOnPath,
  installRequirement,
  planInstall,
  getEnv,
  probePlxtoolsModule,
  readStartupPath,
  resolveSettingPath,
  scriptCandidates,
} from '../../src/serverDiscovery';

const posixOnly = process.platform === 'win32' ? describe.skip : describe;

let tmp: string;

function file(rel: string, content = '#!/bin/sh\nexit 0\n', mode = 0o755): string {
  const p = path.join(tmp, rel);
  fs.mkdirSync(path.dirname(p), { recursive: true });
  fs.writeFileSync(p, content);
  fs.chmodSync(p, mode);
  return p;
}

/** A fake virtual environment: `<name>/bin/python` and, optionally, `<name>/bin/plx`. */
function venv(name: string, withPlx: boolean): { python: string; plx: string } {
  const python = file(`${name}/bin/python`);
  const plx = path.join(tmp, name, 'bin', 'plx');
  if (withPlx) {
    file(`${name}/bin/plx`);
  }
  return { python, plx };
}

const never = async (): Promise<boolean> => {
  throw new Error('the module probe should not run here');
};

function input(overrides: Partial<DiscoveryInput>): DiscoveryInput {
  return {
    env: { PATH: '' },
    platform: 'linux',
    hasPlxtoolsModule: async () => false,
    startupPath: async () => undefined,
    loginShellPath: async () => undefined,
    ...overrides,
  };
}

function expectFound(result: DiscoveryResult): Extract<DiscoveryResult, { found: true }> {
  assert.ok(result.found, `expected plx to be found, got: ${result.found ? '' : result.message}`);
  return result;
}

function expectNotFound(result: DiscoveryResult): Extract<DiscoveryResult, { found: false }> {
  assert.ok(!result.found, `expected no plx, got ${result.found ? result.invocation.description : ''}`);
  return result;
}

beforeEach(() => {
  tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'plx-discovery-'));
});

afterEach(() => {
  fs.rmSync(tmp, { recursive: true, force: true });
});

posixOnly('discoverPlx: openplx.server.path', () => {
  it('uses an executable given by path', async () => {
    const plx = file('tools/plx');
    const r = expectFound(await discoverPlx(input({ serverPath: plx })));
    assert.equal(r.invocation.command, plx);
    assert.deepEqual(r.invocation.prefixArgs, []);
    assert.equal(r.invocation.source, 'server.path');
    assert.match(r.invocation.description, /openplx\.server\.path/);
  });

  it('resolves ${workspaceFolder} and relative paths against the workspace folder', async () => {
    const plx = file('ws/.venv/bin/plx');
    const ws = path.join(tmp, 'ws');
    let r = expectFound(await discoverPlx(input({ serverPath: '${workspaceFolder}/.venv/bin/plx', workspaceFolder: ws })));
    assert.equal(r.invocation.command, plx);
    r = expectFound(await discoverPlx(input({ serverPath: './.venv/bin/plx', workspaceFolder: ws })));
    assert.equal(r.invocation.command, plx);
  });

  it('expands ${env:NAME}', async () => {
    const plx = file('opt/plx');
    const r = expectFound(await discoverPlx(input({ serverPath: '${env:PLX_HOME}/plx', env: { PATH: '', PLX_HOME: path.join(tmp, 'opt') } })));
    assert.equal(r.invocation.command, plx);
  });

  it('looks a bare command name up on PATH', async () => {
    const plx = file('bin/plx-dev');
    const r = expectFound(await discoverPlx(input({ serverPath: 'plx-dev', env: { PATH: path.join(tmp, 'bin') } })));
    assert.equal(r.invocation.command, plx);
  });

  it('reports a missing file and does not fall back to other places', async () => {
    const onPath = file('bin/plx');
    const missing = path.join(tmp, 'nowhere', 'plx');
    const r = expectNotFound(
      await discoverPlx(
        input({
          serverPath: missing,
          env: { PATH: path.dirname(onPath) },
          pythonExtensionInterpreter: async () => {
            throw new Error('the Python extension should not be asked');
          },
        }),
      ),
    );
    assert.equal(r.attempts.length, 1);
    assert.equal(r.attempts[0].candidate, missing);
    assert.equal(r.attempts[0].outcome, 'does not exist');
    assert.ok(r.message.includes(missing), r.message);
    assert.ok(r.message.includes('OpenPLX: Install plxtools'), r.message);
  });

  it('reports a file that is not executable', async () => {
    const plx = file('tools/plx', 'not a program', 0o644);
    const r = expectNotFound(await discoverPlx(input({ serverPath: plx })));
    assert.match(r.attempts[0].outcome, /not executable/);
  });

  it('reports a directory', async () => {
    fs.mkdirSync(path.join(tmp, 'plxdir'));
    const r = expectNotFound(await discoverPlx(input({ serverPath: path.join(tmp, 'plxdir') })));
    assert.equal(r.attempts[0].outcome, 'not a file');
  });
});

posixOnly('discoverPlx: openplx.interpreter', () => {
  it('uses plx next to the interpreter (venv/bin/plx)', async () => {
    const { python, plx } = venv('venv', true);
    const r = expectFound(await discoverPlx(input({ interpreter: python, hasPlxtoolsModule: never })));
    assert.equal(r.invocation.command, plx);
    assert.deepEqual(r.invocation.prefixArgs, []);
    assert.equal(r.invocation.source, 'interpreter');
  });

  it('does not follow the interpreter symlink out of the venv', async () => {
    const base = file('base/bin/python3');
    fs.mkdirSync(path.join(tmp, 'venv', 'bin'), { recursive: true });
    const python = path.join(tmp, 'venv', 'bin', 'python');
    fs.symlinkSync(base, python);
    const plx = file('venv/bin/plx');
    const r = expectFound(await discoverPlx(input({ interpreter: python })));
    assert.equal(r.invocation.command, plx);
  });

  it('falls back to `python -m plxtools` when plxtools is importable', async () => {
    const { python } = venv('venv', false);
    const probed: string[] = [];
    const r = expectFound(
      await discoverPlx(
        input({
          interpreter: python,
          hasPlxtoolsModule: async (p) => {
            probed.push(p);
            return true;
          },
        }),
      ),
    );
    assert.deepEqual(probed, [python]);
    assert.equal(r.invocation.command, python);
    assert.deepEqual(r.invocation.prefixArgs, ['-m', 'plxtools']);
    assert.match(r.invocation.description, /-m plxtools/);
  });

  it('fails without falling back to PATH when plxtools is not installed there', async () => {
    const { python } = venv('venv', false);
    const onPath = file('bin/plx');
    const r = expectNotFound(await discoverPlx(input({ interpreter: python, env: { PATH: path.dirname(onPath) } })));
    assert.ok(r.message.includes(`${python} -m pip install "`), r.message);
    assert.ok(r.message.includes('plxtools is not installed in this interpreter'), r.message);
    assert.ok(!r.attempts.some((a) => a.source === 'PATH'));
  });

  it('reports an interpreter that does not exist', async () => {
    const python = path.join(tmp, 'gone', 'bin', 'python');
    const r = expectNotFound(await discoverPlx(input({ interpreter: python, hasPlxtoolsModule: never })));
    assert.ok(r.attempts.some((a) => a.candidate === python && /interpreter does not exist/.test(a.outcome)), r.message);
  });

  it('wins over the Python extension, which is not even asked', async () => {
    const { python, plx } = venv('chosen', true);
    let asked = false;
    const r = expectFound(
      await discoverPlx(
        input({
          interpreter: python,
          pythonExtensionInterpreter: async () => {
            asked = true;
            return venv('other', true).python;
          },
        }),
      ),
    );
    assert.equal(r.invocation.command, plx);
    assert.equal(asked, false);
  });

  it('is ignored when openplx.server.path is set', async () => {
    const plx = file('tools/plx');
    const { python } = venv('venv', true);
    const r = expectFound(await discoverPlx(input({ serverPath: plx, interpreter: python })));
    assert.equal(r.invocation.command, plx);
  });
});

posixOnly('discoverPlx: the Python extension interpreter', () => {
  it('uses plx from the active interpreter (given as a function)', async () => {
    const { python, plx } = venv('active', true);
    const r = expectFound(await discoverPlx(input({ pythonExtensionInterpreter: async () => python })));
    assert.equal(r.invocation.command, plx);
    assert.equal(r.invocation.source, 'python-extension');
  });

  it('accepts a plain string', async () => {
    const { python, plx } = venv('active', true);
    const r = expectFound(await discoverPlx(input({ pythonExtensionInterpreter: python })));
    assert.equal(r.invocation.command, plx);
  });

  it('uses `python -m plxtools` from the active interpreter', async () => {
    const { python } = venv('active', false);
    const r = expectFound(await discoverPlx(input({ pythonExtensionInterpreter: python, hasPlxtoolsModule: async () => true })));
    assert.equal(r.invocation.command, python);
    assert.deepEqual(r.invocation.prefixArgs, ['-m', 'plxtools']);
    assert.equal(r.invocation.source, 'python-extension');
  });

  it('falls through to PATH when the active interpreter has no plxtools', async () => {
    const { python } = venv('active', false);
    const onPath = file('bin/plx');
    const r = expectFound(await discoverPlx(input({ pythonExtensionInterpreter: python, env: { PATH: path.dirname(onPath) } })));
    assert.equal(r.invocation.command, onPath);
    assert.equal(r.invocation.source, 'PATH');
    assert.ok(r.attempts.some((a) => a.source === 'python-extension' && a.outcome !== 'found'));
  });

  it('falls through to PATH when reading the interpreter fails', async () => {
    const onPath = file('bin/plx');
    const r = expectFound(
      await discoverPlx(
        input({
          env: { PATH: path.dirname(onPath) },
          pythonExtensionInterpreter: async () => {
            throw new Error('API changed');
          },
        }),
      ),
    );
    assert.equal(r.invocation.command, onPath);
    assert.match(r.attempts[0].outcome, /could not be read.*API changed/);
  });

  it('skips an empty answer', async () => {
    const onPath = file('bin/plx');
    const r = expectFound(await discoverPlx(input({ env: { PATH: path.dirname(onPath) }, pythonExtensionInterpreter: async () => '  ' })));
    assert.equal(r.invocation.source, 'PATH');
    assert.equal(r.attempts.length, 1);
  });
});

posixOnly('discoverPlx: PATH and the not-found message', () => {
  it('takes the first executable plx on PATH, skipping non-executable files', async () => {
    file('a/plx', 'data', 0o644);
    const good = file('b/plx');
    file('c/plx');
    const PATH = ['', path.join(tmp, 'missing'), path.join(tmp, 'a'), path.join(tmp, 'b'), path.join(tmp, 'c')].join(':');
    const r = expectFound(await discoverPlx(input({ env: { PATH } })));
    assert.equal(r.invocation.command, good);
    assert.match(r.invocation.description, /from PATH/);
  });

  it('says what was tried and how to install when nothing is found', async () => {
    const { python } = venv('active', false);
    const r = expectNotFound(await discoverPlx(input({ pythonExtensionInterpreter: python, env: { PATH: path.join(tmp, 'empty') } })));
    assert.deepEqual(
      r.attempts.map((a) => a.source),
      ['python-extension', 'python-extension', 'PATH', 'login-shell'],
    );
    assert.match(r.message, /^The OpenPLX language server \(plx\) was not found\. Tried: /);
    assert.ok(r.message.includes(path.join(tmp, 'active', 'bin', 'plx')), r.message);
    assert.ok(r.message.includes('plx on PATH [PATH]: not found'), r.message);
    assert.ok(r.message.includes(`${python} -m pip install "<a plxtools wheel or checkout>"`), r.message);
    assert.ok(r.message.includes('OpenPLX: Install plxtools'), r.message);
    assert.ok(r.message.includes('openplx.server.path'), r.message);
    assert.ok(r.message.includes('OpenPLX: Restart server'), r.message);
  });

  it('suggests the bundled wheel, never the unpublished name, when no interpreter is known', async () => {
    const wheel = file('ext/server/plxtools-0.1.0-py3-none-any.whl', 'PK');
    const r = expectNotFound(await discoverPlx(input({ installRequirement: installRequirement(wheel) })));
    assert.ok(r.message.includes(`\`pip install "plxtools[sim] @ file://${wheel}"\``), r.message);
    assert.ok(!/pip install "?plxtools(\[sim\])?"?`/.test(r.message), r.message);
  });
});

posixOnly('discoverPlx: the login shell and the workspace', () => {
  it("uses plx from the login shell's PATH when the process PATH has none (code-server)", async () => {
    const plx = file('shellbin/plx');
    const r = expectFound(await discoverPlx(input({
      env: { PATH: path.join(tmp, 'empty') },
      loginShellPath: async () => [path.join(tmp, 'nothing'), path.dirname(plx)].join(':'),
    })));
    assert.equal(r.invocation.command, plx);
    assert.equal(r.invocation.source, 'login-shell');
    assert.deepEqual(r.attempts.map((a) => a.source), ['PATH', 'login-shell']);
  });

  it('prefers the process PATH and does not start a shell then', async () => {
    const onPath = file('procbin/plx');
    const r = expectFound(await discoverPlx(input({
      env: { PATH: path.dirname(onPath) },
      loginShellPath: async () => { throw new Error('the login shell should not be asked'); },
    })));
    assert.equal(r.invocation.source, 'PATH');
  });

  it("finds plx in the workspace's .venv, then venv, when no PATH has it", async () => {
    file('ws/venv/bin/plx');
    const dotVenv = file('ws/.venv/bin/plx');
    const r = expectFound(await discoverPlx(input({ workspaceFolder: path.join(tmp, 'ws') })));
    assert.equal(r.invocation.command, dotVenv);
    assert.equal(r.invocation.source, 'workspace-venv');
    fs.rmSync(path.join(tmp, 'ws', '.venv'), { recursive: true });
    const r2 = expectFound(await discoverPlx(input({ workspaceFolder: path.join(tmp, 'ws') })));
    assert.equal(r2.invocation.command, path.join(tmp, 'ws', 'venv', 'bin', 'plx'));
  });

  it('lists every place it looked when nothing is found', async () => {
    const r = expectNotFound(await discoverPlx(input({ workspaceFolder: path.join(tmp, 'empty-ws') })));
    assert.deepEqual(r.attempts.map((a) => a.source),
      ['workspace-venv', 'workspace-venv', 'workspace-venv', 'PATH', 'login-shell']);
    assert.ok(r.message.includes(path.join(tmp, 'empty-ws', '.venv', 'bin', 'plx')), r.message);
  });
});

posixOnly("discoverPlx: the workspace's environment before any PATH (as ruff's extension)", () => {
  it('prefers the workspace .venv over a global plx on every PATH', async () => {
    const dotVenv = file('ws/.venv/bin/plx');
    const global = file('usr-local-bin/plx');
    const r = expectFound(await discoverPlx(input({
      workspaceFolder: path.join(tmp, 'ws'),
      env: { PATH: path.dirname(global) },
      startupPath: async () => path.dirname(global),
      loginShellPath: async () => { throw new Error('the login shell should not be asked'); },
    })));
    assert.equal(r.invocation.command, dotVenv);
    assert.equal(r.invocation.source, 'workspace-venv');
    assert.deepEqual(r.attempts.map((a) => a.source), ['workspace-venv']);
  });

  it('then venv/, and only then PATH', async () => {
    const venvPlx = file('ws/venv/bin/plx');
    const global = file('usr-local-bin/plx');
    const r = expectFound(await discoverPlx(input({ workspaceFolder: path.join(tmp, 'ws'), env: { PATH: path.dirname(global) } })));
    assert.equal(r.invocation.command, venvPlx);
    fs.rmSync(path.join(tmp, 'ws', 'venv'), { recursive: true });
    const r2 = expectFound(await discoverPlx(input({ workspaceFolder: path.join(tmp, 'ws'), env: { PATH: path.dirname(global) } })));
    assert.equal(r2.invocation.command, global);
    assert.deepEqual(r2.attempts.map((a) => a.source), ['workspace-venv', 'workspace-venv', 'workspace-venv', 'PATH']);
  });

  it("puts the Python extension's interpreter first: the user chose it", async () => {
    const chosen = venv('elsewhere', true);
    file('ws/.venv/bin/plx');
    const r = expectFound(await discoverPlx(input({ workspaceFolder: path.join(tmp, 'ws'), pythonExtensionInterpreter: chosen.python })));
    assert.equal(r.invocation.command, chosen.plx);
    assert.equal(r.invocation.source, 'python-extension');
  });

  it("falls back to the workspace .venv when the Python extension's interpreter has no plxtools", async () => {
    const global = venv('global-python', false);
    const dotVenv = file('ws/.venv/bin/plx');
    const r = expectFound(await discoverPlx(input({ workspaceFolder: path.join(tmp, 'ws'), pythonExtensionInterpreter: global.python })));
    assert.equal(r.invocation.command, dotVenv);
  });
});

posixOnly('install plan ("OpenPLX: Install plxtools")', () => {
  const req = 'plxtools[sim] @ file:///ext/server/plxtools-0.1.0-py3-none-any.whl';

  it('installs into the workspace .venv when there is one', () => {
    const { python } = venv('ws/.venv', false);
    assert.deepEqual(planInstall({ requirement: req, workspaceFolder: path.join(tmp, 'ws') }), { python, requirement: req });
  });

  it("else into the Python extension's interpreter when it is a virtual environment", () => {
    const { python } = venv('proj-env', false);
    file('proj-env/pyvenv.cfg', 'home = /usr/bin\n', 0o644);
    const plan = planInstall({ requirement: req, workspaceFolder: path.join(tmp, 'ws'), pythonExtensionInterpreter: python });
    assert.deepEqual(plan, { python, requirement: req });
  });

  it('else makes a .venv in the workspace (never pip into a system interpreter)', () => {
    const system = file('usr/bin/python3');
    const plan = planInstall({ requirement: req, workspaceFolder: path.join(tmp, 'ws'), pythonExtensionInterpreter: system });
    assert.deepEqual(plan, {
      python: path.join(tmp, 'ws', '.venv', 'bin', 'python'),
      createVenv: { base: system, folder: path.join(tmp, 'ws', '.venv') },
      requirement: req,
    });
    assert.equal(planInstall({ requirement: req }), undefined);
  });

  it('installs the wheel the extension carries; nothing by the unpublished name', () => {
    assert.equal(installRequirement(undefined), undefined);
    const wheel = file('ext dir/server/plxtools-0.1.0-py3-none-any.whl', 'PK');
    file('ext dir/server/notes.txt', '', 0o644);
    assert.equal(findBundledWheel(path.join(tmp, 'ext dir')), wheel);
    assert.equal(findBundledWheel(path.join(tmp, 'nowhere')), undefined);
    assert.equal(installRequirement(wheel), `plxtools[sim] @ file://${encodeURI(wheel)}`);
  });
});

posixOnly('discoverPlx: the PATH the editor was started with (code-server)', () => {
  // Under code-server the extension host's PATH is the login shell's (here with a pyenv shim that
  // runs some other plx); the shell that started code-server had the project's venv on its PATH.
  it("prefers plx on the PATH code-server was started with over the extension host's PATH", async () => {
    const venvPlx = file('project/.venv/bin/plx');
    file('shims/plx');
    const r = expectFound(await discoverPlx(input({
      env: { PATH: [path.join(tmp, 'remote-cli'), path.join(tmp, 'shims')].join(':') },
      startupPath: async () => [path.dirname(venvPlx), path.join(tmp, 'shims')].join(':'),
      loginShellPath: async () => { throw new Error('the login shell should not be asked'); },
    })));
    assert.equal(r.invocation.command, venvPlx);
    assert.equal(r.invocation.source, 'startup-PATH');
    assert.match(r.invocation.description, /from the PATH the editor was started with/);
    assert.deepEqual(r.attempts.map((a) => a.source), ['startup-PATH']);
  });

  it("falls through to the extension host's PATH, then the login shell, when it has no plx", async () => {
    const shellPlx = file('shellbin/plx');
    const r = expectFound(await discoverPlx(input({
      env: { PATH: path.join(tmp, 'empty') },
      startupPath: async () => path.join(tmp, 'nothing'),
      loginShellPath: async () => path.dirname(shellPlx),
    })));
    assert.equal(r.invocation.source, 'login-shell');
    assert.deepEqual(r.attempts.map((a) => [a.source, a.outcome]), [
      ['startup-PATH', 'not found'],
      ['PATH', 'not found'],
      ['login-shell', 'found'],
    ]);
  });

  it("is not searched twice when it equals the extension host's PATH", async () => {
    const r = expectNotFound(await discoverPlx(input({
      env: { PATH: path.join(tmp, 'empty') },
      startupPath: async () => path.join(tmp, 'empty'),
    })));
    assert.deepEqual(r.attempts.map((a) => a.source), ['PATH', 'login-shell']);
  });

  it('is not asked when openplx.server.path is set', async () => {
    const plx = file('given/plx');
    const r = expectFound(await discoverPlx(input({
      serverPath: plx,
      startupPath: async () => { throw new Error('the startup PATH should not be read'); },
    })));
    assert.equal(r.invocation.source, 'server.path');
  });

  const linuxOnly = process.platform === 'linux' ? it : it.skip;
  linuxOnly("readStartupPath reads the PATH a process was started with from /proc", async () => {
    const PATH = [path.join(tmp, 'a b'), '/usr/bin', '/bin'].join(':');
    const child = spawn(process.execPath, ['-e', 'process.env.PATH = "changed"; setTimeout(() => {}, 10000)'], {
      env: { PATH, OTHER: 'x' },
      stdio: 'ignore',
    });
    try {
      await new Promise((resolve) => setTimeout(resolve, 300));
      assert.equal(await readStartupPath(child.pid), PATH);
    } finally {
      child.kill();
    }
    assert.equal(await readStartupPath(2 ** 22 + 12345), undefined);
  });
});

describe('discoverPlx: Windows file layout (simulated)', () => {
  const win = (overrides: Partial<DiscoveryInput>): DiscoveryInput => input({ platform: 'win32', ...overrides });

  it('finds Scripts\\plx.exe next to a venv interpreter', async () => {
    const python = file('venv/Scripts/python.exe', '', 0o644);
    const plx = file('venv/Scripts/plx.exe', '', 0o644);
    const r = expectFound(await discoverPlx(win({ interpreter: python })));
    assert.equal(r.invocation.command, plx);
  });

  it('finds Scripts\\plx.exe below a base interpreter', async () => {
    const python = file('Python311/python.exe', '', 0o644);
    const plx = file('Python311/Scripts/plx.exe', '', 0o644);
    const r = expectFound(await discoverPlx(win({ interpreter: python })));
    assert.equal(r.invocation.command, plx);
  });

  it('searches PATH with ; and PATHEXT, with any casing of the variable names', async () => {
    file('tools/plx', '', 0o644); // no extension: not a Windows program
    const plx = file('tools/plx.exe', '', 0o644);
    const env = { Path: `${path.join(tmp, 'none')};${path.join(tmp, 'tools')}`, PathExt: '.COM;.EXE;.BAT' };
    const r = expectFound(await discoverPlx(win({ env })));
    assert.equal(r.invocation.command, plx);
  });

  it('lists Windows candidates for an interpreter', () => {
    const dir = path.join('C:', 'venv', 'Scripts');
    assert.deepEqual(scriptCandidates(path.join(dir, 'python.exe'), 'win32'), [
      path.join(dir, 'plx.exe'),
      path.join(dir, 'Scripts', 'plx.exe'),
    ]);
  });
});

describe('helpers', () => {
  it('resolveSettingPath expands ~ and ${userHome}, keeps bare names', () => {
    const opts = { env: {}, platform: 'linux' as const, command: true };
    assert.equal(resolveSettingPath('~/venv/bin/plx', opts), path.join(os.homedir(), 'venv/bin/plx'));
    assert.equal(resolveSettingPath('${userHome}/x/plx', opts), path.join(os.homedir(), 'x/plx'));
    assert.equal(resolveSettingPath('  plx  ', opts), 'plx');
    // Not a command: a bare name is a relative path.
    assert.equal(resolveSettingPath('bundles', { ...opts, command: false, workspaceFolder: '/ws' }), path.resolve('/ws', 'bundles'));
  });

  it('getEnv is case-insensitive on Windows only', () => {
    assert.equal(getEnv({ Path: 'a' }, 'PATH', 'win32'), 'a');
    assert.equal(getEnv({ Path: 'a' }, 'PATH', 'linux'), undefined);
  });

  posixOnly('on POSIX', () => {
    it('findOnPath ignores empty and quoted entries', () => {
      const plx = file('q/plx');
      assert.equal(findOnPath('plx', { PATH: `::"${path.join(tmp, 'q')}"` }, 'linux'), plx);
    });

    it('probePlxtoolsModule asks the interpreter (exit 0 = installed)', async () => {
      const yes = file('yes/python', '#!/bin/sh\nexit 0\n');
      const no = file('no/python', '#!/bin/sh\nexit 3\n');
      assert.equal(await probePlxtoolsModule(yes, process.env), true);
      assert.equal(await probePlxtoolsModule(no, process.env), false);
      assert.equal(await probePlxtoolsModule(path.join(tmp, 'missing'), process.env), false);
    });

    it('probePlxtoolsModule works with a real Python when one is on PATH', async function () {
      const python = findOnPath('python3', process.env, process.platform);
      if (!python) {
        this.skip();
      }
      // The stdlib module `json` is always there; plxtools may or may not be.
      assert.equal(typeof (await probePlxtoolsModule(python, process.env)), 'boolean');
    });
  });
});
