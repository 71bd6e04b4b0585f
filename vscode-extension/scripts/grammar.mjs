// Source of the TextMate grammar. Writes syntaxes/openplx.tmLanguage.json.
//
//   node scripts/grammar.mjs           regenerate the JSON
//   node scripts/grammar.mjs --check   exit 1 when the committed JSON is out of date (used by ci.sh)
//
// The grammar is kept here, not hand-edited as JSON, so that the identifier and qualified-name
// regexes are written once. Constructs follow shared/spec/openplx-language.md sections A and B.
import { readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const OUT = join(dirname(fileURLToPath(import.meta.url)), '..', 'syntaxes', 'openplx.tmLanguage.json');

// Identifiers: plain, or backtick-quoted (may contain dots: `nested.backticks`).
const PLAIN_ID = '[A-Za-z_][A-Za-z0-9_]*';
const ID = `(?:${PLAIN_ID}|\`[^\`\\n]*\`)`;
// A dotted path such as Physics3D.Bodies.RigidBody or kinematics.local_transform.position.z.
const QNAME = `${ID}(?:\\s*\\.\\s*${ID})*`;
// Keywords that start a top-level statement, so they can never be a model name.
const STATEMENT_KEYWORDS = '(?:trait|operator|import|fn|static|const|optional|with|is|becomes|or|reference)';
// Not preceded by an identifier character, a dot or a backtick.
const NOT_AFTER_NAME = '(?<![A-Za-z0-9_.`])';
// Not preceded by an identifier character or a backtick (a dot is fine: Math.PI).
const NOT_AFTER_ID = '(?<![A-Za-z0-9_`])';
const NOT_BEFORE_NAME = '(?![A-Za-z0-9_`])';

/** A capture that gets a scope and marks backticks of a quoted identifier inside it. */
const named = (name) => ({ name, patterns: [{ include: '#backtick' }] });

const grammar = {
  $schema: 'https://raw.githubusercontent.com/martinring/tmlanguage/master/tmlanguage.json',
  name: 'OpenPLX',
  scopeName: 'source.openplx',
  fileTypes: ['openplx'],
  patterns: [
    { include: '#comment' },
    { include: '#strings' },
    { include: '#import' },
    { include: '#operator-declaration' },
    { include: '#method-declaration' },
    { include: '#trait-definition' },
    { include: '#global-attribute' },
    { include: '#model-definition' },
    { include: '#annotation' },
    { include: '#member-declaration' },
    { include: '#assignment' },
    { include: '#type-clause' },
    { include: '#expression' },
  ],
  repository: {
    comment: {
      // `#` to the end of the line; strings are matched first, so a `#` inside a string is text.
      match: '(#).*$',
      name: 'comment.line.number-sign.openplx',
      captures: { 1: { name: 'punctuation.definition.comment.openplx' } },
    },

    strings: {
      patterns: [
        { include: '#string-triple' },
        { include: '#string-path' },
        { include: '#string-interpolated' },
        { include: '#string-double' },
      ],
    },
    'string-triple': {
      // """...""": may span lines, raw (no escapes).
      name: 'string.quoted.triple.openplx',
      begin: '"""',
      beginCaptures: { 0: { name: 'punctuation.definition.string.begin.openplx' } },
      end: '"""',
      endCaptures: { 0: { name: 'punctuation.definition.string.end.openplx' } },
    },
    'string-path': {
      // @"chassis.obj": a path relative to the .openplx file.
      name: 'string.quoted.double.path.openplx',
      begin: '(@)(")',
      beginCaptures: {
        1: { name: 'storage.type.string.path.openplx' },
        2: { name: 'punctuation.definition.string.begin.openplx' },
      },
      end: '(")|$',
      endCaptures: { 1: { name: 'punctuation.definition.string.end.openplx' } },
    },
    'string-interpolated': {
      // $"{AGX_DATA_DIR}/models/x.png": {NAME} parts are substituted.
      name: 'string.interpolated.openplx',
      begin: '(\\$)(")',
      beginCaptures: {
        1: { name: 'storage.type.string.interpolated.openplx' },
        2: { name: 'punctuation.definition.string.begin.openplx' },
      },
      end: '(")|$',
      endCaptures: { 1: { name: 'punctuation.definition.string.end.openplx' } },
      patterns: [
        {
          match: `(\\{)\\s*(${PLAIN_ID})\\s*(\\})`,
          name: 'meta.embedded.line.interpolation.openplx',
          captures: {
            1: { name: 'punctuation.section.embedded.begin.openplx' },
            2: { name: 'variable.other.interpolation.openplx' },
            3: { name: 'punctuation.section.embedded.end.openplx' },
          },
        },
      ],
    },
    'string-double': {
      // "...": one line only, no escapes. An unclosed string stops at the end of the line.
      name: 'string.quoted.double.openplx',
      begin: '"',
      beginCaptures: { 0: { name: 'punctuation.definition.string.begin.openplx' } },
      end: '(")|$',
      endCaptures: { 1: { name: 'punctuation.definition.string.end.openplx' } },
    },

    import: {
      // import @"x.obj" as Mesh / import $"m.urdf" as model.mymodel
      name: 'meta.import.openplx',
      begin: '^\\s*(import)\\b',
      beginCaptures: { 1: { name: 'keyword.control.import.openplx' } },
      end: '$',
      patterns: [
        { include: '#comment' },
        { include: '#strings' },
        {
          match: `\\b(as)\\s+(${QNAME})`,
          captures: {
            1: { name: 'keyword.control.as.openplx' },
            2: { patterns: [{ include: '#type-names' }] },
          },
        },
        { match: '\\bas\\b', name: 'keyword.control.as.openplx' },
      ],
    },

    'operator-declaration': {
      // operator *(lhs: Vec3, rhs: Real) -> Vec3
      name: 'meta.function.operator.openplx',
      begin: '^\\s*(operator)\\s*([-+*/])?',
      beginCaptures: {
        1: { name: 'storage.type.function.operator.openplx' },
        2: { name: 'entity.name.function.operator.openplx' },
      },
      end: '$',
      patterns: [{ include: '#signature' }],
    },
    'method-declaration': {
      // fn length() -> Real / static fn from_xyz(x: Real, y: Real, z: Real) -> Vec3
      name: 'meta.function.openplx',
      begin: `^\\s*(?:(static)\\s+)?(fn)\\b\\s*(${ID})?`,
      beginCaptures: {
        1: { name: 'storage.modifier.static.openplx' },
        2: { name: 'storage.type.function.openplx' },
        3: named('entity.name.function.openplx'),
      },
      end: '$',
      patterns: [{ include: '#signature' }],
    },
    signature: {
      patterns: [
        { include: '#comment' },
        { include: '#parameters' },
        { include: '#arrow' },
        { include: '#type-names' },
        { include: '#punctuation' },
      ],
    },
    parameters: {
      name: 'meta.function.parameters.openplx',
      begin: '\\(',
      beginCaptures: { 0: { name: 'punctuation.section.parameters.begin.openplx' } },
      // Signatures are one line: an unclosed parameter list stops at the end of the line.
      end: '(\\))|$',
      endCaptures: { 1: { name: 'punctuation.section.parameters.end.openplx' } },
      patterns: [
        { include: '#comment' },
        {
          match: `(${ID})\\s*(:)`,
          captures: {
            1: named('variable.parameter.openplx'),
            2: { name: 'punctuation.separator.type.openplx' },
          },
        },
        { include: '#type-names' },
        { include: '#punctuation' },
      ],
    },

    'trait-definition': {
      // trait Name [is Parent][:]
      match: `^(trait)\\s+(${ID})`,
      captures: {
        1: { name: 'storage.type.trait.openplx' },
        2: named('entity.name.type.trait.openplx'),
      },
    },
    'global-attribute': {
      // Top level `NAME is Type: value` (a value on the same line): PI is Real: 3.14
      match: `^(?:(const)\\s+)?(?!${STATEMENT_KEYWORDS}\\b)(${ID})(?=\\s+is\\s+[^:#]*:\\s*[^\\s#])`,
      captures: {
        1: { name: 'storage.modifier.const.openplx' },
        2: named('variable.other.constant.global.openplx'),
      },
    },
    'model-definition': {
      // Top level `[const] Name [is Base][:]`: the model being defined.
      match: `^(?:(const)\\s+)?(?!${STATEMENT_KEYWORDS}\\b)(${ID})(?=\\s*(?:\\bis\\b|:|#|$))`,
      captures: {
        1: { name: 'storage.modifier.const.openplx' },
        2: named('entity.name.type.model.openplx'),
      },
    },
    annotation: {
      // .doc: """...""" / .agx_debug_render_frame: true
      match: `^\\s*(\\.)(${ID})\\s*(:)`,
      name: 'meta.annotation.openplx',
      captures: {
        1: { name: 'punctuation.definition.annotation.openplx' },
        2: named('storage.type.annotation.openplx'),
        3: { name: 'punctuation.separator.key-value.openplx' },
      },
    },
    'member-declaration': {
      // [optional] path is|becomes ...: the attribute names left of is/becomes.
      match: `^\\s*(?:(optional)\\s+)?(${QNAME})(?=\\s+(?:is|becomes)\\b)`,
      captures: {
        1: { name: 'storage.modifier.optional.openplx' },
        2: { patterns: [{ include: '#attribute-path' }] },
      },
    },
    assignment: {
      // path: value / path: (block). The attribute names left of the colon.
      match: `^\\s*(${QNAME})\\s*(:)`,
      captures: {
        1: { patterns: [{ include: '#attribute-path' }] },
        2: { name: 'punctuation.separator.key-value.openplx' },
      },
    },
    'attribute-path': {
      // kinematics.local_transform.position.z: the last name is the attribute, the others lead to it.
      patterns: [
        {
          match: `(${ID})\\s*(\\.)`,
          captures: {
            1: named('variable.other.object.property.openplx'),
            2: { name: 'punctuation.accessor.openplx' },
          },
        },
        { match: ID, captures: { 0: named('variable.other.property.openplx') } },
      ],
    },
    'type-clause': {
      // is|becomes|with followed by a type expression, up to `:`, a comment or the end of the line:
      // Physics3D.Bodies.RigidBody or Physics3D.System, Real[], T with A, B, Connector reference
      begin: '\\b(?:(is)|(becomes)|(with))\\b',
      beginCaptures: {
        1: { name: 'keyword.other.is.openplx' },
        2: { name: 'keyword.other.becomes.openplx' },
        3: { name: 'keyword.other.with.openplx' },
      },
      end: '(?=[:#]|$)',
      patterns: [
        { match: '\\bor\\b', name: 'keyword.operator.union.openplx' },
        { match: '\\bwith\\b', name: 'keyword.other.with.openplx' },
        { match: '\\breference\\b', name: 'storage.modifier.reference.openplx' },
        { include: '#type-names' },
        { include: '#punctuation' },
      ],
    },
    'type-names': {
      // A (qualified) type reference: namespaces, then the type; primitives; the [] suffix.
      patterns: [
        {
          match: `${NOT_AFTER_NAME}(Real|Int|Bool|String)${NOT_BEFORE_NAME}(?!\\s*\\.)`,
          name: 'support.type.primitive.openplx',
        },
        {
          match: `${NOT_AFTER_NAME}(Blob|BundleConfig)${NOT_BEFORE_NAME}(?!\\s*\\.)`,
          name: 'support.type.builtin.openplx',
        },
        {
          match: `(${ID})\\s*(\\.)`,
          captures: {
            1: named('entity.name.namespace.openplx'),
            2: { name: 'punctuation.accessor.openplx' },
          },
        },
        { match: ID, captures: { 0: named('entity.name.type.openplx') } },
        { match: '\\[\\s*\\]', name: 'storage.modifier.array.openplx' },
      ],
    },

    expression: {
      patterns: [
        { include: '#comment' },
        { include: '#strings' },
        { include: '#literals' },
        { include: '#keywords' },
        { include: '#names' },
        { include: '#arrow' },
        { include: '#operators' },
        { include: '#punctuation' },
      ],
    },
    literals: {
      patterns: [
        { match: '\\bthis\\b', name: 'variable.language.this.openplx' },
        { match: '\\btrue\\b', name: 'constant.language.boolean.true.openplx' },
        { match: '\\bfalse\\b', name: 'constant.language.boolean.false.openplx' },
        {
          // 0.5, 9.80665, 5.0e-3, 1e8, 865e-9, 1E-6
          match: `${NOT_AFTER_NAME}(?:\\d+\\.\\d+(?:[eE][-+]?\\d+)?|\\d+[eE][-+]?\\d+)${NOT_BEFORE_NAME}`,
          name: 'constant.numeric.float.openplx',
        },
        { match: `${NOT_AFTER_NAME}\\d+${NOT_BEFORE_NAME}`, name: 'constant.numeric.integer.openplx' },
      ],
    },
    keywords: {
      // Keywords met outside the statement forms above (e.g. while a line is being typed).
      patterns: [
        { match: '\\b(?:is|becomes|with)\\b', name: 'keyword.other.openplx' },
        { match: '\\bor\\b', name: 'keyword.operator.union.openplx' },
        { match: '\\b(?:import|as)\\b', name: 'keyword.control.import.openplx' },
        { match: '\\btrait\\b', name: 'storage.type.trait.openplx' },
        { match: '\\bfn\\b', name: 'storage.type.function.openplx' },
        { match: '\\boperator\\b', name: 'storage.type.function.operator.openplx' },
        { match: '\\b(?:const|static|optional|reference)\\b', name: 'storage.modifier.openplx' },
      ],
    },
    names: {
      // Names inside values. Order matters: calls, CONSTANTS, PascalCase (models, namespaces),
      // members after a dot, then plain variables.
      patterns: [
        { match: `(${ID})(?=\\s*\\()`, captures: { 1: named('entity.name.function.openplx') } },
        { match: `${NOT_AFTER_ID}[A-Z][A-Z0-9_]*[A-Z0-9_]${NOT_BEFORE_NAME}`, name: 'variable.other.constant.openplx' },
        { match: `${NOT_AFTER_ID}[A-Z][A-Za-z0-9_]*[a-z][A-Za-z0-9_]*${NOT_BEFORE_NAME}`, name: 'entity.name.type.openplx' },
        { match: `(?<=\\.)\\s*(${ID})`, captures: { 1: named('variable.other.property.openplx') } },
        { match: `(${ID})(?=\\s*\\.)`, captures: { 1: named('variable.other.object.openplx') } },
        { match: ID, captures: { 0: named('variable.other.readwrite.openplx') } },
      ],
    },
    arrow: { match: '->', name: 'keyword.operator.arrow.openplx' },
    operators: { match: '[-+*/]', name: 'keyword.operator.arithmetic.openplx' },
    punctuation: {
      patterns: [
        { match: ':', name: 'punctuation.separator.key-value.openplx' },
        { match: ',', name: 'punctuation.separator.comma.openplx' },
        { match: '\\.', name: 'punctuation.accessor.openplx' },
        { match: '\\(', name: 'punctuation.section.parens.begin.openplx' },
        { match: '\\)', name: 'punctuation.section.parens.end.openplx' },
        { match: '\\[', name: 'punctuation.section.brackets.begin.openplx' },
        { match: '\\]', name: 'punctuation.section.brackets.end.openplx' },
        { match: '\\{', name: 'punctuation.section.braces.begin.openplx' },
        { match: '\\}', name: 'punctuation.section.braces.end.openplx' },
      ],
    },
    backtick: { match: '`', name: 'punctuation.definition.identifier.backtick.openplx' },
  },
};

const json = JSON.stringify(grammar, null, 2) + '\n';
if (process.argv.includes('--check')) {
  let current = '';
  try {
    current = readFileSync(OUT, 'utf8');
  } catch {
    // missing counts as out of date
  }
  if (current !== json) {
    console.error('syntaxes/openplx.tmLanguage.json is out of date: run `node scripts/grammar.mjs`.');
    process.exit(1);
  }
  console.log('grammar: syntaxes/openplx.tmLanguage.json is up to date');
} else {
  writeFileSync(OUT, json);
  console.log(`grammar: wrote ${OUT}`);
}
