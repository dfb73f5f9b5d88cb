"""`make bench` (`python -m bench`): the papers' figures, measured on real processes on loopback,
with baselines (pyzmq, a plain TCP socket with struct framing) measured in the same run.

Layout:

- ``__main__.py``    the command line; ``plan.py`` the groups (``--only``) and how long each
  scenario runs; ``run.py`` starts the station, runs the groups in order, writes the results;
- ``station.py``     the slave station the run starts (and its mutual-TLS twin);
  ``session.py``     the run's state and what every group does with it (workers, rows,
  failures, the ``*_tls`` and ``*_mcap`` twins, a DecisionServer in front of the station);
- ``groups/``        a module per group, each what its rows measure: command, force,
  baselines, observers, estop, decision (Teleoperate and the e-stop through the
  DecisionServer), closed_loop, stereo, soak, soak_overload, network, video;
- ``procs.py``       child processes (services, workers, baseline servers) and their clean stop;
- ``worker.py``      ``python -m bench.worker KIND``: one measuring client process;
- ``command.py``, ``teleop.py``, ``force.py``, ``estop.py``, ``closed_loop.py``, ``stereo.py``:
  the scenarios' client code (run inside workers); ``teleop.py`` streams Teleoperate pipelined;
- ``soak.py``, ``overload.py``, ``network.py``, ``video.py``: those groups' definitions,
  worker side, rows, tables and figures (the soak, issue #16; Teleoperate beside busy
  co-tenants, soak_overload, #29; the peg-in-hole task across a delayed link, #14 and #15;
  the stereo stream across it, #27);
- ``baseline_server.py``: the same domain code (ProxyRobotCore, ForceSensorCore; the
  DecisionServer's DecisionCore for Teleoperate) behind pyzmq or a plain TCP socket
  (``framing.py``) instead of gRPC, so a ratio isolates the transport;
- ``worldwatch.py``  reads the world's shared memory (read only) to see what the servo applied;
  ``worldloop.py`` counts the world loop's overruns per scenario and over the run;
- ``goals.py``       the one table of goals, and each scenario's PASS/FAIL;
- ``stats.py``, ``report.py``, ``plots.py``: figures, the terminal table, JSON and PNG plots;
  ``readme.py`` (``python -m bench.readme``) the Performance tables from the JSON;
- ``probes/``        experiments that print figures and judge nothing: the floor under the rows
  that miss their goals (docs/probes.md).

How each scenario is measured, the goals and how to read PASS/FAIL: ``bench/README.md``.
"""
