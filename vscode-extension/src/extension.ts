import * as path from 'node:path';
import * as vscode from 'vscode';
import {
  LanguageClient,
  type LanguageClientOptions,
  RevealOutputChannelOn,
  type ServerOptions,
  TransportKind,
} from 'vscode-languageclient/node';
import { disposePreview, openPreview } from './preview';
import { activePythonInterpreter, onPythonInterpreterChanged } from './python';
import { discoverPlx, type DiscoveryResult, type PlxInvocation } from './serverDiscovery';
import { installRequirementOf, runInstall } from './install';
import { checkArgs, type LaunchSettings, plxCommand, serverLaunch, viewArgs } from './serverLaunch';

const LANGUAGE_ID = 'openplx';
const TASK_TYPE = 'openplx';
/** Settings whose change needs a new server process. `openplx.trace.server` is applied live by the client. */
const RESTART_SETTINGS = ['openplx.server.path', 'openplx.server.args', 'openplx.interpreter', 'openplx.bundlePath'];

interface OpenPlxTaskDefinition extends vscode.TaskDefinition {
  type: typeof TASK_TYPE;
  file: string;
  simulate?: boolean;
}

let log: vscode.LogOutputChannel;
let status: vscode.LanguageStatusItem;
let client: LanguageClient | undefined;
let invocation: PlxInvocation | undefined;
/** Serialises start/stop so that overlapping restarts cannot start two servers. */
let lifecycle: Promise<void> = Promise.resolve();
let restartTimer: NodeJS.Timeout | undefined;
let pythonListener: vscode.Disposable | undefined;
/** Tells the server about .openplx files changed on disk (one watcher shared by all restarts). */
let fileWatcher: vscode.FileSystemWatcher;
/** Where the extension is installed (its bundled plxtools wheel is in `server/`). */
let extensionPath = '';

function workspaceFolder(resource?: vscode.Uri): string | undefined {
  const folder = resource ? vscode.workspace.getWorkspaceFolder(resource) : undefined;
  return (folder ?? vscode.workspace.workspaceFolders?.[0])?.uri.fsPath;
}

function launchSettings(folder: string | undefined): LaunchSettings {
  const config = vscode.workspace.getConfiguration('openplx');
  return {
    serverArgs: config.get<string[]>('server.args', []),
    bundlePath: config.get<string>('bundlePath', ''),
    env: process.env,
    workspaceFolder: folder,
  };
}

async function discover(resource?: vscode.Uri): Promise<DiscoveryResult> {
  const config = vscode.workspace.getConfiguration('openplx');
  const result = await discoverPlx({
    serverPath: config.get<string>('server.path', ''),
    interpreter: config.get<string>('interpreter', ''),
    pythonExtensionInterpreter: () => activePythonInterpreter(resource),
    env: process.env,
    workspaceFolder: workspaceFolder(resource),
    installRequirement: installRequirementOf(extensionPath),
  });
  for (const attempt of result.attempts) {
    log.info(`discovery [${attempt.source}] ${attempt.candidate}: ${attempt.outcome}`);
  }
  // Registered once the Python extension is active (discovery may just have activated it).
  pythonListener ??= onPythonInterpreterChanged(() => {
    // Only matters when the interpreter setting and server.path are not in charge.
    if (!invocation || invocation.source === 'python-extension' || invocation.source === 'startup-PATH' || invocation.source === 'PATH') {
      log.info('The Python interpreter changed; restarting the server.');
      scheduleRestart();
    }
  });
  return result;
}

function setStatus(text: string, detail: string, severity: vscode.LanguageStatusSeverity): void {
  status.text = text;
  status.detail = detail;
  status.severity = severity;
}

