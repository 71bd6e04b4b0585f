"""A bundle depends on a bundle that is not loaded, or two bundles share a name.

## Why it matters

Names from a missing dependency cannot resolve. Add its folder with `--bundle-path` or the
`bundle-path` config key.
"""

from __future__ import annotations

from plxtools.model import facts as found

FACTS = (found.UnknownDependency,)


def check(facts, report) -> None:
    for f in facts.of(*FACTS):
        if f.loaded_from is not None:
            report(f"a bundle named '{f.name}' is already loaded from {f.loaded_from}", f.span)
        else:
            report(f"unknown dependency '{f.name}': no bundle with that name is loaded", f.span,
                   help="add its folder with --bundle-path or bundle-path in the config")
