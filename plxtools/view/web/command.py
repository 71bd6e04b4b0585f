"""`plx view --web`: the preview served on 127.0.0.1, for a browser or an editor's web view."""

from __future__ import annotations

import signal
import sys
import threading
import webbrowser


def run_web(args) -> int:
    from plxtools.view.session import ViewSession
    from plxtools.view.web.live import LivePreview
    from plxtools.view.web.server import PreviewServer

    def say(line: str) -> None:
        print(f"plx view: {line}", file=sys.stderr, flush=True)

    session = ViewSession(args.path, args.model, bundle_path=args.bundle_path,
                          openplx_version=getattr(args, "openplx_version", None), controller=args.controller,
                          keymap=args.keys, paused=args.paused, say=say)
    live = LivePreview(session, editor_command=getattr(args, "editor_command", None), say=say)
    try:
        server = PreviewServer(live, port=args.port or 0)
    except OSError as exc:
        print(f"plx view: cannot serve on 127.0.0.1:{args.port}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    # the URL first, so that a caller (the VS Code extension, a test) can connect while the model loads
    print(f"plx view: preview of {args.path} at {server.url}", flush=True)
    server.serve_in_thread()
    live.start()
    if not args.no_open:
        threading.Thread(target=webbrowser.open, args=(server.url,), daemon=True).start()
    stop = threading.Event()
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, lambda *_: stop.set())
    try:
        while not stop.wait(0.5):
            pass
    except KeyboardInterrupt:
        pass
    finally:
        live.stop()
        server.shutdown()
        server.server_close()
    return 0
