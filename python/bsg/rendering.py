"""Rendering of bsg environments, headless (OpenGL through EGL, no display).

``bsg.make(id, render_mode="rgb_array", width=480, height=360, camera="default")``
then ``env.render()`` returns the frame as an ``[height, width, 3]`` uint8
array; ``render_mode="depth_array"`` returns ``[height, width]`` float32
distances along the view axis in metres. Cameras: ``"default"`` (the task's
own, as the original suite sets it), ``"arena"`` (the whole arena, so the agent
is always in view; ``bsg eval --video``'s default), ``"track"`` (follows the
agent) and ``"top"`` (the arena from above). The graphics context is created at the first
``render()``: an environment that never renders creates none.
"""

from . import _core

RENDER_MODES = ["rgb_array", "depth_array"]
# One frame per environment step plays in real time: every id steps 1/60
# simulated second (4 engine steps of 1/240 s in Circle, Run and Gather, one of
# 1/60 s in Reach).
RENDER_FPS = round(1.0 / _core.env_step_seconds)
METADATA = {"render_modes": RENDER_MODES, "render_fps": RENDER_FPS}
CAMERAS = list(_core.camera_names)


def make_renderer(render_mode, width, height, camera):
    """The renderer for ``render_mode`` (None for None); ValueError for bad arguments."""
    if render_mode is None:
        return None
    if render_mode not in RENDER_MODES:
        raise ValueError(f"render_mode must be one of {RENDER_MODES} or None, got {render_mode!r}")
    for name, value in (("width", width), ("height", height)):
        if isinstance(value, bool) or not isinstance(value, int):
            raise ValueError(f"{name} must be an int, got {value!r}")
    if not isinstance(camera, str):
        raise ValueError(f"camera must be one of {CAMERAS}, got {camera!r}")
    return _core.Renderer(width, height, camera, render_mode == "depth_array")


def render(env, renderer, vector=False):
    """``env``'s frame(s) with ``renderer``; RuntimeError without a render mode."""
    if renderer is None:
        raise RuntimeError(f"{env.spec.id}: render() needs a render_mode at construction "
                           f"(one of {RENDER_MODES})")
    return renderer.render_vector(env) if vector else renderer.render(env)
