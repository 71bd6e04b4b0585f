/**
 * "OpenPLX: Install plxtools": installs the language server into the workspace's virtual
 * environment (made when there is none) in a terminal task, then restarts the server. What is
 * installed is the wheel bundled in the extension, until plxtools is published (serverDiscovery.ts).
 */
import * as vscode from 'vscode';
import { activePythonInterpreter } from './python';
import { findBundledWheel, installRequirement, planInstall } from './serverDiscovery';

export function installRequirementOf(extensionPath: string): string | undefined {
  return installRequirement(extensionPath ? findBundledWheel(extensionPath) : undefined);
}

export async function runInstall(
  extensionPath: string,
  folder: string | undefined,
  log: vscode.LogOutputChannel,
  restart: () => Promise<void>,
): Promise<void> {
  const requirement = installRequirementOf(extensionPath);
  if (!requirement) {
    void vscode.window.showErrorMessage('This build of the OpenPLX extension carries no plxtools wheel, and plxtools is ' +
      'not on PyPI yet: install it from a checkout (`pip install ".[sim]"`) and set `openplx.server.path`.');
    return;
  }
  let extPython: string | undefined;
  try {
    extPython = await activePythonInterpreter();
  } catch {
    extPython = undefined;
  }
  const plan = planInstall({ requirement, workspaceFolder: folder, pythonExtensionInterpreter: extPython });
  if (!plan) {
    void vscode.window.showErrorMessage('Open a folder first: plxtools is installed into its .venv.');
    return;
  }
  const steps: string[][] = [];
  if (plan.createVenv) {
    steps.push([plan.createVenv.base, '-m', 'venv', plan.createVenv.folder]);
  }
  steps.push([plan.python, '-m', 'pip', 'install', plan.requirement]);
  for (const step of steps) {
    log.info(`Install: ${step.join(' ')}`);
    const task = new vscode.Task({ type: 'openplx-install' }, vscode.TaskScope.Workspace, 'install plxtools', 'plx',
      new vscode.ProcessExecution(step[0], step.slice(1), { cwd: folder }));
    const code = await runTask(task);
    if (code !== 0) {
      void vscode.window.showErrorMessage(`Installing plxtools failed (exit ${code ?? '?'}): see the terminal.`);
      return;
    }
  }
  void vscode.window.showInformationMessage(`plxtools is installed in ${plan.python}; restarting the server.`);
  await restart();
}

function runTask(task: vscode.Task): Promise<number | undefined> {
  return new Promise((resolve) => {
    const listener = vscode.tasks.onDidEndTaskProcess((e) => {
      if (e.execution.task === task || e.execution.task.name === task.name) {
        listener.dispose();
        resolve(e.exitCode);
      }
    });
    void vscode.tasks.executeTask(task).then(undefined, () => {
      listener.dispose();
      resolve(undefined);
    });
  });
}
