"""The plain HTTP and unauthenticated ports stay on loopback unless told otherwise: the
metrics (read-only), and the Foxglove live view (no client authentication)."""

from __future__ import annotations

import pytest

from services.foxglove.__main__ import main as live_view
from services.runtime.process import check_metrics_address
from services.runtime.server import PlaintextRefused


@pytest.mark.parametrize("address", ["0.0.0.0:9100", "10.0.0.2:9100", "[::]:9100"])
def test_metrics_beyond_loopback_are_refused_unless_allowed(address):
    with pytest.raises(PlaintextRefused, match="--allow-metrics-network"):
        check_metrics_address(address, allow_network=False)
    check_metrics_address(address, allow_network=True)  # allowed: a warning, no refusal
    check_metrics_address("127.0.0.1:0", allow_network=False)
    check_metrics_address("off", allow_network=False)


def test_the_live_view_beyond_loopback_is_refused_unless_allowed(capsys, monkeypatch):
    monkeypatch.delenv("TELEROBOT_ALLOW_LIVE_VIEW_NETWORK", raising=False)
    assert live_view(["--address", "0.0.0.0:0"]) == 2
    assert "--allow-network" in capsys.readouterr().err
