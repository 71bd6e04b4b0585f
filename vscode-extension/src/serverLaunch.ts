/**
 * Turns a discovered `plx` invocation plus the user's settings into concrete process launches:
 * the language server (`plx lsp`) and the scene checks (`plx check [--simulate] FILE`).
 *
 * Pure Node (no `vscode` import): the extension hands the result to vscode-languageclient, and the
 * integration test spawns exactly the same command line itself.
 */
import { spawn, type ChildProcessWithoutNullStreams } from 'node:child_process';
import { type Env, type PlxInvocation, resolveSettingPath } from './serverDiscovery';

export const BUNDLE_PATH_ENV = 'OPENPLX_BUNDLE_PATH';

export interface LaunchSettings {
  /** `openplx.server.args`: extra arguments appended after `lsp`. */
  serverArgs?: string[];
  /** `openplx.bundlePath`: extra OpenPLX bundle folder(s). Empty or undefined when unset. */
  bundlePath?: string;
  /** The environment to start from (usually `process.env`). Not modified. */
  env: Env;
  /** For `${workspaceFolder}` and relative paths; also the server's working directory. */
  workspaceFolder?: string;
  platform?: NodeJS.Platform;
}

export interface InitializationOptions {
  bundlePath?: string;
}

export interface ProcessSpec {
  command: string;
  args: string[];
  /** A complete environment for the child. */
  env: Record<string, string>;
  cwd?: string;
}

export interface ServerLaunch extends ProcessSpec {
  initializationOptions: InitializationOptions;
}

/**
 * The bundle path with variables expanded and each folder made absolute, or undefined when unset.
 * Like OPENPLX_BUNDLE_PATH it may list several folders, separated by `:` (`;` on Windows).
 */
export function resolvedBundlePath(settings: LaunchSettings): string | undefined {
  const delimiter = (settings.platform ?? process.platform) === 'win32' ? ';' : ':';
  const folders = (settings.bundlePath ?? '')
    .split(delimiter)
    .map((p) => p.trim())
    .filter((p) => p.length > 0)
    .map((p) =>
      resolveSettingPath(p, { env: settings.env, workspaceFolder: settings.workspaceFolder, platform: settings.platform }),
    );
  return folders.length ? folders.join(delimiter) : undefined;
}

function childEnv(settings: LaunchSettings): Record<string, string> {
  const env: Record<string, string> = {};
  for (const [k, v] of Object.entries(settings.env)) {
    if (v !== undefined) {
      env[k] = v;
    }
  }
  const bundlePath = resolvedBundlePath(settings);
  if (bundlePath) {
    env[BUNDLE_PATH_ENV] = bundlePath;
  }
  return env;
}

/** `plx <subcommand...>` as a process spec (same environment rules as the server). */
export function plxCommand(invocation: PlxInvocation, subcommand: string[], settings: LaunchSettings): ProcessSpec {
  return {
    command: invocation.command,
    args: [...invocation.prefixArgs, ...subcommand],
    env: childEnv(settings),
    cwd: settings.workspaceFolder,
  };
}

/** The language server launch: `plx lsp [server.args...]` plus its initializationOptions. */
export function serverLaunch(invocation: PlxInvocation, settings: LaunchSettings): ServerLaunch {
  const bundlePath = resolvedBundlePath(settings);
  const args = (settings.serverArgs ?? []).filter((a) => typeof a === 'string' && a.length > 0);
  return {
    ...plxCommand(invocation, ['lsp', ...args], settings),
    initializationOptions: bundlePath ? { bundlePath } : {},
  };
}

/** Arguments for "Check this scene" / "Check and simulate this scene". */
export function checkArgs(file: string, simulate: boolean): string[] {
  return simulate ? ['check', '--simulate', file] : ['check', file];
}

/** Arguments for "View scene": `plx view FILE` (MuJoCo's viewer window, reloaded when FILE is saved). */
export function viewArgs(file: string): string[] {
  return ['view', file];
}

/** Starts a process spec with piped stdio (used by the Node-side integration test). */
export function spawnProcess(spec: ProcessSpec): ChildProcessWithoutNullStreams {
  return spawn(spec.command, spec.args, { env: spec.env, cwd: spec.cwd, stdio: 'pipe', windowsHide: true });
}
