"""Step 11 headless: the tutorial's arrow-key controller, pressed by a timeline instead of a person.

The controller keeps one target speed and sends it to the left front motor and its negative to
the right one (the hubs are mirrored). Run from anywhere:

    python examples/tutorial/step11-controls/drive.py

It prints where the truck is after each key and exits non-zero when the truck did not go forward
and come back, so CI can run it as a test.
"""

from __future__ import annotations

import sys
from pathlib import Path

from plxtools.check.api import RealInputSignal, load

HERE = Path(__file__).resolve().parent
SPEED = 3.0  # rad/s, the tutorial's amplitude


class ArrowKeys:
    """What the up and down arrows do in the tutorial's controller."""

    def __init__(self, sim, left_path: str, right_path: str):
        scene = sim.scene()
        self.queue = sim.getInputSignalQueue()
        self.left = scene.getObject(left_path)
        self.right = scene.getObject(right_path)

    def send(self, speed: float) -> None:
        self.queue.send(RealInputSignal.create(speed, self.left))
        self.queue.send(RealInputSignal.create(-speed, self.right))

    def press_up(self) -> None:
        self.send(SPEED)

    def press_down(self) -> None:
        self.send(-SPEED)

    def release(self) -> None:
        self.send(0.0)


def main() -> int:
    sim = load(HERE / "boxtruck.openplx")
    keys = ArrowKeys(sim, "boxTruck.front_left_drive_motor.target_angular_velocity_input",
                     "boxTruck.front_right_drive_motor.target_angular_velocity_input")
    start_x = sim.body("boxTruck.chassis").position[0]
    timeline = [("up", keys.press_up, 2.0), ("down", keys.press_down, 2.0), ("release", keys.release, 0.5)]
    positions = {}
    for name, action, seconds in timeline:
        action()
        sim.step(seconds)
        x, y, _z = sim.body("boxTruck.chassis").position
        positions[name] = (x, y)
        print(f"after {name:<7} t = {sim.time:4.2f} s: chassis at x = {x:+.2f} m, y = {y:+.3f} m")
    went = abs(positions["up"][0] - start_x)
    back = abs(positions["release"][0] - start_x)
    if went < 1.0 or back > 0.3 or abs(positions["release"][1]) > 0.05:
        print(f"the truck did not drive and come back: {went:.2f} m out, {back:.2f} m from the start",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
