"""Drive examples/viewer/truck.openplx with the arrow keys:

    plx view examples/viewer/truck.openplx --controller examples/viewer/truck_controller.py

Written the way an AGX runtime controller is (an input queue, RealInputSignal, KeyboardCallback
callbacks that look at ``key.down``); only the imports and buildScene()'s loading are plx's.
"""

import os

from plxtools.check.api import RealInputSignal
from plxtools.view import KeyboardCallback, agxSDK, application, openplx, root


class ArrowKeyDriver:
    """Up drives forward, Down backward, at ``speed`` rad/s on both front motors while held."""

    def __init__(self, queue, left: openplx.Physics.Signals.Input, right: openplx.Physics.Signals.Input):
        self.queue = queue
        self.left = left
        self.right = right
        self.speed = 3.0

    def drive(self, wheel_speed):
        # the right hub's axis is mirrored, so it turns the other way for the same direction
        self.queue.send(RealInputSignal.create(wheel_speed, self.left))
        self.queue.send(RealInputSignal.create(-wheel_speed, self.right))

    def on_up(self, key):
        self.drive(self.speed if key.down else 0.0)

    def on_down(self, key):
        self.drive(-self.speed if key.down else 0.0)

    def listen(self):
        KeyboardCallback.bind(name="forward", key=agxSDK.GuiEventListener.KEY_Up, callback=self.on_up)
        KeyboardCallback.bind(name="backward", key=agxSDK.GuiEventListener.KEY_Down, callback=self.on_down)


def buildScene():  # noqa: N802 - the runtime's name; plx view calls it after every (re)load
    here = os.path.dirname(os.path.abspath(__file__))
    result = application().loadOpenPlxFile(os.path.join(here, "truck.openplx"), root())
    scene = result.scene()
    left = scene.getObject("box_truck.front_left_drive_motor.target_angular_velocity_input")
    right = scene.getObject("box_truck.front_right_drive_motor.target_angular_velocity_input")
    ArrowKeyDriver(result.getInputSignalQueue(), left, right).listen()
