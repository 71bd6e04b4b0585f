/**
 * Tokenizes OpenPLX text with the extension's TextMate grammar, the way VS Code does
 * (vscode-textmate + the oniguruma WASM build). Used by the grammar corpus test and by
 * `node out/test/support/tokenize.js FILE` to print the scopes of a file while editing the grammar.
 */
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as oniguruma from 'vscode-oniguruma';
import * as vsctm from 'vscode-textmate';

const ROOT = path.resolve(__dirname, '..', '..', '..');
export const GRAMMAR_PATH = path.join(ROOT, 'syntaxes', 'openplx.tmLanguage.json');

export interface Token {
  line: number;
  text: string;
  scopes: string[];
}

export interface Tokenized {
  tokens: Token[];
  /** Scopes still open at the end of the file (a runaway string or block), if any. */
  openScopes: string[];
}

let grammarPromise: Promise<vsctm.IGrammar> | undefined;

export function loadGrammar(): Promise<vsctm.IGrammar> {
  grammarPromise ??= (async () => {
    const wasm = fs.readFileSync(require.resolve('vscode-oniguruma/release/onig.wasm'));
    await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
    const registry = new vsctm.Registry({
      onigLib: Promise.resolve({
        createOnigScanner: (sources: string[]) => new oniguruma.OnigScanner(sources),
        createOnigString: (s: string) => new oniguruma.OnigString(s),
      }),
      loadGrammar: async (scopeName: string) => {
        if (scopeName !== 'source.openplx') {
          return null;
        }
        return vsctm.parseRawGrammar(fs.readFileSync(GRAMMAR_PATH, 'utf8'), GRAMMAR_PATH);
      },
    });
    const grammar = await registry.loadGrammar('source.openplx');
    if (!grammar) {
      throw new Error(`could not load ${GRAMMAR_PATH}`);
    }
    return grammar;
  })();
  return grammarPromise;
}

export async function tokenize(text: string): Promise<Tokenized> {
  const grammar = await loadGrammar();
  const tokens: Token[] = [];
  let stack: vsctm.StackElement = vsctm.INITIAL;
  const lines = text.split(/\r?\n/);
  lines.forEach((line, i) => {
    const result = grammar.tokenizeLine(line, stack);
    for (const t of result.tokens) {
      tokens.push({ line: i, text: line.slice(t.startIndex, t.endIndex), scopes: t.scopes });
    }
    stack = result.ruleStack;
  });
  // Scopes open at the end: tokenize an empty line and look at what it inherits.
  const probe = grammar.tokenizeLine('', stack);
  const openScopes = probe.tokens.length ? probe.tokens[0].scopes.slice(1) : [];
  return { tokens, openScopes };
}

if (require.main === module) {
  const file = process.argv[2];
  if (!file) {
    console.error('usage: node out/test/support/tokenize.js FILE.openplx');
    process.exit(2);
  }
  void tokenize(fs.readFileSync(file, 'utf8')).then(({ tokens, openScopes }) => {
    for (const t of tokens) {
      if (t.text.trim()) {
        console.log(`${t.line + 1}\t${JSON.stringify(t.text)}\t${t.scopes.slice(1).join(' ')}`);
      }
    }
    if (openScopes.length) {
      console.log(`open at end of file: ${openScopes.join(' ')}`);
    }
  });
}
