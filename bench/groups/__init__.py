"""The bench's groups (`python -m bench --only GROUP`), a module each, named for the group:
what it measures, `steps(plan)` (its progress lines) and `run(session)` (its rows, recorded in
the bench.session.Session it is given). bench/run.py runs them in bench.plan.GROUPS' order.
Each runs its measuring clients as worker processes (bench/worker.py) whose code is the
scenario's module in bench/ (command.py, teleop.py, force.py, estop.py, ...)."""
