"""The gRPC metadata keys of the contracts, and the lane names a client may ask for."""

from __future__ import annotations

# Which lane (priority) a call should run on: one of LANES, at most the lane its RPC declares
# (a client may lower a call, never raise it) and the server's --client-lane-limit; without it
# a call runs on the lane its RPC declares.
LANE_METADATA_KEY = "telerobot-lane"
# The lease id from DecisionServer.AcquireControl, which commanding calls on the
# DecisionServer's port need.
LEASE_METADATA_KEY = "telerobot-lease-id"
# Lane names, most urgent first (the services' runtime.lanes.Lane, lower-cased).
LANES = ("emergency", "high", "medium", "low")
