"""Every official bundle file parses with no diagnostic at all."""

from plxtools.syntax import parse_file


def test_all_bundle_files_parse_clean(bundles):
    failures = {}
    statements = 0
    for path in bundles:
        tree = parse_file(path)
        if tree.diagnostics:
            failures[str(path)] = [d.message for d in tree.diagnostics]
        statements += len(tree.statements)
    assert failures == {}
    assert statements > 465
