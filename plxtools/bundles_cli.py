"""`plx bundles`: install and list official openplx-bundles versions; `plx lint --show-settings` output.

Exit codes: 0 done, 2 when a version cannot be fetched or unpacked (the message says why).
"""

from __future__ import annotations

import sys


def add_parser(sub) -> None:
    p = sub.add_parser("bundles", help="install or list official openplx-bundles versions in plx's cache",
                       description="Manage the official OpenPLX bundle versions plx can lint against. "
                       "Versions are fetched with pip (the wheel only, no dependencies) and unpacked into "
                       "plx's cache; 'openplx-version' in the config or --openplx-version selects one.")
    bsub = p.add_subparsers(dest="bundles_command", metavar="ACTION")
    i = bsub.add_parser("install", help="fetch versions into the cache",
                        description="Fetch openplx-bundles VERSION... into plx's cache (a no-op when cached).")
    i.add_argument("versions", nargs="+", metavar="VERSION", help="for example 0.17.26")
    i.add_argument("--force", action="store_true", help="download and unpack again even when cached")
    ls = bsub.add_parser("list", help="list the installed and cached versions",
                         description="List the installed openplx-bundles package and the versions in plx's cache.")
    ls.add_argument("--all", action="store_true", help="also list every release known to this plx")
    p.set_defaults(func=run_bundles, _parser=p)


def run_bundles(args) -> int:
    from plxtools.model.versions import (KNOWN_VERSIONS, BundleSetError, cache_dir, cached_root, cached_versions,
                                         install, installed)

    if args.bundles_command == "install":
        status = 0
        for v in args.versions:
            try:
                root = install(v, force=args.force)
            except BundleSetError as exc:
                print(f"plx bundles: {exc}", file=sys.stderr)
                status = 2
                continue
            print(f"openplx-bundles {v}: {root}")
        return status
    if args.bundles_command == "list":
        inst = installed()
        cached = cached_versions()
        if inst is not None:
            print(f"{inst[1] or '?':10} installed  {inst[0]}")
        for v in cached:
            print(f"{v:10} cached     {cached_root(v)}")
        if not cached:
            print(f"(no version in the cache {cache_dir() / 'bundles'}; 'plx bundles install VERSION' adds one)")
        if args.all:
            have = set(cached) | ({inst[1]} if inst else set())
            print("releases: " + ", ".join(v + ("*" if v in have else "") for v in KNOWN_VERSIONS))
        return 0
    args._parser.print_help()
    return 2


def print_settings(ws) -> int:
    """`plx lint --show-settings`: the bundle set, one bundle per line, and where the choice came from."""
    from plxtools.model.workspace import describe_bundle_set

    print_set(ws.bundle_set)
    rows = describe_bundle_set(ws)
    w = max((len(r["name"]) for r in rows), default=4)
    print(f"{'bundle':{w}}  {'version':9}  folder  (why)")
    for r in rows:
        print(f"{r['name']:{w}}  {r['version'] or '-':9}  {r['folder']}  ({r['why'] or 'user bundle'})")
    return 0


def print_set(bs, indent: str = "") -> None:
    """A bundle set's choice: the official bundles (OpenPLX version, folder, why), the AGX
    installation found (in use or not), the bundle folders and the notes."""
    print(f"{indent}official bundles: {bs.official_version or '?'} from {bs.official_root} ({bs.official_why})")
    agx = getattr(bs, "agx", None)
    if agx is not None:
        print(f"{indent}AGX: {agx.describe()}"
              f"{' (in use: its bundles are the official bundles)' if bs.agx_used else ' (found, not used: see the note below)'}")
    else:
        from plxtools.model.agx import ENV_VARS

        print(f"{indent}AGX: none found ({', '.join(ENV_VARS)}, the agx Python package, the usual install folders)")
    for s in bs.sources:
        print(f"{indent}bundle folder: {s.path} ({s.why})")
    for n in bs.notes:
        print(f"{indent}note: {n}")


def show_settings(command: str, args) -> int:
    """`plx check --show-settings`: the bundle set `plx check` would use for these paths, by the
    same rule as `plx lint` (exit 2 with a message when the setup cannot be used)."""
    from plxtools.config import ConfigError
    from plxtools.discovery import UsageError, discover
    from plxtools.model.workspace import workspace_for_cli

    try:
        files = discover(args.paths)
        ws = workspace_for_cli(args.bundle_path, files, openplx_version=getattr(args, "openplx_version", None))
    except (UsageError, ConfigError, ValueError) as exc:
        print(f"plx {command}: {exc}", file=sys.stderr)
        return 2
    return print_settings(ws)
