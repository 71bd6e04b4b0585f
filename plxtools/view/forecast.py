"""Will the scene leave the opening camera's view as soon as it runs?

The tutorial's step 3 is a chassis with no ground: by the first drawn frame it had fallen out of
view and the window was black (issue 40.6). The AGX viewer waits for E; `plx view` does the same for
a scene that a short look ahead shows leaving the view, and says why.
"""

from __future__ import annotations

from typing import Any

HORIZON_S = 1.5  # simulated seconds looked ahead
MAX_STEPS = 1500  # ... at most (a tiny time step would look ahead less far)
OUT_OF_VIEW = 0.6  # the bodies' centre this many camera distances from where the camera looks:
# past the edge of MuJoCo's 45 degree view (tan 22.5 deg = 0.41), with margin for the bodies' size


def leaves_view(model: Any, data: Any) -> str | None:
    """Why the scene should start paused (None: it stays in view for the look ahead).

    Steps a copy of ``data`` with MuJoCo's plain step (the forecast only decides whether to wait;
    what is shown is the session's own simulation, untouched)."""
    import mujoco
    import numpy as np

    from plxtools.check.mujoco.render import frame_camera

    ids = [b for b in range(1, model.nbody) if model.body_weldid[b] != 0]
    if not ids:
        return None
    cam = frame_camera(model, data)
    look, reach = np.array(cam.lookat), OUT_OF_VIEW * float(cam.distance)
    ahead = mujoco.MjData(model)
    mujoco.mj_copyData(ahead, model, data)
    h = float(model.opt.timestep)
    steps = min(MAX_STEPS, max(1, int(HORIZON_S / h)))
    every = max(1, int(0.05 / h))  # look every 50 ms of simulated time
    for k in range(0, steps, every):
        mujoco.mj_step(model, ahead, nstep=min(every, steps - k))
        if not np.all(np.isfinite(ahead.xpos[ids])):
            return f"the scene becomes unstable within {ahead.time - data.time:.2f} s"
        centre = np.mean(ahead.xpos[ids], axis=0)
        if float(np.linalg.norm(centre - look)) > reach:
            return f"it leaves the view within {ahead.time - data.time:.2f} s"
    return None
