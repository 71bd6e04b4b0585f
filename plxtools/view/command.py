"""The `plx view` command body: arguments -> a ViewSession -> the window."""

from __future__ import annotations

import os
import sys


def run_view(args) -> int:
    from plxtools.view.session import ViewSession

    for what, path in (("FILE", args.path), ("--controller", args.controller), ("--keys", args.keys)):
        if path is not None and not os.path.isfile(path):
            print(f"plx view: {what} {path}: no such file", file=sys.stderr)
            return 2
    if getattr(args, "web", False):
        from plxtools.view.web.command import run_web

        return run_web(args)
    for flag in ("no_open", "editor_command"):
        if getattr(args, flag, None):
            print(f"plx view: --{flag.replace('_', '-')} needs --web", file=sys.stderr)
            return 2
    if getattr(args, "port", 0):
        print("plx view: --port needs --web", file=sys.stderr)
        return 2
    if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY") and sys.platform.startswith("linux"):
        print("plx view: no display (DISPLAY is not set); for a headless machine use "
              "'plx check --simulate --video FILE.gif' or run under xvfb-run", file=sys.stderr)
        return 2
    session = ViewSession(args.path, args.model, bundle_path=args.bundle_path,
                          openplx_version=getattr(args, "openplx_version", None), controller=args.controller,
                          keymap=args.keys, paused=args.paused,
                          say=lambda line: print(f"plx view: {line}", file=sys.stderr, flush=True))
    try:
        from plxtools.view.window import run
    except ImportError as exc:  # mujoco.viewer needs glfw
        print(f"plx view: MuJoCo's viewer cannot start: {exc}", file=sys.stderr)
        return 2
    return run(session)
