/**
 * Finds the `plx` command that runs the OpenPLX language server (and the `check` CLI).
 *
 * Pure Node: this module must not import `vscode`. Everything it needs (settings, environment,
 * platform, the Python extension's interpreter) comes in as plain inputs, so it can be unit-tested
 * under plain Node with mocha.
 *
 * Order:
 *  1. `openplx.server.path`: a `plx` executable. Explicit, so a wrong value is an error (no fallback).
 *  2. `openplx.interpreter`: a Python interpreter. Use `plx` from that interpreter's scripts folder,
 *     else `<python> -m plxtools` when the package is importable there. Explicit, so no fallback.
 *  3. The Python extension's active interpreter (same two checks). Implicit: on failure, go on.
 *  4. A virtual environment in the workspace: `.venv`, `venv`, `env` (`bin/plx`, `Scripts\plx.exe`).
 *     The project's own environment wins over a `plx` installed globally, as ruff's extension does.
 *  5. `plx` on the PATH the editor was started with: the environment the extension host's parent
 *     process (the code-server or VS Code server process) was started with, read from
 *     `/proc/<ppid>/environ` (Linux only). A VS Code server (code-server, Remote-SSH) replaces the
 *     extension host's PATH with the login shell's, so without this step the PATH of the shell that
 *     started code-server (say, with a virtual environment activated) is never searched.
 *     Skipped when it cannot be read or equals the extension host's PATH.
 *  6. `plx` on the PATH of the extension host process.
 *  7. `plx` on the PATH of the user's login shell (editors started from a desktop menu, or
 *     code-server started by a service, may not have the shell's PATH). Not on Windows.
 */
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { execFile } from 'node:child_process';

/**
 * Whether `plxtools` is on PyPI under that name. Until it is, installing by name would fail, or
 * install whatever someone else registered: the extension installs the wheel it carries instead
 * (`server/plxtools-VERSION-py3-none-any.whl`, built from the same commit as the extension).
 */
export const PUBLISHED_ON_PYPI = false;

/** The pip requirement for plxtools with its simulation extra (check and simulate need it). */
export function installRequirement(bundledWheel: string | undefined): string | undefined {
  if (bundledWheel) {
    return `plxtools[sim] @ ${pathToFileUrl(bundledWheel)}`;
  }
  return PUBLISHED_ON_PYPI ? 'plxtools[sim]' : undefined;
}

function pathToFileUrl(p: string): string {
  const forward = p.replace(/\\/g, '/');
  return encodeURI(`file://${forward.startsWith('/') ? '' : '/'}${forward}`);
}

/** The wheel bundled in the extension (`<extension>/server/plxtools-*.whl`), or undefined. */
export function findBundledWheel(extensionPath: string): string | undefined {
  const dir = path.join(extensionPath, 'server');
  try {
    const wheel = fs.readdirSync(dir).filter((n) => /^plxtools-.*\.whl$/.test(n)).sort().pop();
    return wheel ? path.join(dir, wheel) : undefined;
  } catch {
    return undefined;
  }
}

/** The shell line that installs plxtools for `python` (`pip install ...` when no interpreter is known). */
export function installCommandLine(requirement: string | undefined, python?: string): string {
  const req = requirement ?? '<a plxtools wheel or checkout>';
  const quoted = `"${req}"`;
  return python ? `${quoteForShell(python)} -m pip install ${quoted}` : `pip install ${quoted}`;
}

/** How "OpenPLX: Install plxtools" installs: into which interpreter, creating a `.venv` first if needed. */
export interface InstallPlan {
  /** The interpreter pip runs in (created by the first step when `createVenv`). */
  python: string;
  /** `python3 -m venv <workspace>/.venv` first. */
  createVenv?: { base: string; folder: string };
  requirement: string;
}

/**
 * Where to install: the workspace's existing virtual environment, else the Python extension's
 * interpreter when it is a virtual environment, else a new `.venv` in the workspace (made with the
 * Python extension's interpreter, else `python3`). Never a system interpreter: pip refuses those
 * (PEP 668), and a global install would shadow nothing the workspace can see.
 */
