/**
 * End-to-end: start the real `plx lsp` through the extension's own discovery and launch code
 * (src/serverDiscovery.ts + src/serverLaunch.ts, the same functions the extension calls), talk LSP
 * over the child's stdio, open a broken model and wait for its diagnostics.
 *
 * Which plx: PLX_SERVER_PATH (given to discovery as the `openplx.server.path` setting), else
 * discovery's normal lookup (plx on PATH). When no plx is found the test FAILS: CI must run it.
 */
import * as assert from 'node:assert/strict';
import type { ChildProcessWithoutNullStreams } from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { pathToFileURL } from 'node:url';
import {
  ConfigurationRequest,
  createProtocolConnection,
  type Diagnostic,
  DidChangeTextDocumentNotification,
  DidOpenTextDocumentNotification,
  DiagnosticSeverity,
  ExitNotification,
  InitializedNotification,
  InitializeRequest,
  type InitializeResult,
  type ProtocolConnection,
  type PublishDiagnosticsParams,
  PublishDiagnosticsNotification,
  RegistrationRequest,
  ShowMessageRequest,
  ShutdownRequest,
  StreamMessageReader,
  StreamMessageWriter,
  UnregistrationRequest,
  WorkDoneProgressCreateRequest,
} from 'vscode-languageserver-protocol/node';
import { discoverPlx } from '../../src/serverDiscovery';
import { type ServerLaunch, serverLaunch, spawnProcess } from '../../src/serverLaunch';

const DIAGNOSTICS_TIMEOUT_MS = 20000;

// Line 3 (0-based) has a syntax error: `is` with no type.
const BROKEN = ['# broken on purpose: the last line has no type after `is`', 'Cart:', '    mass is Real: 10', '    wheels is : 3', ''].join('\n');
const BROKEN_LINE = 3;
const FIXED = ['# fixed', 'Cart:', '    mass is Real: 10', '    wheels is Int: 3', ''].join('\n');
// Line 2 (0-based) misspells an inherited attribute: `mas` is not an attribute of Inertia.
const TYPO = ['Scene is Physics3D.System:', '    chassis is Physics3D.Bodies.RigidBody:', '        inertia.mas: 10', ''].join('\n');
const TYPO_LINE = 2;

/** A diagnostic's message as text (LSP 3.18 also allows markup). */
function messageText(d: Diagnostic): string {
  return typeof d.message === 'string' ? d.message : d.message.value;
}

