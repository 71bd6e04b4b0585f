/**
 * Checks of the declarative parts (grammar, language configuration, manifest) that the scope
 * assertions in test/grammar/*.openplx do not cover: nothing stays open at the end of a file,
 * no text is left without a scope, and the manifest points at the right files.
 */
import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { tokenize } from '../support/tokenize';

const ROOT = path.resolve(__dirname, '..', '..', '..');

function openplxFiles(dir: string): string[] {
  return fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
    const p = path.join(dir, e.name);
    if (e.isDirectory()) {
      return openplxFiles(p);
    }
    return e.name.endsWith('.openplx') ? [p] : [];
  });
}

async function checkFile(file: string): Promise<string[]> {
  const problems: string[] = [];
  const { tokens, openScopes } = await tokenize(fs.readFileSync(file, 'utf8'));
  if (openScopes.length) {
    problems.push(`${file}: still open at the end: ${openScopes.join(' ')}`);
  }
  for (const t of tokens) {
    if (t.text.trim() && t.scopes.length === 1) {
      problems.push(`${file}:${t.line + 1}: no scope for ${JSON.stringify(t.text)}`);
    }
    if (t.scopes.some((s) => s.startsWith('invalid'))) {
      problems.push(`${file}:${t.line + 1}: invalid scope on ${JSON.stringify(t.text)}`);
    }
  }
  return problems;
}

describe('TextMate grammar', () => {
  it('leaves nothing open and nothing unscoped in the test fixtures', async () => {
    const files = openplxFiles(path.join(ROOT, 'test', 'grammar'));
    assert.ok(files.length >= 8, `expected the grammar fixtures, found ${files.length}`);
    const problems = (await Promise.all(files.map(checkFile))).flat();
    assert.deepEqual(problems, []);
  });

  it('handles every official bundle file (OPENPLX_BUNDLES_DIR)', async function () {
    const dir = process.env.OPENPLX_BUNDLES_DIR;
    if (!dir) {
      console.log('      (skipped: set OPENPLX_BUNDLES_DIR to the openplxbundles folder to run it)');
      this.skip();
    }
    this.timeout(60000);
    const files = openplxFiles(dir);
    assert.ok(files.length > 0, `no .openplx files under ${dir}`);
    const problems: string[] = [];
    for (const file of files) {
      problems.push(...(await checkFile(file)));
    }
    assert.deepEqual(problems.slice(0, 20), [], `${problems.length} problems in ${files.length} files`);
    console.log(`      (${files.length} bundle files tokenized)`);
  });

  it('marks a `#` inside a string as string text, not as a comment', async () => {
    const { tokens } = await tokenize('    .doc: """see https://x.org/a#b"""\n    url: "a#b" # real');
    const hash = tokens.filter((t) => t.text.includes('#'));
    assert.equal(hash.length, 3);
    assert.ok(hash[0].scopes.includes('string.quoted.triple.openplx'));
    assert.ok(hash[1].scopes.includes('string.quoted.double.openplx'));
    assert.ok(hash[2].scopes.includes('comment.line.number-sign.openplx'));
    assert.ok(!hash[0].scopes.some((s) => s.startsWith('comment')));
  });
});

describe('manifest and language configuration', () => {
  const pkg = JSON.parse(fs.readFileSync(path.join(ROOT, 'package.json'), 'utf8'));

  it('contributes the openplx language, grammar and commands', () => {
    const lang = pkg.contributes.languages[0];
    assert.equal(lang.id, 'openplx');
    assert.deepEqual(lang.extensions, ['.openplx']);
    assert.ok(fs.existsSync(path.join(ROOT, lang.configuration)));
    const grammar = pkg.contributes.grammars[0];
    assert.equal(grammar.scopeName, 'source.openplx');
    const json = JSON.parse(fs.readFileSync(path.join(ROOT, grammar.path), 'utf8'));
    assert.equal(json.scopeName, 'source.openplx');
    const commands = pkg.contributes.commands.map((c: { command: string; category: string; title: string }) => `${c.category}: ${c.title}`);
    assert.deepEqual(commands, [
      'OpenPLX: Restart server',
      'OpenPLX: Show server log',
      'OpenPLX: Install plxtools (the language server)',
      'OpenPLX: Check this scene',
      'OpenPLX: Check and simulate this scene',
      'OpenPLX: View scene',
      'OpenPLX: Open 3D Preview',
    ]);
    assert.deepEqual(Object.keys(pkg.contributes.configuration.properties).sort(), [
      'openplx.bundlePath',
      'openplx.interpreter',
      'openplx.server.args',
      'openplx.server.path',
      'openplx.trace.server',
    ]);
    assert.ok(fs.existsSync(path.join(ROOT, pkg.icon)));
  });

  it('activation events are implied by the contributions; main points at the bundle', () => {
    assert.equal(pkg.main, './dist/extension.js');
    assert.equal(pkg.engines.vscode, '^1.91.0');
  });

  const config = JSON.parse(fs.readFileSync(path.join(ROOT, 'language-configuration.json'), 'utf8'));

  it('folds by indentation and uses # comments', () => {
    assert.equal(config.folding.offSide, true);
    assert.equal(config.comments.lineComment, '#');
  });

  it('indents after a line ending in `:` (a comment may follow), not after comments or values', () => {
    const increase = new RegExp(config.indentationRules.increaseIndentPattern);
    const onEnter = new RegExp(config.onEnterRules[0].beforeText);
    const opens = ['Rover is Physics3D.System:', '    size:', '    main_axis is Math.Vec3: # Defaults to z', '    "a#b" x:  '];
    const plain = ['    x: 3', '# note:', '    # comment:', '    url: "http://a#b:"', '    y: 1 # see:', '    fn f(a: Real) -> Real'];
    for (const line of opens) {
      assert.ok(increase.test(line) && onEnter.test(line), `should indent after ${JSON.stringify(line)}`);
    }
    for (const line of plain) {
      assert.ok(!increase.test(line) && !onEnter.test(line), `should not indent after ${JSON.stringify(line)}`);
    }
  });

  it('auto-closes quotes outside strings and comments only', () => {
    const quote = config.autoClosingPairs.find((p: { open: string }) => p.open === '"');
    assert.deepEqual(quote.notIn, ['string', 'comment']);
  });
});
