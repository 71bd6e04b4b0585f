"""The MuJoCo side of `plx check --simulate`: compiling a checked scene into an MjSpec (`compile`,
`geoms`, `controllers`, `drivetrain`, `restitution`, `integrator`), stepping it and watching the run
(`simulate` and its monitors), and what is made from a run (`render`, `video`, `kinematic`).

Everything here imports mujoco; `plx check` without `--simulate` never loads this package.
"""
