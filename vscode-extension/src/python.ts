/**
 * Optional use of the Python extension (ms-python.python): its active interpreter is step 3 of
 * server discovery. The extension is not a hard dependency; when it is missing, nothing happens.
 * Only the small part of its public API used here is typed.
 */
import * as vscode from 'vscode';

const PYTHON_EXTENSION_ID = 'ms-python.python';

interface EnvironmentPath {
  id: string;
  path: string;
}

interface PythonExtensionApi {
  environments?: {
    getActiveEnvironmentPath(resource?: vscode.Uri): EnvironmentPath;
    resolveEnvironment(
      env: EnvironmentPath | string,
    ): Promise<{ executable?: { uri?: vscode.Uri } } | undefined>;
    onDidChangeActiveEnvironmentPath: vscode.Event<unknown>;
  };
  /** Older API, still present. */
  settings?: {
    getExecutionDetails(resource?: vscode.Uri): { execCommand: string[] | undefined };
    onDidChangeExecutionDetails?: vscode.Event<unknown>;
  };
}

async function pythonApi(): Promise<PythonExtensionApi | undefined> {
  const ext = vscode.extensions.getExtension<PythonExtensionApi>(PYTHON_EXTENSION_ID);
  if (!ext) {
    return undefined;
  }
  return ext.isActive ? ext.exports : await ext.activate();
}

/** The Python extension's active interpreter for `resource`, or undefined. */
export async function activePythonInterpreter(resource?: vscode.Uri): Promise<string | undefined> {
  const api = await pythonApi();
  if (!api) {
    return undefined;
  }
  if (api.environments) {
    const envPath = api.environments.getActiveEnvironmentPath(resource);
    const resolved = await api.environments.resolveEnvironment(envPath);
    const executable = resolved?.executable?.uri?.fsPath;
    if (executable) {
      return executable;
    }
  }
  const execCommand = api.settings?.getExecutionDetails(resource).execCommand;
  // A multi-word command (e.g. `conda run ...`) is not an interpreter path.
  return execCommand && execCommand.length === 1 ? execCommand[0] : undefined;
}

/**
 * Calls `listener` when the Python extension's active interpreter changes. Returns undefined (and
 * does not activate the Python extension) when it is not installed or not active yet.
 */
export function onPythonInterpreterChanged(listener: () => void): vscode.Disposable | undefined {
  const ext = vscode.extensions.getExtension<PythonExtensionApi>(PYTHON_EXTENSION_ID);
  if (!ext?.isActive) {
    return undefined;
  }
  const api = ext.exports;
  const event = api.environments?.onDidChangeActiveEnvironmentPath ?? api.settings?.onDidChangeExecutionDetails;
  return event?.(() => listener());
}
