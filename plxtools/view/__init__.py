"""`plx view`: the compiled scene in MuJoCo's interactive viewer, live-reloaded and driven by keys.

A controller script written for the AGX runtime runs after changing its imports::

    from plxtools.check.api import RealInputSignal
    from plxtools.view import KeyboardCallback, application, root
    from plxtools.view import agxSDK, openplx   # agxSDK.GuiEventListener.KEY_Up, openplx.Physics.Signals.Input
    from plxtools.view import agx, agxOSG       # camera and light set-up: accepted and ignored

Layering: view sits above check (it loads through ``plxtools.check.api``) and below lsp/cli.
"""

from __future__ import annotations

from types import SimpleNamespace

from plxtools.view.controller import application, init_app, root
from plxtools.view.display_stubs import agx, agxOSG
from plxtools.view.keys import GuiEventListener, KeyboardCallback, KeyEvent

from plxtools.check.api import Input, Output, RealInputSignal  # noqa: E402 - after the view's own names

agxSDK = SimpleNamespace(GuiEventListener=GuiEventListener)  # noqa: N816 - the runtime's module name
# ``openplx.Physics.Signals.Input`` in a controller's annotations: the API's classes under the runtime's path
openplx = SimpleNamespace(Physics=SimpleNamespace(Signals=SimpleNamespace(
    Input=Input, Output=Output, RealInputSignal=RealInputSignal)))

__all__ = ["GuiEventListener", "KeyEvent", "KeyboardCallback", "agx", "agxOSG", "agxSDK", "application", "init_app", "openplx",
           "root"]
