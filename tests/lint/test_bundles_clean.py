"""`plx lint` reports no error and no warning on the official bundles; a false positive is a bug."""

from plxtools.lint.runner import lint_file


def test_official_bundles_have_no_errors_or_warnings(bundles, workspace):
    bad = {}
    for path in bundles:
        for d in lint_file(path, workspace=workspace).diagnostics:
            if d.severity.value in ("error", "warning"):
                bad.setdefault(str(path), []).append(f"{d.code} {d.message}")
    assert bad == {}
