/**
 * "OpenPLX: Open 3D Preview": the page of `plx view --web` in a webview beside the editor.
 *
 * The extension starts `plx view --web FILE --no-open` with the plx the language server uses,
 * shows the printed URL in an iframe (through `asExternalUri`, so code-server's port forwarding
 * works), and links the two: the active `.openplx` editor is previewed (`api/open`), its text is
 * sent as it is typed (`api/text`) and its cursor as it moves (`api/cursor`); a click in the page
 * (the server's `reveal` event) opens that line in the editor.
 */
import * as path from 'node:path';
import type { ChildProcessWithoutNullStreams } from 'node:child_process';
import * as vscode from 'vscode';
import type { PlxInvocation } from './serverDiscovery';
import { type LaunchSettings, plxCommand, spawnProcess } from './serverLaunch';
import { PreviewClient, pageHtml, previewArgs, previewUrl } from './previewClient';

export interface PreviewDeps {
  plx: (resource: vscode.Uri) => Promise<PlxInvocation | undefined>;
  settings: (folder: string | undefined) => LaunchSettings;
  log: vscode.LogOutputChannel;
}

const TEXT_DELAY_MS = 120;
const CURSOR_DELAY_MS = 80;
const START_TIMEOUT_MS = 60000;

let current: Preview | undefined;

export async function openPreview(deps: PreviewDeps, uri?: vscode.Uri): Promise<void> {
  const doc = uri
    ? await vscode.workspace.openTextDocument(uri)
    : vscode.window.activeTextEditor?.document;
  if (!doc || doc.languageId !== 'openplx' || doc.uri.scheme !== 'file') {
    void vscode.window.showWarningMessage('Open an .openplx file on disk to preview it.');
    return;
  }
  if (current) {
    current.panel.reveal(vscode.ViewColumn.Beside, true);
    await current.follow(doc);
    return;
  }
  const plx = await deps.plx(doc.uri);
  if (!plx) return;
  try {
    current = await Preview.start(deps, plx, doc);
  } catch (e) {
    deps.log.error(`3D preview: ${String(e)}`);
    void vscode.window.showErrorMessage(`The 3D preview did not start: ${String(e)}`);
  }
}

export function disposePreview(): void {
  current?.panel.dispose();
}

class Preview {
  private readonly disposables: vscode.Disposable[] = [];
  private stream: { close(): void } | undefined;
  private file: string;
  private textTimer: NodeJS.Timeout | undefined;
  private cursorTimer: NodeJS.Timeout | undefined;
  private editorColumn: vscode.ViewColumn = vscode.ViewColumn.One;

  private constructor(
    readonly panel: vscode.WebviewPanel,
    private readonly proc: ChildProcessWithoutNullStreams,
    private readonly client: PreviewClient,
    doc: vscode.TextDocument,
    private readonly log: vscode.LogOutputChannel,
  ) {
    this.file = doc.uri.fsPath;
    this.editorColumn = vscode.window.activeTextEditor?.viewColumn ?? vscode.ViewColumn.One;
  }

  static async start(deps: PreviewDeps, plx: PlxInvocation, doc: vscode.TextDocument): Promise<Preview> {
    const folder = vscode.workspace.getWorkspaceFolder(doc.uri)?.uri.fsPath;
    const spec = plxCommand(plx, previewArgs(doc.uri.fsPath), deps.settings(folder));
    deps.log.info(`3D preview: ${[spec.command, ...spec.args].join(' ')}`);
    const proc = spawnProcess({ ...spec, cwd: folder ?? path.dirname(doc.uri.fsPath) });
    proc.stderr.setEncoding('utf8');
    proc.stderr.on('data', (chunk: string) => chunk.split('\n').filter((l) => l).forEach((l) => deps.log.info(l)));
    const url = await new Promise<string>((resolve, reject) => {
      let out = '';
      const timer = setTimeout(() => reject(new Error('plx view --web printed no URL within 60 s')), START_TIMEOUT_MS);
      proc.stdout.setEncoding('utf8');
      proc.stdout.on('data', (chunk: string) => {
        out += chunk;
        const found = previewUrl(out);
        if (found) {
          clearTimeout(timer);
          resolve(found);
        }
      });
      proc.on('exit', (code) => {
        clearTimeout(timer);
        reject(new Error(`plx view --web exited (${code}); see the OpenPLX output`));
      });
      proc.on('error', (e) => {
        clearTimeout(timer);
        reject(e);
      });
    });
    // the token is added after asExternalUri: a port forwarder (code-server's /proxy/PORT/) may drop the query
    const client = new PreviewClient(url);
    const external = await vscode.env.asExternalUri(vscode.Uri.parse(`${client.base}/`));
    const pageUrl = `${external.toString(true).replace(/\?.*$/, '')}?t=${encodeURIComponent(client.token)}`;
    deps.log.info(`3D preview: the page is ${pageUrl.replace(/t=.*/, 't=...')}`);
    const panel = vscode.window.createWebviewPanel(
      'openplx.preview',
      `Preview ${path.basename(doc.uri.fsPath)}`,
      { viewColumn: vscode.ViewColumn.Beside, preserveFocus: true },
      { enableScripts: true, retainContextWhenHidden: true },
    );
    panel.webview.html = pageHtml(pageUrl);
    const preview = new Preview(panel, proc, client, doc, deps.log);
    preview.listen();
    if (doc.isDirty) preview.sendText(doc);
    return preview;
  }

