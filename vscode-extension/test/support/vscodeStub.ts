/**
 * A small stand-in for the `vscode` module, enough to activate the shipped bundle
 * (dist/extension.js) under plain Node and watch what it does: registered commands, messages,
 * executed tasks. Anything not modelled here is a generic no-op (so that vscode-languageclient can
 * be loaded), which means this is a smoke test of the glue, not of VS Code behaviour.
 */
import Module = require('node:module');

export interface Recorder {
  commands: Map<string, (...args: unknown[]) => unknown>;
  errors: string[];
  warnings: string[];
  tasks: Array<{ definition: Record<string, unknown>; name: string; execution: { process: string; args: string[]; options?: { env?: Record<string, string>; cwd?: string } } }>;
  logs: string[];
  settings: Record<string, unknown>;
  activeDocument?: { uri: StubUri; languageId: string; isDirty: boolean; save(): Promise<boolean> };
}

export class StubUri {
  constructor(
    public readonly scheme: string,
    public readonly fsPath: string,
  ) {}
  static file(p: string): StubUri {
    return new StubUri('file', p);
  }
  toString(): string {
    return `${this.scheme}://${this.fsPath}`;
  }
}

class Disposable {
  constructor(private readonly fn: () => void = () => undefined) {}
  dispose(): void {
    this.fn();
  }
  static from(...items: Array<{ dispose(): unknown }>): Disposable {
    return new Disposable(() => items.forEach((i) => i.dispose()));
  }
}

class EventEmitter<T> {
  private listeners: Array<(e: T) => void> = [];
  event = (listener: (e: T) => void): Disposable => {
    this.listeners.push(listener);
    return new Disposable();
  };
  fire(e: T): void {
    this.listeners.forEach((l) => l(e));
  }
  dispose(): void {
    this.listeners = [];
  }
}

/** A class or function that accepts anything: for APIs the extension does not use in these tests. */
function anything(): unknown {
  const target = function () {
    return undefined;
  };
  return new Proxy(target, {
    get: (_t, prop) => (prop === Symbol.toPrimitive ? () => '' : prop === 'then' ? undefined : anything()),
    construct: () => ({}),
    apply: () => undefined,
  });
}

export function createVscodeStub(rec: Recorder): unknown {
  const noEvent = () => new Disposable();
  const logChannel = new Proxy(
    { show: () => undefined, dispose: () => undefined },
    {
      get: (t, prop: string) =>
        prop in t
          ? (t as Record<string, unknown>)[prop]
          : (...args: unknown[]) => {
              rec.logs.push(`${prop}: ${args.map(String).join(' ')}`);
            },
    },
  );
  const api: Record<string, unknown> = {
    Uri: StubUri,
    Disposable,
    EventEmitter,
    LanguageStatusSeverity: { Information: 0, Warning: 1, Error: 2 },
    TaskRevealKind: { Always: 1, Silent: 2, Never: 3 },
    TaskPanelKind: { Shared: 1, Dedicated: 2, New: 3 },
    TaskScope: { Global: 1, Workspace: 2 },
    ProcessExecution: class {
      constructor(
        public process: string,
        public args: string[],
        public options?: unknown,
      ) {}
    },
    Task: class {
      presentationOptions: unknown;
      constructor(
        public definition: unknown,
        public scope: unknown,
        public name: string,
        public source: string,
        public execution: unknown,
      ) {}
    },
    window: {
      createOutputChannel: () => logChannel,
      showErrorMessage: async (msg: string) => {
        rec.errors.push(msg);
        return undefined;
      },
      showWarningMessage: async (msg: string) => {
        rec.warnings.push(msg);
        return undefined;
      },
      get activeTextEditor() {
        return rec.activeDocument ? { document: rec.activeDocument } : undefined;
      },
    },
    languages: {
      createLanguageStatusItem: () => ({ dispose: () => undefined }),
    },
    commands: {
      registerCommand: (id: string, fn: (...args: unknown[]) => unknown) => {
        rec.commands.set(id, fn);
        return new Disposable();
      },
      executeCommand: async () => undefined,
    },
    workspace: {
      workspaceFolders: undefined,
      get textDocuments() {
        return rec.activeDocument ? [rec.activeDocument] : [];
      },
      getWorkspaceFolder: () => undefined,
      getConfiguration: (section: string) => ({
        get: (key: string, fallback: unknown) => rec.settings[`${section}.${key}`] ?? fallback,
      }),
      createFileSystemWatcher: () => ({ dispose: () => undefined, onDidCreate: noEvent, onDidChange: noEvent, onDidDelete: noEvent }),
      onDidChangeConfiguration: noEvent,
      onDidGrantWorkspaceTrust: noEvent,
    },
    tasks: {
      registerTaskProvider: () => new Disposable(),
      executeTask: async (task: Recorder['tasks'][number]) => {
        rec.tasks.push(task);
        return {};
      },
    },
    extensions: {
      getExtension: () => undefined,
    },
  };
  return new Proxy(api, { get: (t, prop: string) => (prop in t ? t[prop] : anything()) });
}

/** Makes `require('vscode')` return `stub` until the returned function is called. */
export function installVscodeStub(stub: unknown): () => void {
  const mod = Module as unknown as { _load: (request: string, ...rest: unknown[]) => unknown };
  const original = mod._load;
  mod._load = function (request: string, ...rest: unknown[]) {
    return request === 'vscode' ? stub : original.call(this, request, ...rest);
  };
  return () => {
    mod._load = original;
  };
}