export function planInstall(opts: {
  requirement: string;
  workspaceFolder?: string;
  pythonExtensionInterpreter?: string;
  platform?: NodeJS.Platform;
}): InstallPlan | undefined {
  const platform = opts.platform ?? process.platform;
  const pythonIn = (venvDir: string) => platform === 'win32'
    ? path.join(venvDir, 'Scripts', 'python.exe')
    : path.join(venvDir, 'bin', 'python');
  if (opts.workspaceFolder) {
    for (const name of WORKSPACE_VENVS) {
      const python = pythonIn(path.join(opts.workspaceFolder, name));
      if (isExecutableFile(python, platform)) {
        return { python, requirement: opts.requirement };
      }
    }
  }
  const ext = opts.pythonExtensionInterpreter;
  if (ext && isVenvInterpreter(ext)) {
    return { python: ext, requirement: opts.requirement };
  }
  if (!opts.workspaceFolder) {
    return undefined;
  }
  const folder = path.join(opts.workspaceFolder, '.venv');
  return {
    python: pythonIn(folder),
    createVenv: { base: ext ?? (platform === 'win32' ? 'python' : 'python3'), folder },
    requirement: opts.requirement,
  };
}

/** True when `python` belongs to a virtual environment (a `pyvenv.cfg` one or two folders up). */
export function isVenvInterpreter(python: string): boolean {
  const bin = path.dirname(python);
  return [path.dirname(bin), bin].some((d) => fs.existsSync(path.join(d, 'pyvenv.cfg')));
}

export type PlxSource =
  | 'server.path'
  | 'interpreter'
  | 'python-extension'
  | 'startup-PATH'
  | 'PATH'
  | 'login-shell'
  | 'workspace-venv';

/** How to run `plx <subcommand>`: `command ...prefixArgs <subcommand> ...`. */
export interface PlxInvocation {
  /** The executable to spawn: a `plx` executable or a Python interpreter. */
  command: string;
  /** Arguments before the plx subcommand: `[]` for `plx`, `['-m', 'plxtools']` for a Python interpreter. */
  prefixArgs: string[];
  /** Which discovery step found it. */
  source: PlxSource;
  /** One line for logs and the status item, e.g. `/venv/bin/plx (from openplx.interpreter)`. */
  description: string;
}

export type Env = Record<string, string | undefined>;

export interface DiscoveryInput {
  /** Value of `openplx.server.path` (empty or undefined when unset). */
  serverPath?: string;
  /** Value of `openplx.interpreter` (empty or undefined when unset). */
  interpreter?: string;
  /**
   * The Python extension's active interpreter, or a function that returns it. A function is only
   * called when steps 1 and 2 do not apply, so the caller can avoid activating the Python extension.
   */
  pythonExtensionInterpreter?: string | (() => Promise<string | undefined>);
  /** Environment used for PATH lookup, variable substitution and probing interpreters. */
  env: Env;
  /** Defaults to `process.platform`. Only affects file names (`plx.exe`, `Scripts`) and PATH syntax. */
  platform?: NodeJS.Platform;
  /** Used for `${workspaceFolder}` and for resolving relative paths in settings. */
  workspaceFolder?: string;
  /** Returns true when `import plxtools` would work in `python`. Injectable for tests. */
  hasPlxtoolsModule?: (python: string, env: Env) => Promise<boolean>;
  /**
   * The PATH the editor process was started with (undefined when it cannot be read). Defaults to
   * {@link readStartupPath}. Injectable for tests.
   */
  startupPath?: () => Promise<string | undefined>;
  /** The PATH of the user's login shell (undefined when it cannot be read). Injectable for tests. */
  loginShellPath?: (env: Env) => Promise<string | undefined>;
  /** What the "not found" message tells users to install (see {@link installRequirement}). */
  installRequirement?: string;
}

/** Folders of a workspace where a virtual environment usually lives. */
export const WORKSPACE_VENVS = ['.venv', 'venv', 'env'];

/**
 * The PATH in the environment process `pid` (by default the extension host's parent) was started
 * with, from `/proc/<pid>/environ`. Undefined where there is no /proc (Windows, macOS) or the file
 * cannot be read. The file holds the environment given at exec time, so it is the PATH of the shell
 * (or service) that started code-server, whatever the server did to its own `process.env` later.
 */
export async function readStartupPath(pid: number = process.ppid): Promise<string | undefined> {
  if (process.platform !== 'linux' || !pid) {
    return undefined;
  }
  try {
    const environ = await fs.promises.readFile(`/proc/${pid}/environ`, 'utf8');
    const entry = environ.split('\0').find((e) => e.startsWith('PATH='));
    return entry === undefined ? undefined : entry.slice('PATH='.length);
  } catch {
    return undefined;
  }
}