/** `promise`, or a rejection after `ms`; the timer never outlives the race (so mocha can exit). */
function withTimeout<T>(promise: Promise<T>, ms: number, onTimeout: () => Error): Promise<T> {
  let timer: NodeJS.Timeout | undefined;
  const timeout = new Promise<never>((_, reject) => {
    timer = setTimeout(() => reject(onTimeout()), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

describe('plx lsp, started through the extension launch code', function () {
  this.timeout(90000);

  let workspace: string;
  let launch: ServerLaunch;
  let child: ChildProcessWithoutNullStreams;
  let connection: ProtocolConnection;
  let stderr = '';
  let exited: Promise<number | null>;
  let initializeResult: InitializeResult;
  const published: PublishDiagnosticsParams[] = [];
  const waiters: Array<() => void> = [];

  function serverOutput(): string {
    const tail = stderr.length > 4000 ? `...${stderr.slice(-4000)}` : stderr;
    return `\n--- server command: ${[launch.command, ...launch.args].join(' ')}\n--- server stderr:\n${tail || '(empty)'}`;
  }

  /** Resolves with the first publishDiagnostics for `uri` that satisfies `accept`. */
  function waitForDiagnostics(uri: string, accept: (p: PublishDiagnosticsParams) => boolean, what: string): Promise<PublishDiagnosticsParams> {
    return new Promise((resolve, reject) => {
      const check = (): boolean => {
        const hit = published.find((p) => p.uri === uri && accept(p));
        if (hit) {
          resolve(hit);
        }
        return hit !== undefined;
      };
      if (check()) {
        return;
      }
      const timer = setTimeout(() => {
        const seen = published.filter((p) => p.uri === uri).map((p) => JSON.stringify(p.diagnostics));
        reject(
          new Error(
            `no textDocument/publishDiagnostics with ${what} for ${uri} within ${DIAGNOSTICS_TIMEOUT_MS / 1000} s. ` +
              `Seen for this file: ${seen.length ? seen.join(' | ') : 'none'}${serverOutput()}`,
          ),
        );
      }, DIAGNOSTICS_TIMEOUT_MS);
      waiters.push(() => {
        if (check()) {
          clearTimeout(timer);
        }
      });
      void exited.then((code) => {
        clearTimeout(timer);
        reject(new Error(`the server exited (code ${code}) before publishing ${what}${serverOutput()}`));
      });
    });
  }

  before(async () => {
    const serverPath = process.env.PLX_SERVER_PATH;
    const discovery = await discoverPlx({ serverPath, env: process.env });
    if (!discovery.found) {
      assert.fail(
        `Cannot run the language server test: ${discovery.message}\n` +
          'Set PLX_SERVER_PATH=/path/to/venv/bin/plx (or put plx on PATH). ' +
          'For local runs without a server only: PLX_SKIP_LSP_TEST=1 bash scripts/ci.sh',
      );
    }
    workspace = fs.mkdtempSync(path.join(os.tmpdir(), 'plx-lsp-'));
    launch = serverLaunch(discovery.invocation, { env: process.env, workspaceFolder: workspace });
    child = spawnProcess(launch);
    child.stderr.setEncoding('utf8');
    child.stderr.on('data', (chunk: string) => {
      stderr += chunk;
    });
    exited = new Promise((resolve) => {
      child.on('exit', (code) => resolve(code));
      child.on('error', (err) => {
        stderr += `\nspawn error: ${String(err)}`;
        resolve(null);
      });
    });

    connection = createProtocolConnection(new StreamMessageReader(child.stdout), new StreamMessageWriter(child.stdin));
    connection.onNotification(PublishDiagnosticsNotification.type, (params) => {
      published.push(params);
      waiters.forEach((w) => w());
    });
    // Answer server-to-client requests the way a minimal editor would.
    connection.onRequest(ConfigurationRequest.type, (params) => params.items.map(() => null));
    connection.onRequest(RegistrationRequest.type, () => undefined);
    connection.onRequest(UnregistrationRequest.type, () => undefined);
    connection.onRequest(WorkDoneProgressCreateRequest.type, () => undefined);
    connection.onRequest(ShowMessageRequest.type, () => null);
    connection.onError(([err]) => {
      stderr += `\nconnection error: ${String(err)}`;
    });
    connection.listen();

    const rootUri = pathToFileURL(workspace).href;
    const initialize = connection.sendRequest(InitializeRequest.type, {
      processId: process.pid,
      clientInfo: { name: 'openplx-vscode integration test' },
      rootUri,
      workspaceFolders: [{ uri: rootUri, name: 'test' }],
      initializationOptions: launch.initializationOptions,
      capabilities: {
        general: { positionEncodings: ['utf-16'] },
        workspace: { configuration: true, workspaceFolders: true },
        textDocument: {
          synchronization: { dynamicRegistration: false, didSave: true },
          publishDiagnostics: { relatedInformation: true, versionSupport: true, codeDescriptionSupport: true, dataSupport: true },
          hover: { contentFormat: ['markdown', 'plaintext'] },
          completion: { completionItem: { snippetSupport: false } },
        },
      },
    });
    const died = exited.then((code) => {
      throw new Error(`the server exited (code ${code}) during initialize${serverOutput()}`);
    });
    initializeResult = await withTimeout(
      Promise.race([initialize, died]),
      30000,
      () => new Error(`initialize got no answer within 30 s${serverOutput()}`),
    );
    await connection.sendNotification(InitializedNotification.type, {});
  });

  after(async () => {
    if (!child) {
      return;
    }
    try {
      await withTimeout(connection.sendRequest(ShutdownRequest.type), 5000, () => new Error('shutdown timed out'));
      await connection.sendNotification(ExitNotification.type);
      await withTimeout(exited, 5000, () => new Error('the server did not exit'));
    } catch {
      child.kill();
    }
    connection.dispose();
    fs.rmSync(workspace, { recursive: true, force: true });
  });

  it('answers initialize with text document sync', () => {
    assert.ok(initializeResult.capabilities.textDocumentSync !== undefined, 'the server announces no textDocumentSync');
  });

  it('publishes a diagnostic on the broken line of an opened model, and clears it after the fix', async () => {
    const file = path.join(workspace, 'broken.openplx');
    fs.writeFileSync(file, BROKEN);
    const uri = pathToFileURL(file).href;
    const withError = waitForDiagnostics(uri, (p) => p.diagnostics.length > 0, 'at least one diagnostic');
    await connection.sendNotification(DidOpenTextDocumentNotification.type, {
      textDocument: { uri, languageId: 'openplx', version: 1, text: BROKEN },
    });
    const params = await withError;
    const lines = params.diagnostics.map((d) => d.range.start.line);
    assert.ok(
      lines.includes(BROKEN_LINE),
      `expected a diagnostic on line ${BROKEN_LINE} (0-based), got ${JSON.stringify(params.diagnostics)}`,
    );
    const onLine = params.diagnostics.filter((d) => d.range.start.line === BROKEN_LINE);
    assert.ok(onLine.every((d) => messageText(d).length > 0), 'empty diagnostic message');

    // Replace the whole text (valid for both full and incremental sync) and expect the error to go.
    published.length = 0;
    fs.writeFileSync(file, FIXED);
    const cleared = waitForDiagnostics(
      uri,
      (p) => !p.diagnostics.some((d) => d.severity === DiagnosticSeverity.Error || d.severity === undefined),
      'no errors after the fix',
    );
    await connection.sendNotification(DidChangeTextDocumentNotification.type, {
      textDocument: { uri, version: 2 },
      contentChanges: [{ text: FIXED }],
    });
    await cleared;
  });

  it('publishes a diagnostic for a misspelled attribute (needs the bundles)', async () => {
    const file = path.join(workspace, 'typo.openplx');
    fs.writeFileSync(file, TYPO);
    const uri = pathToFileURL(file).href;
    const onTypoLine = waitForDiagnostics(
      uri,
      (p) => p.diagnostics.some((d) => d.range.start.line === TYPO_LINE),
      `a diagnostic on line ${TYPO_LINE} (0-based)`,
    );
    await connection.sendNotification(DidOpenTextDocumentNotification.type, {
      textDocument: { uri, languageId: 'openplx', version: 1, text: TYPO },
    });
    const params = await onTypoLine;
    const hit = params.diagnostics.find((d) => d.range.start.line === TYPO_LINE)!;
    assert.ok(messageText(hit).includes('mas'), `the message should name the attribute: ${messageText(hit)}`);
  });
});
