"""Probes: `python -m bench.probes.<name>`, each a small experiment that prints figures and
judges nothing. They measure the floor under a bench row whose goal the station misses: what a
bare server, doing only the gRPC part of the scenario, reaches on the machine. What each one
measures and what it showed: docs/probes.md.

- ``hop``:    one ProxyRobot move: the handler alone, then the round trip at 1 kHz on a no-op
  server, a bare server and the station's server stack;
- ``aio``:    a Teleoperate-like bidi echo at 1 kHz on grpcio's sync server and on grpc.aio;
- ``fanout``: a 1 kHz stream to an operator beside 100 Hz streams to observers;
- ``estop``:  when a loaded server sees an EmergencyStop arrive;
- ``arm``:    the arm at rest the hop and estop probes serve ProxyRobot's servicer on;
- ``tenant``: a process computing a share of every millisecond, the world's stand-in.
"""