/** Asks `$SHELL -lc` for its PATH (2 s at most); undefined when there is no such shell or it fails. */
export function readLoginShellPath(env: Env): Promise<string | undefined> {
  const shell = env.SHELL;
  if (!shell || process.platform === 'win32') {
    return Promise.resolve(undefined);
  }
  return new Promise((resolve) => {
    execFile(shell, ['-lc', 'printf "%s" "$PATH"'], { env: env as NodeJS.ProcessEnv, timeout: 2000 }, (err, stdout) => {
      resolve(err || !stdout ? undefined : String(stdout).trim());
    });
  });
}

export interface Attempt {
  source: PlxSource;
  /** What was looked at (a path, or `plx on PATH`). */
  candidate: string;
  /** Why it was not used, or `found`. */
  outcome: string;
}

export type DiscoveryResult =
  | { found: true; invocation: PlxInvocation; attempts: Attempt[] }
  | { found: false; attempts: Attempt[]; message: string };

/** Looks up the value of an environment variable; on Windows names are case-insensitive. */
export function getEnv(env: Env, name: string, platform: NodeJS.Platform = process.platform): string | undefined {
  if (platform !== 'win32') {
    return env[name];
  }
  const key = Object.keys(env).find((k) => k.toUpperCase() === name.toUpperCase());
  return key === undefined ? undefined : env[key];
}

/**
 * Expands `~`, `${userHome}`, `${workspaceFolder}` and `${env:NAME}` in a setting value and makes a
 * relative path absolute (against the workspace folder, else the current directory).
 * With `command: true`, a bare name without a path separator (e.g. `plx`) is returned unchanged so
 * that it can be looked up on PATH.
 */
export function resolveSettingPath(
  value: string,
  opts: { env: Env; workspaceFolder?: string; platform?: NodeJS.Platform; command?: boolean },
): string {
  const platform = opts.platform ?? process.platform;
  const home = os.homedir();
  let v = value.trim();
  v = v.replace(/\$\{userHome\}/g, home);
  v = v.replace(/\$\{env:([^}]+)\}/g, (_m, name: string) => getEnv(opts.env, name, platform) ?? '');
  if (opts.workspaceFolder !== undefined) {
    v = v.replace(/\$\{workspaceFolder\}/g, opts.workspaceFolder);
  }
  if (v === '~' || v.startsWith('~/') || v.startsWith('~\\')) {
    v = path.join(home, v.slice(1));
  }
  if (opts.command && !hasPathSeparator(v, platform)) {
    return v;
  }
  if (!path.isAbsolute(v)) {
    v = path.resolve(opts.workspaceFolder ?? process.cwd(), v);
  }
  return v;
}

/** Why `file` cannot be run (`does not exist`, `not a file`, `is not executable`), or undefined if it can. */
function executableProblem(file: string, platform: NodeJS.Platform): string | undefined {
  try {
    if (!fs.statSync(file).isFile()) {
      return 'not a file';
    }
    if (platform !== 'win32') {
      fs.accessSync(file, fs.constants.X_OK);
    }
    return undefined;
  } catch (e) {
    const code = (e as NodeJS.ErrnoException).code;
    if (code === 'ENOENT' || code === 'ENOTDIR') {
      return 'does not exist';
    }
    return code === 'EACCES' ? 'is not executable' : `cannot be used (${code ?? String(e)})`;
  }
}

/** True when `file` exists, is a file, and (outside Windows) is executable. */
export function isExecutableFile(file: string, platform: NodeJS.Platform = process.platform): boolean {
  return executableProblem(file, platform) === undefined;
}

/**
 * Where pip puts the `plx` script for an interpreter: next to it (`venv/bin/python` ->
 * `venv/bin/plx`, `venv\Scripts\python.exe` -> `venv\Scripts\plx.exe`) or, for a base install on
 * Windows, in `Scripts\` below it (`C:\Python311\python.exe` -> `C:\Python311\Scripts\plx.exe`).
 * The interpreter path is not resolved through symlinks: a venv's `python` is a symlink to the base
 * interpreter, and following it would leave the venv.
 */
export function scriptCandidates(python: string, platform: NodeJS.Platform = process.platform): string[] {
  const dir = path.dirname(python);
  if (platform === 'win32') {
    return [path.join(dir, 'plx.exe'), path.join(dir, 'Scripts', 'plx.exe')];
  }
  return [path.join(dir, 'plx')];
}

