/**
 * "OpenPLX: Open 3D Preview" without VS Code: the command line the extension starts (discovered as
 * for the language server), the URL it prints, and what the extension sends and listens to: the
 * editor's unsaved text gives a new scene, a selection in the page comes back as a `reveal` event,
 * another file is previewed on `api/open`.
 */
import * as assert from 'node:assert/strict';
import type { ChildProcessWithoutNullStreams } from 'node:child_process';
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import { PreviewClient, type SseEvent, pageHtml, previewArgs, previewUrl } from '../../src/previewClient';
import { discoverPlx } from '../../src/serverDiscovery';
import { plxCommand, spawnProcess } from '../../src/serverLaunch';

const MODEL = `Box is Physics3D.Bodies.RigidBody:
    inertia.mass: 1
    geometry is Physics3D.Geometries.Box:
        size: {0.5, 0.5, 0.5}

Scene is Physics3D.System:
    box is Box:
        kinematics.local_transform.position.z: 1
`;

describe('3D preview (plx view --web, as the extension drives it)', function () {
  this.timeout(90000);
  let tmp: string;
  let child: ChildProcessWithoutNullStreams;
  let client: PreviewClient;
  let stream: { close(): void };
  const events: SseEvent[] = [];

  async function next(kind: string, where: (d: any) => boolean, ms = 20000): Promise<any> {
    const end = Date.now() + ms;
    while (Date.now() < end) {
      const i = events.findIndex((e) => e.event === kind && where(e.data));
      if (i >= 0) return events.splice(0, i + 1)[i].data;
      await new Promise((r) => setTimeout(r, 20));
    }
    throw new Error(`no ${kind} event within ${ms} ms`);
  }

  before(async () => {
    const discovery = await discoverPlx({ serverPath: process.env.PLX_SERVER_PATH, env: process.env });
    assert.ok(discovery.found, discovery.found ? '' : discovery.message);
    tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'plx-preview-'));
    fs.writeFileSync(path.join(tmp, 'box.openplx'), MODEL);
    fs.writeFileSync(path.join(tmp, 'other.openplx'), MODEL.replace('{0.5, 0.5, 0.5}', '{2, 0.5, 0.5}'));
    child = spawnProcess(plxCommand(discovery.invocation, previewArgs(path.join(tmp, 'box.openplx')),
      { env: process.env, workspaceFolder: tmp }));
    const url = await new Promise<string>((resolve, reject) => {
      let out = '';
      child.stdout.setEncoding('utf8');
      child.stdout.on('data', (c: string) => {
        out += c;
        const u = previewUrl(out);
        if (u) resolve(u);
      });
      child.on('exit', (code) => reject(new Error(`plx view --web exited (${code})`)));
    });
    client = new PreviewClient(url);
    stream = client.events((e) => events.push(e));
  });

  after(() => {
    stream?.close();
    child?.kill();
    if (tmp) fs.rmSync(tmp, { recursive: true, force: true });
  });

  it('shows the file, then the editor text as typed', async () => {
    const file = path.join(tmp, 'box.openplx');
    const scene = await next('scene', () => true);
    assert.equal(scene.file, file);
    const box = (s: any): number[] => s.geoms.find((g: any) => g.path === 'box.geometry').size;
    assert.deepEqual(box(scene), [0.25, 0.25, 0.25]);
    await client.post('api/text', { file, text: MODEL.replace('{0.5, 0.5, 0.5}', '{1, 0.5, 0.5}') });
    const edited = await next('scene', (s) => box(s)[0] === 0.5);
    assert.ok(edited.generation > scene.generation);
  });

  it('relays a selection in the page as a reveal event', async () => {
    const file = path.join(tmp, 'box.openplx');
    await client.post('api/select', { path: 'box', file, line: 7, column: 5 });
    const at = await next('reveal', () => true);
    assert.deepEqual(at, { file, line: 7, column: 5, path: 'box' });
  });

  it('follows the active file', async () => {
    const other = path.join(tmp, 'other.openplx');
    await client.post('api/open', { file: other });
    const scene = await next('scene', (s) => s.file === other);
    assert.equal(scene.geoms.find((g: any) => g.path === 'box.geometry').size[0], 1);
  });

  it('frames the page for the webview', () => {
    const html = pageHtml('https://example.test/proxy/8765/?t=abc');
    assert.match(html, /frame-src https:\/\/example\.test;/);
    assert.match(html, /<iframe src="https:\/\/example\.test\/proxy\/8765\/\?t=abc"/);
    assert.equal(previewUrl('plx view: preview of a.openplx at http://127.0.0.1:4242/?t=x-Y_1\n'), 'http://127.0.0.1:4242/?t=x-Y_1');
  });
});
