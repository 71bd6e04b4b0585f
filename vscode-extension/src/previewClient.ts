/**
 * The Node side of "OpenPLX: Open 3D Preview": the `plx view --web` command line, the URL it
 * prints, and a client of its HTTP interface (POST actions, the Server-Sent Events stream).
 *
 * Pure Node (no `vscode` import), so the unit tests run it against a real `plx view --web`.
 */
import * as http from 'node:http';

/** What `plx view --web` prints on its standard output: `... at http://127.0.0.1:PORT/?t=TOKEN`. */
export const PREVIEW_URL = /(http:\/\/127\.0\.0\.1:\d+\/\?t=[A-Za-z0-9_-]+)/;

/** Arguments of the preview server for one file (no browser: the webview shows the page). */
export function previewArgs(file: string): string[] {
  return ['view', '--web', file, '--no-open'];
}

/** The preview URL in a line of output, or undefined. */
export function previewUrl(line: string): string | undefined {
  return PREVIEW_URL.exec(line)?.[1];
}

export interface SseEvent {
  event: string;
  data: unknown;
}

/** Splits a Server-Sent Events buffer into whole events and the unfinished rest. */
export function parseSse(buffer: string): { events: SseEvent[]; rest: string } {
  const events: SseEvent[] = [];
  const blocks = buffer.split('\n\n');
  const rest = blocks.pop() ?? '';
  for (const block of blocks) {
    let event = 'message';
    const data: string[] = [];
    for (const line of block.split('\n')) {
      if (line.startsWith('event: ')) event = line.slice(7);
      else if (line.startsWith('data: ')) data.push(line.slice(6));
    }
    if (data.length) {
      try {
        events.push({ event, data: JSON.parse(data.join('\n')) });
      } catch {
        // not JSON: not one of plx's events
      }
    }
  }
  return { events, rest };
}

export class PreviewClient {
  readonly base: string;
  readonly token: string;

  constructor(readonly url: string) {
    const u = new URL(url);
    this.token = u.searchParams.get('t') ?? '';
    this.base = `${u.protocol}//${u.host}`;
  }

  /** POST a JSON body to `name` (api/text, api/cursor, api/open...); resolves to the JSON answer. */
  post(name: string, body: unknown): Promise<unknown> {
    const payload = Buffer.from(JSON.stringify(body));
    return new Promise((resolve, reject) => {
      const req = http.request(`${this.base}/${name}`, {
        method: 'POST',
        headers: { 'Content-Type': 'application/json', 'Content-Length': payload.length, 'X-Plx-Token': this.token },
      }, (res) => {
        const chunks: Buffer[] = [];
        res.on('data', (c: Buffer) => chunks.push(c));
        res.on('end', () => {
          try {
            resolve(JSON.parse(Buffer.concat(chunks).toString('utf8')));
          } catch (e) {
            reject(e);
          }
        });
      });
      req.on('error', reject);
      req.end(payload);
    });
  }

  /** Follows the event stream; reconnects after half a second while not closed. */
  events(onEvent: (e: SseEvent) => void): { close(): void } {
    let closed = false;
    let req: http.ClientRequest | undefined;
    const connect = (): void => {
      if (closed) return;
      let buffer = '';
      req = http.get(`${this.base}/events`, { headers: { 'X-Plx-Token': this.token } }, (res) => {
        res.setEncoding('utf8');
        res.on('data', (chunk: string) => {
          const parsed = parseSse(buffer + chunk);
          buffer = parsed.rest;
          parsed.events.forEach(onEvent);
        });
        res.on('end', () => setTimeout(connect, 500));
      });
      req.on('error', () => setTimeout(connect, 500));
    };
    connect();
    return {
      close(): void {
        closed = true;
        req?.destroy();
      },
    };
  }
}

/** The webview's page: the preview served by plx (at its external URL), in a frame that fills it. */
export function pageHtml(url: string): string {
  const origin = new URL(url).origin;
  const esc = (s: string): string => s.replace(/&/g, '&amp;').replace(/"/g, '&quot;').replace(/</g, '&lt;');
  return `<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; frame-src ${esc(origin)}; style-src 'unsafe-inline';">
<style>html,body,iframe{margin:0;padding:0;border:0;width:100%;height:100%;overflow:hidden;display:block}</style>
</head><body><iframe src="${esc(url)}" title="OpenPLX 3D preview"></iframe></body></html>`;
}
