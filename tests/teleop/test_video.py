"""The operator station's video pauses while the camera is away and resumes when it is back."""

from __future__ import annotations

import threading

from clients.teleop.video import StereoView
from tests.conftest import wait_for
from wire.errors import UnavailableError


class _CameraThatRestarts:
    """A camera whose first stream fails (its process died), and whose next one is up."""

    def __init__(self):
        self.streams = 0
        self.resumed = threading.Event()

    def stream_pairs(self, *_encoding, **_options):
        self.streams += 1
        if self.streams == 1:
            raise UnavailableError("Connection refused")
        self.resumed.set()
        return iter(())  # up again; the test stops the view before any frame


class _ArmAtRest:
    """An arm whose state stream ends at once (nothing moves while the camera is away)."""

    class _Ended(list):
        def cancel(self) -> None:
            pass

    def stream_state(self, _period_s):
        return self._Ended()


def test_the_video_pauses_and_resumes_when_the_camera_restarts(tmp_path):
    camera = _CameraThatRestarts()
    view = StereoView(camera, _ArmAtRest(), model=None, out=tmp_path,
                      calibration_path=tmp_path / "c.json")
    view.start()
    wait_for(camera.resumed.is_set, what="a second stream, after the pause")
    view.stop()
    assert view.pauses == 1 and view.error is None
