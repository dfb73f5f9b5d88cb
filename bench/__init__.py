"""`make bench` (`python -m bench`): the papers' figures, measured on real processes on loopback,
with baselines (pyzmq, a plain TCP socket with struct framing) measured in the same run.

Layout:

- ``__main__.py``    the command line; ``run.py`` the order of scenarios and the station;
- ``procs.py``       child processes (services, workers, baseline servers) and their clean stop;
- ``worker.py``      ``python -m bench.worker KIND``: one measuring client process;
- ``run.py``'s groups: command, force, baselines, observers, estop, decision (Teleoperate and
  the e-stop through the DecisionServer), closed_loop, stereo, soak (``python -m bench --only``);
- ``command.py``, ``teleop.py``, ``force.py``, ``estop.py``, ``closed_loop.py``, ``stereo.py``:
  the scenarios' client code (run inside workers); ``teleop.py`` streams Teleoperate pipelined;
- ``baseline_server.py``: the same domain code (ProxyRobotCore, ForceSensorCore; the
  DecisionServer's DecisionCore for Teleoperate) behind pyzmq or a plain TCP socket
  (``framing.py``) instead of gRPC, so a ratio isolates the transport;
- ``worldwatch.py``  reads the world's shared memory (read only) to see what the servo applied;
  ``worldloop.py`` counts the world loop's overruns per scenario and over the run;
- ``soak.py``        the soak (``--only soak``, not in ``make bench``): the station under a
  steady load for 10 minutes, each process's RSS slope and what was lost (issue #16);
- ``goals.py``       the one table of goals, and each scenario's PASS/FAIL;
- ``stats.py``, ``report.py``, ``plots.py``: figures, the terminal table, JSON and PNG plots;
  ``readme.py`` (``python -m bench.readme``) README.md's Performance table from the JSON.

How each scenario is measured, the goals and how to read PASS/FAIL: ``bench/README.md``.
"""