async function startServer(): Promise<void> {
  const result = await discover(vscode.window.activeTextEditor?.document.uri);
  if (!result.found) {
    invocation = undefined;
    log.error(result.message);
    setStatus('plx not found', 'OpenPLX language server', vscode.LanguageStatusSeverity.Error);
    void vscode.window.showErrorMessage(result.message, 'Install plxtools', 'Open Settings', 'Show Log').then((choice) => {
      if (choice === 'Install plxtools') {
        void vscode.commands.executeCommand('openplx.installServer');
      } else if (choice === 'Open Settings') {
        void vscode.commands.executeCommand('workbench.action.openSettings', 'openplx.');
      } else if (choice === 'Show Log') {
        log.show();
      }
    });
    return;
  }
  invocation = result.invocation;
  const folder = workspaceFolder();
  const launch = serverLaunch(result.invocation, launchSettings(folder));
  log.info(`Starting: ${[launch.command, ...launch.args].join(' ')}`);

  const serverOptions: ServerOptions = {
    command: launch.command,
    args: launch.args,
    transport: TransportKind.stdio,
    options: { env: launch.env, cwd: launch.cwd },
  };
  const clientOptions: LanguageClientOptions = {
    documentSelector: [
      { scheme: 'file', language: LANGUAGE_ID },
      { scheme: 'untitled', language: LANGUAGE_ID },
    ],
    synchronize: { fileEvents: fileWatcher },
    initializationOptions: launch.initializationOptions,
    outputChannel: log,
    revealOutputChannelOn: RevealOutputChannelOn.Never,
  };
  // The client id `openplx` makes vscode-languageclient read `openplx.trace.server`.
  const newClient = new LanguageClient(LANGUAGE_ID, 'OpenPLX', serverOptions, clientOptions);
  client = newClient;
  try {
    await newClient.start();
    setStatus('plx', result.invocation.description, vscode.LanguageStatusSeverity.Information);
  } catch (e) {
    log.error(`The server did not start: ${String(e)}`);
    setStatus('plx failed', result.invocation.description, vscode.LanguageStatusSeverity.Error);
    void vscode.window
      .showErrorMessage(
        `The OpenPLX language server (${result.invocation.description}) did not start. ` +
          'Does this plxtools version have `plx lsp`? See the server log.',
        'Show Log',
      )
      .then((choice) => choice && log.show());
  }
}

async function stopServer(): Promise<void> {
  const old = client;
  client = undefined;
  if (old) {
    try {
      await old.dispose(5000); // stops the server if it runs
    } catch (e) {
      log.warn(`Stopping the server: ${String(e)}`);
    }
  }
}

function restart(): Promise<void> {
  lifecycle = lifecycle.then(async () => {
    try {
      await stopServer();
      await startServer();
    } catch (e) {
      // Keep the chain alive: a later restart must still run.
      log.error(`Restarting the server failed: ${String(e)}`);
    }
  });
  return lifecycle;
}

function scheduleRestart(): void {
  if (restartTimer) {
    clearTimeout(restartTimer);
  }
  restartTimer = setTimeout(() => {
    restartTimer = undefined;
    void restart();
  }, 300);
}

/** The .openplx document a command applies to: the explorer selection or the active editor. */
function targetDocumentUri(uri?: vscode.Uri): vscode.Uri | undefined {
  if (uri instanceof vscode.Uri) {
    return uri;
  }
  const doc = vscode.window.activeTextEditor?.document;
  return doc && doc.languageId === LANGUAGE_ID ? doc.uri : undefined;
}

/**
 * A task that runs `plx check [--simulate] FILE` in the terminal. `definition` is kept as given:
 * VS Code requires a resolved tasks.json task to carry its original definition object.
 */
function checkTask(
  definition: OpenPlxTaskDefinition,
  file: string,
  plx: PlxInvocation,
  scope: vscode.WorkspaceFolder | undefined,
): vscode.Task {
  const folder = scope?.uri.fsPath;
  const spec = plxCommand(plx, checkArgs(file, definition.simulate === true), launchSettings(folder));
  const execution = new vscode.ProcessExecution(spec.command, spec.args, {
    env: spec.env,
    cwd: folder ?? path.dirname(file),
  });
  const name = `${definition.simulate ? 'check --simulate' : 'check'} ${path.basename(file)}`;
  const task = new vscode.Task(definition, scope ?? vscode.TaskScope.Workspace, name, 'plx', execution, []);
  task.presentationOptions = {
    reveal: vscode.TaskRevealKind.Always,
    panel: vscode.TaskPanelKind.Shared,
    clear: true,
    showReuseMessage: false,
  };
  return task;
}

/** The plx the running server uses, else a fresh discovery (reported when it fails). */
async function plxForCheck(resource?: vscode.Uri): Promise<PlxInvocation | undefined> {
  if (invocation) {
    return invocation;
  }
  const result = await discover(resource);
  if (result.found) {
    return result.invocation;
  }
  log.error(result.message);
  void vscode.window.showErrorMessage(result.message);
  return undefined;
}

async function runCheck(simulate: boolean, uri?: vscode.Uri): Promise<void> {
  const target = targetDocumentUri(uri);
  if (!target) {
    void vscode.window.showWarningMessage('Open an .openplx file to check it.');
    return;
  }
  if (target.scheme !== 'file') {
    void vscode.window.showWarningMessage('Save the file first: plx check works on files on disk.');
    return;
  }
  const open = vscode.workspace.textDocuments.find((d) => d.uri.toString() === target.toString());
  if (open?.isDirty) {
    await open.save();
  }
  const plx = await plxForCheck(target);
  if (plx) {
    const definition: OpenPlxTaskDefinition = { type: TASK_TYPE, file: target.fsPath, simulate };
    await vscode.tasks.executeTask(checkTask(definition, target.fsPath, plx, vscode.workspace.getWorkspaceFolder(target)));
  }
}

