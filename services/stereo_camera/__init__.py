"""StereoCamera: synchronized stereo pairs from the sim, a test pattern, cameras or recordings.

Offscreen MuJoCo rendering needs its GL backend chosen before mujoco is first imported; this
package picks EGL unless MUJOCO_GL already says otherwise.
"""

import os

os.environ.setdefault("MUJOCO_GL", "egl")