/** Default probe: asks the interpreter whether `plxtools` can be imported (without importing it). */
export function probePlxtoolsModule(python: string, env: Env): Promise<boolean> {
  const code = 'import importlib.util, sys; sys.exit(0 if importlib.util.find_spec("plxtools") else 3)';
  return new Promise((resolve) => {
    execFile(python, ['-c', code], { env: env as NodeJS.ProcessEnv, timeout: 15000, windowsHide: true }, (err) => {
      resolve(!err);
    });
  });
}

/**
 * Searches PATH for an executable called `name`. On Windows the PATHEXT extensions are tried in
 * order (pip creates `plx.exe` launchers) unless `name` already has an extension.
 */
export function findOnPath(name: string, env: Env, platform: NodeJS.Platform = process.platform): string | undefined {
  const pathValue = getEnv(env, 'PATH', platform) ?? '';
  const delimiter = platform === 'win32' ? ';' : ':';
  let names = [name];
  if (platform === 'win32' && !/\.[A-Za-z0-9]+$/.test(name)) {
    const exts = (getEnv(env, 'PATHEXT', platform) ?? '.COM;.EXE;.BAT;.CMD')
      .split(';')
      .map((e) => e.trim().toLowerCase())
      .filter((e) => e.startsWith('.'));
    names = exts.map((e) => name + e);
  }
  for (const rawDir of pathValue.split(delimiter)) {
    const dir = rawDir.trim().replace(/^"(.*)"$/, '$1');
    if (!dir) {
      continue;
    }
    for (const n of names) {
      const candidate = path.join(dir, n);
      if (isExecutableFile(candidate, platform)) {
        return candidate;
      }
    }
  }
  return undefined;
}

/** Steps 2 and 3: `plx` next to the interpreter, else `<python> -m plxtools`. Records attempts. */
async function fromInterpreter(
  python: string,
  source: 'interpreter' | 'python-extension',
  label: string,
  input: DiscoveryInput,
  platform: NodeJS.Platform,
  attempts: Attempt[],
): Promise<PlxInvocation | undefined> {
  for (const candidate of scriptCandidates(python, platform)) {
    const problem = executableProblem(candidate, platform);
    if (!problem) {
      attempts.push({ source, candidate, outcome: 'found' });
      return { command: candidate, prefixArgs: [], source, description: `${candidate} (from ${label})` };
    }
    attempts.push({ source, candidate, outcome: problem });
  }
  const pythonProblem = executableProblem(python, platform);
  if (pythonProblem) {
    attempts.push({ source, candidate: python, outcome: `interpreter ${pythonProblem}` });
    return undefined;
  }
  const probe = input.hasPlxtoolsModule ?? probePlxtoolsModule;
  const candidate = `${python} -m plxtools`;
  if (await probe(python, input.env)) {
    attempts.push({ source, candidate, outcome: 'found' });
    return { command: python, prefixArgs: ['-m', 'plxtools'], source, description: `${candidate} (from ${label})` };
  }
  attempts.push({ source, candidate, outcome: 'plxtools is not installed in this interpreter' });
  return undefined;
}