/**
 * "OpenPLX: View scene": `plx view FILE` in its own terminal panel. The window stays open while
 * the user edits: every save reloads the scene in it (plx view watches the files the model read).
 */
async function runView(uri?: vscode.Uri): Promise<void> {
  const target = targetDocumentUri(uri);
  if (!target || target.scheme !== 'file') {
    void vscode.window.showWarningMessage('Open a saved .openplx file to view it.');
    return;
  }
  const open = vscode.workspace.textDocuments.find((d) => d.uri.toString() === target.toString());
  if (open?.isDirty) {
    await open.save();
  }
  const plx = await plxForCheck(target);
  if (!plx) {
    return;
  }
  const scope = vscode.workspace.getWorkspaceFolder(target);
  const folder = scope?.uri.fsPath;
  const spec = plxCommand(plx, viewArgs(target.fsPath), launchSettings(folder));
  const execution = new vscode.ProcessExecution(spec.command, spec.args, {
    env: spec.env,
    cwd: folder ?? path.dirname(target.fsPath),
  });
  const definition: OpenPlxTaskDefinition = { type: TASK_TYPE, file: target.fsPath };
  const task = new vscode.Task(definition, scope ?? vscode.TaskScope.Workspace, `view ${path.basename(target.fsPath)}`,
    'plx', execution, []);
  task.isBackground = true;
  task.presentationOptions = { reveal: vscode.TaskRevealKind.Always, panel: vscode.TaskPanelKind.Dedicated, clear: true };
  await vscode.tasks.executeTask(task);
}

/** Lets users put `{"type": "openplx", "file": "...", "simulate": true}` in tasks.json. */
const taskProvider: vscode.TaskProvider = {
  provideTasks: () => [],
  resolveTask: async (task) => {
    const definition = task.definition as OpenPlxTaskDefinition;
    if (!definition.file) {
      return undefined;
    }
    const scope = typeof task.scope === 'object' ? task.scope : undefined;
    const file = path.isAbsolute(definition.file) || !scope ? definition.file : path.join(scope.uri.fsPath, definition.file);
    const plx = await plxForCheck(vscode.Uri.file(file));
    return plx ? checkTask(definition, file, plx, scope) : undefined;
  },
};

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  extensionPath = context.extensionPath;
  log = vscode.window.createOutputChannel('OpenPLX', { log: true });
  fileWatcher = vscode.workspace.createFileSystemWatcher('**/*.openplx');
  status = vscode.languages.createLanguageStatusItem('openplx.server', { language: LANGUAGE_ID });
  status.name = 'OpenPLX language server';
  status.command = { title: 'Show log', command: 'openplx.showServerLog' };
  setStatus('plx', 'starting', vscode.LanguageStatusSeverity.Information);

  context.subscriptions.push(
    log,
    status,
    fileWatcher,
    vscode.commands.registerCommand('openplx.restartServer', () => restart()),
    vscode.commands.registerCommand('openplx.showServerLog', () => log.show()),
    vscode.commands.registerCommand('openplx.installServer', () =>
      runInstall(extensionPath, workspaceFolder(vscode.window.activeTextEditor?.document.uri), log, () => restart())),
    vscode.commands.registerCommand('openplx.checkScene', (uri?: vscode.Uri) => runCheck(false, uri)),
    vscode.commands.registerCommand('openplx.simulateScene', (uri?: vscode.Uri) => runCheck(true, uri)),
    vscode.commands.registerCommand('openplx.viewScene', (uri?: vscode.Uri) => runView(uri)),
    vscode.commands.registerCommand('openplx.openPreview', (uri?: vscode.Uri) =>
      openPreview({ plx: plxForCheck, settings: launchSettings, log }, uri)),
    { dispose: disposePreview },
    vscode.tasks.registerTaskProvider(TASK_TYPE, taskProvider),
    vscode.workspace.onDidChangeConfiguration((e) => {
      if (RESTART_SETTINGS.some((s) => e.affectsConfiguration(s))) {
        log.info('Settings changed; restarting the server.');
        scheduleRestart();
      }
    }),
    vscode.workspace.onDidGrantWorkspaceTrust(() => scheduleRestart()),
    { dispose: () => pythonListener?.dispose() },
  );
  // Not awaited: activation should not wait for the Python extension or the server's start.
  void restart();
}

export async function deactivate(): Promise<void> {
  if (restartTimer) {
    clearTimeout(restartTimer);
  }
  await lifecycle;
  await stopServer();
}