  private listen(): void {
    this.stream = this.client.events((e) => {
      if (e.event === 'reveal') void this.reveal(e.data as { file: string; line: number; column: number });
    });
    this.disposables.push(
      vscode.workspace.onDidChangeTextDocument((e) => {
        if (e.document.uri.fsPath !== this.file) return;
        if (this.textTimer) clearTimeout(this.textTimer);
        this.textTimer = setTimeout(() => this.sendText(e.document), TEXT_DELAY_MS);
      }),
      vscode.workspace.onDidSaveTextDocument((d) => {
        if (d.uri.fsPath === this.file) this.post('api/text', { file: this.file, text: null });
      }),
      vscode.workspace.onDidCloseTextDocument((d) => {
        if (d.uri.fsPath === this.file) this.post('api/text', { file: this.file, text: null });
      }),
      vscode.window.onDidChangeActiveTextEditor((ed) => {
        if (ed && ed.document.languageId === 'openplx' && ed.document.uri.scheme === 'file') {
          this.editorColumn = ed.viewColumn ?? this.editorColumn;
          void this.follow(ed.document);
        }
      }),
      vscode.window.onDidChangeTextEditorSelection((e) => {
        if (e.textEditor.document.uri.fsPath !== this.file) return;
        if (this.cursorTimer) clearTimeout(this.cursorTimer);
        const line = e.selections[0].active.line + 1;
        this.cursorTimer = setTimeout(() => this.post('api/cursor', { file: this.file, line }), CURSOR_DELAY_MS);
      }),
    );
    this.panel.onDidDispose(() => this.dispose(), undefined, this.disposables);
  }

  /** Preview another .openplx document (the active editor changed). */
  async follow(doc: vscode.TextDocument): Promise<void> {
    if (doc.uri.fsPath === this.file) return;
    this.file = doc.uri.fsPath;
    this.panel.title = `Preview ${path.basename(this.file)}`;
    await this.client.post('api/open', { file: this.file }).catch((e) => this.log.warn(`3D preview: ${String(e)}`));
    if (doc.isDirty) this.sendText(doc);
  }

  sendText(doc: vscode.TextDocument): void {
    this.post('api/text', { file: doc.uri.fsPath, text: doc.getText() });
  }

  private post(name: string, body: unknown): void {
    this.client.post(name, body).catch((e) => this.log.warn(`3D preview ${name}: ${String(e)}`));
  }

  private async reveal(at: { file: string; line: number; column: number }): Promise<void> {
    if (!at.file || !at.line) return;
    const pos = new vscode.Position(Math.max(0, at.line - 1), Math.max(0, (at.column || 1) - 1));
    await vscode.window.showTextDocument(vscode.Uri.file(at.file), {
      viewColumn: this.editorColumn,
      selection: new vscode.Range(pos, pos),
      preserveFocus: false,
    });
  }

  private dispose(): void {
    if (current === this) current = undefined;
    this.stream?.close();
    if (this.textTimer) clearTimeout(this.textTimer);
    if (this.cursorTimer) clearTimeout(this.cursorTimer);
    this.disposables.forEach((d) => d.dispose());
    this.proc.kill();
  }
}