function quoteForShell(p: string): string {
  return /[\s"'$`]/.test(p) ? `"${p}"` : p;
}

/** The "not found" message: what was tried, and how to install. */
export function notFoundMessage(attempts: Attempt[], python?: string, requirement?: string): string {
  const tried = attempts.length
    ? attempts.map((a) => `${a.candidate} [${a.source}]: ${a.outcome}`).join('; ')
    : 'nothing';
  return (
    `The OpenPLX language server (plx) was not found. Tried: ${tried}. ` +
    'Run "OpenPLX: Install plxtools" (into the workspace\'s virtual environment), or install it yourself with ' +
    `\`${installCommandLine(requirement, python)}\` (in the Python environment you use for OpenPLX), ` +
    'or set `openplx.server.path` to the plx executable, then run "OpenPLX: Restart server".'
  );
}

function hasPathSeparator(value: string, platform: NodeJS.Platform): boolean {
  return value.includes('/') || (platform === 'win32' && value.includes('\\'));
}

function plxFound(attempts: Attempt[], command: string, source: PlxSource, label: string): DiscoveryResult {
  attempts.push({ source, candidate: command, outcome: 'found' });
  return {
    found: true,
    attempts,
    invocation: { command, prefixArgs: [], source, description: `${command} (from ${label})` },
  };
}

export async function discoverPlx(input: DiscoveryInput): Promise<DiscoveryResult> {
  const platform = input.platform ?? process.platform;
  const resolveOpts = { env: input.env, workspaceFolder: input.workspaceFolder, platform, command: true };
  const attempts: Attempt[] = [];

  // 1. openplx.server.path: a path, or a command name looked up on PATH.
  const serverPath = input.serverPath?.trim();
  if (serverPath) {
    const resolved = resolveSettingPath(serverPath, resolveOpts);
    if (hasPathSeparator(resolved, platform)) {
      const problem = executableProblem(resolved, platform);
      if (!problem) {
        return plxFound(attempts, resolved, 'server.path', 'openplx.server.path');
      }
      attempts.push({ source: 'server.path', candidate: resolved, outcome: problem });
    } else {
      const onPath = findOnPath(resolved, input.env, platform);
      if (onPath) {
        return plxFound(attempts, onPath, 'server.path', 'openplx.server.path');
      }
      attempts.push({ source: 'server.path', candidate: resolved, outcome: 'not found on PATH' });
    }
    return { found: false, attempts, message: notFoundMessage(attempts, undefined, input.installRequirement) };
  }

  // 2. openplx.interpreter
  const interpreter = input.interpreter?.trim();
  if (interpreter) {
    const resolved = resolveSettingPath(interpreter, resolveOpts);
    const python = hasPathSeparator(resolved, platform) ? resolved : findOnPath(resolved, input.env, platform) ?? resolved;
    const invocation = await fromInterpreter(python, 'interpreter', 'openplx.interpreter', input, platform, attempts);
    if (invocation) {
      return { found: true, attempts, invocation };
    }
    return { found: false, attempts, message: notFoundMessage(attempts, python, input.installRequirement) };
  }

  // 3. The Python extension's active interpreter. Failing here is not final.
  let extPython: string | undefined;
  const source = input.pythonExtensionInterpreter;
  try {
    extPython = (typeof source === 'function' ? await source() : source)?.trim() || undefined;
  } catch (e) {
    attempts.push({ source: 'python-extension', candidate: 'active interpreter', outcome: `could not be read (${String(e)})` });
  }
  if (extPython) {
    const invocation = await fromInterpreter(extPython, 'python-extension', 'the Python extension', input, platform, attempts);
    if (invocation) {
      return { found: true, attempts, invocation };
    }
  }

  // 4. A virtual environment in the workspace: before any PATH, so a global plx does not shadow the project's
  if (input.workspaceFolder) {
    for (const name of WORKSPACE_VENVS) {
      const candidate = platform === 'win32'
        ? path.join(input.workspaceFolder, name, 'Scripts', 'plx.exe')
        : path.join(input.workspaceFolder, name, 'bin', 'plx');
      const problem = executableProblem(candidate, platform);
      if (!problem) {
        return plxFound(attempts, candidate, 'workspace-venv', `the workspace's ${name}`);
      }
      attempts.push({ source: 'workspace-venv', candidate, outcome: problem });
    }
  }
  // 5. The PATH the editor was started with (before the extension host's own, which a VS Code
  //    server sets to the login shell's PATH).
  if (platform !== 'win32') {
    const startupPath = await (input.startupPath ?? readStartupPath)();
    if (startupPath && startupPath !== getEnv(input.env, 'PATH', platform)) {
      const onStartupPath = findOnPath('plx', { ...input.env, PATH: startupPath }, platform);
      if (onStartupPath) {
        return plxFound(attempts, onStartupPath, 'startup-PATH', 'the PATH the editor was started with');
      }
      attempts.push({ source: 'startup-PATH', candidate: 'plx on the PATH the editor was started with', outcome: 'not found' });
    }
  }

  // 6. The extension host's PATH
  const onPath = findOnPath('plx', input.env, platform);
  if (onPath) {
    return plxFound(attempts, onPath, 'PATH', 'PATH');
  }
  attempts.push({ source: 'PATH', candidate: 'plx on PATH', outcome: 'not found' });

  // 7. The login shell's PATH
  if (platform !== 'win32') {
    const shellPath = await (input.loginShellPath ?? readLoginShellPath)(input.env);
    const onShellPath = shellPath ? findOnPath('plx', { ...input.env, PATH: shellPath }, platform) : undefined;
    if (onShellPath) {
      return plxFound(attempts, onShellPath, 'login-shell', "the login shell's PATH");
    }
    attempts.push({ source: 'login-shell', candidate: "plx on the login shell's PATH",
                    outcome: shellPath ? 'not found' : 'could not be read' });
  }

  return { found: false, attempts, message: notFoundMessage(attempts, extPython, input.installRequirement) };
}
