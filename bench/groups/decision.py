"""The decision group: the operator's path through the DecisionServer. Teleoperate streamed
at each command rate (bench/teleop.py in a worker), lockstep as a diagnostic, recorded in MCAP,
over TLS and over pyzmq; with --profile, py-spy on it (bench/profile.py); then the emergency
stop through it, idle and under its intended load."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable

import grpc

from bench.command import acquire_control, release_control
from bench.groups.estop import add_load, under_load
from bench.plan import Plan
from bench.procs import ChildFailed
from bench.session import Session
from bench.station import OPERATOR_IDENTITY
from services.decision_server.backends import RETRY_S
from telerobot.v1 import decision_server_pb2_grpc

EPISODE_TASK = "bench: teleop_1000"


def steps(plan: Plan) -> int:
    return 9 + plan.profile


def run(bench: Session) -> None:
    """Through the DecisionServer, the operator's one address: teleop_<rate> (master
    commands streamed on Teleoperate, pipelined; teleop_1000_lockstep the same sent
    lockstep, a diagnostic; teleop_1000_mcap teleop_1000 recorded in MCAP, in pairs
    interleaved with it; teleop_1000_aa the same pairs with nothing recorded, a diagnostic),
    then teleop_1000_tls (the same pairs, the on legs through a DecisionServer of the TLS
    station), teleop_1000_zmq (the same
    DecisionCore over pyzmq) with the DecisionServer stopped, so nothing else follows
    ProxyRobot's streams meanwhile; then, through a fresh DecisionServer, the emergency
    stop idle and under its intended load (200 RunAction BusyWork on the low lane)."""
    teleop = [f"teleop_{rate}" for rate in bench.plan.command_rates]
    bench.with_decision_server(teleop + ["teleop_1000_lockstep", "teleop_1000_mcap",
                                         "teleop_1000_aa", "teleop_1000_tls"],
                               lambda address: _teleop(bench, address))
    if bench.plan.profile:
        bench.with_decision_server(["profile"],
                                   lambda address: _profile(bench, address))
    _teleop_baseline(bench)
    _teleop_episode(bench)
    bench.with_decision_server(["estop_ds_idle", "estop_ds_busywork"],
                               lambda address: _estop_ds(bench, address))


def _teleop(bench: Session, address: str) -> None:
    plan = bench.plan
    name = "teleop_1000_lockstep"
    bench.progress.step(f"{name} (diagnostic): Teleoperate at 1 kHz offered, each command "
                        f"waited for (the old way), {plan.command_s:.0f} s")
    try:
        result = bench.rate_worker("command", "teleop", address, [1000])["1000"]
        result["diagnostic"] = "lockstep: each command waits for the previous one's ack"
        bench.record(name, result)
        bench.progress.done(bench.headline(name))
    except ChildFailed as error:
        bench.fail([name], error)
    names = [f"teleop_{rate}" for rate in plan.command_rates]
    bench.progress.step(f"{', '.join(names)}: DecisionServer.Teleoperate, commands streamed "
                        f"at the offered rate (pipelined), {plan.command_s:.0f} s each")
    server = _cpu_of(bench)
    try:
        results = bench.rate_worker("teleop", "grpc", address, plan.command_rates, server)
    except ChildFailed as error:  # the recording's twin has nothing to compare with
        return bench.fail([*names, "teleop_1000_mcap", "teleop_1000_aa"], error)
    for rate in plan.command_rates:
        bench.record(f"teleop_{rate}", results[str(rate)])
    lockstep = bench.results.get(name, {})
    if "teleop_1000" in bench.results and lockstep.get("delivered_hz") is not None:
        bench.results["teleop_1000"].update(lockstep_delivered_hz=lockstep["delivered_hz"],
                                            lockstep_p99_ms=lockstep["p99_ms"])
    bench.progress.done("; ".join(f"{r}: {bench.headline(f'teleop_{r}')}"
                                  for r in plan.command_rates))
    # The same DecisionServer, right after. teleop_1000 moved +y: the legs go back (-y) and
    # out again in turn (mcap_twin's sign), so the arm swings about where it was.
    bench.mcap_twin("teleop_1000", "the DecisionServer recording the session in MCAP",
                    _teleop_leg(bench, address),
                    _teleop_leg(bench, address, record_dir=str(bench.procs.scratch / "recordings")))
    # The same pairs with nothing recorded: how far two identical legs' figures differ in
    # this run, the noise the ratio rows (_mcap, _episode, _tls) are judged in.
    bench.mcap_twin("teleop_1000", "nothing recorded: identical legs, this run's noise",
                    _teleop_leg(bench, address), _teleop_leg(bench, address), suffix="aa",
                    reuse_twin=False, pair_count=bench.plan.p99_pairs)
    if bench.tls is not None:
        _teleop_tls(bench, address)


def _teleop_leg(bench: Session, address: str, suffix: str = "",
                **extra) -> Callable[[int, float], dict]:
    """A leg of an interleaved row (Session.mcap_twin): Teleoperate at 1 kHz through the
    DecisionServer at `address` for overhead_teleop_leg_s, moving the arm `sign`-wards, its
    CPU per command measured (`suffix`: of the TLS station's processes, see _cpu_of);
    `extra` goes to the worker (what the on legs record, a TLS station's credentials)."""
    leg = {"duration_s": bench.plan.overhead_teleop_leg_s, **_cpu_of(bench, suffix)}
    return lambda index, sign: bench.rate_worker("teleop", "grpc", address, [1000], {
        "first_sign": sign, **leg, **extra})["1000"]


def _cpu_of(bench: Session, suffix: str = "") -> dict:
    """A teleop worker's parameters to measure the DecisionServer's and ProxyRobot's CPU per
    command (`suffix`: the TLS station's, "_tls")."""
    return {"server_pid": bench.pid("decision_server" + suffix),
            "proxy_pid": bench.pid("proxy_robot" + suffix)}


def _teleop_episode(bench: Session) -> None:
    """teleop_1000_episode: teleop_1000 off and on, interleaved, the on legs recorded as a
    demonstration episode (MCAP, the state at 100 Hz, the stereo video) by a DecisionServer
    with a camera behind it, each written by the recording's writer process (its CPU per
    command is the row's writer_cpu_ms_per_command). The camera is the test card (pattern):
    the row measures what recording costs (an H.264 stream encoded at 320x240 per eye, written
    with the rest), not what rendering the sim costs, which a real camera does not."""
    name = "teleop_1000_episode"
    try:
        camera, camera_address = bench.procs.run_service("stereo_camera", [
            "--source", "pattern", "--width", "640", "--height", "480", "--fps", "30"])
    except ChildFailed as error:
        bench.progress.step(f"{name}: starting its camera")
        return bench.fail([name], error)
    try:
        with bench.decision_server(bench.station, camera_address) as address:
            bench.mcap_twin(
                "teleop_1000", "the DecisionServer recording it as a demonstration episode "
                "(MCAP, the state at 100 Hz, the pattern camera's video at 320x240 per eye)",
                _teleop_leg(bench, address),
                _teleop_leg(bench, address, episode_task=EPISODE_TASK,
                            record_dir=str(bench.procs.scratch / "recordings")),
                suffix="episode", reuse_twin=False, pair_count=bench.plan.p99_pairs)
    except ChildFailed as error:
        bench.progress.step(f"{name}: starting its DecisionServer")
        bench.fail([name], error)
    finally:
        bench.procs.stop(camera)


def _teleop_tls(bench: Session, address: str) -> None:
    """teleop_1000_tls: teleop_1000's legs through the DecisionServer at `address`,
    interleaved with legs through a DecisionServer of the TLS station (which presents its
    own certificate to ProxyRobot), the worker presenting an operator's. The TLS station
    drives the world for its legs (Session.driving), and each leg after a change of driver
    starts once the DecisionServer's streams from the station that drives now are back."""
    name = "teleop_1000_tls"
    tls = bench.tls
    try:
        with bench.decision_server(tls) as tls_address:
            secure = _teleop_leg(bench, tls_address, tls.suffix,
                                 **tls.client_params(OPERATOR_IDENTITY))
            plaintext = _teleop_leg(bench, address)

            def on(index: int, sign: float) -> dict:
                with bench.driving(tls):
                    _await_streams()
                    return secure(index, sign)

            def off(index: int, sign: float) -> dict:
                _await_streams()  # (the TLS station drove the world for the leg before)
                return plaintext(index, sign)

            bench.mcap_twin("teleop_1000", "the on legs through the station serving mutual "
                            "TLS", off, on, suffix="tls", pair_count=bench.plan.p99_pairs)
    except ChildFailed as error:  # (a leg's own failure is mcap_twin's)
        bench.progress.step(f"{name}: starting its DecisionServer")
        bench.fail([name], error)
    except grpc.RpcError as error:  # a station's set-up calls as a leg changes the driver
        bench.fail([name], error)


def _await_streams() -> None:
    """Until the DecisionServer's streams from a station that drives the world again are
    back: each retries every RETRY_S after a failure, so within one RETRY_S of the change,
    and a retry may itself take a round trip; twice that."""
    time.sleep(2 * RETRY_S)


def _teleop_baseline(bench: Session) -> None:
    """teleop_1000_zmq: the DecisionServer's DecisionCore and GrpcSlave (to this station's
    ProxyRobot and ForceSensor) behind pyzmq DEALER/ROUTER, streamed the same way."""
    plan = bench.plan
    name = "teleop_1000_zmq"
    bench.progress.step(f"{name}: the same DecisionCore over pyzmq DEALER/ROUTER, "
                        f"pipelined at 1 kHz, {plan.command_s:.0f} s")
    server = bench.procs.start("baseline_teleop", [
        "-m", "bench.baseline_server", "--transport", "zmq-teleop",
        "--proxy-robot-address", bench.station.address["proxy_robot"],
        "--force-sensor-address", bench.station.address["force_sensor"]])
    try:
        address = server.wait_ready("baseline_teleop", timeout_s=60.0)
        result = bench.rate_worker("teleop", "zmq", address, [1000])["1000"]
    except ChildFailed as error:
        return bench.fail([name], error)
    finally:
        bench.procs.stop(server)
    bench.record(name, result)
    bench.progress.done(bench.headline(name))


def _estop_ds(bench: Session, address: str) -> None:
    plan = bench.plan
    params = {"address": address, "shm": bench.shm, "trials": plan.estop_trials,
              "decision_server": True}
    timeout = 60 + plan.estop_trials * 3
    bench.progress.step("estop_ds_idle: EmergencyStop through the DecisionServer, idle")
    try:
        result = bench.worker("estop", {**params, "label": "ds idle"}, timeout)
        bench.record("estop_ds_idle", result)
        bench.progress.done(bench.headline("estop_ds_idle"))
    except ChildFailed as error:
        bench.fail(["estop_ds_idle"], error)
    bench.progress.step(f"estop_ds_busywork: the same with {plan.load_concurrency} "
                        "concurrent RunAction BusyWork (20 ms each) on the low lane")
    # BusyWork needs the control lease: one lease for both workers (a plaintext station's
    # lease is not bound to an identity).
    with grpc.insecure_channel(address) as channel:
        decision = decision_server_pb2_grpc.DecisionServerStub(channel)
        lease = acquire_control(decision)
        try:
            result, load = under_load(bench, {
                "address": address, "target": "decision_server", "lease_id": lease,
                "concurrency": plan.load_concurrency, "max_s": timeout + 30},
                lambda: bench.worker("estop", {**params, "label": "ds busywork",
                                               "lease_id": lease}, timeout))
        except ChildFailed as error:
            return bench.fail(["estop_ds_busywork"], error)
        finally:
            release_control(decision, lease)
    add_load(result, load, "200 concurrent DecisionServer.RunAction BusyWork (20 ms), "
             "telerobot-lane: low", bench.results.get("estop_ds_idle", {}))
    bench.record("estop_ds_busywork", result)
    bench.progress.done(bench.headline("estop_ds_busywork")
                        + f" (load {load['calls_per_s']:.0f} calls/s)")


def _profile(bench: Session, address: str) -> None:
    """Teleoperate at 1 kHz again, with py-spy on the DecisionServer and ProxyRobot."""
    from bench.profile import Recording

    seconds = bench.plan.command_s + 1
    bench.progress.step(f"profile: Teleoperate at 1 kHz for {seconds:.0f} s with py-spy on "
                        "decision_server and proxy_robot")
    pids = {child.name: child.pid for child in bench.procs.children
            if child.name in ("decision_server", "proxy_robot")
            and child.process.poll() is None}
    recording = Recording(pids, seconds, bench.out_dir)
    try:
        bench.rate_worker("teleop", "grpc", address, [1000])
    except ChildFailed as error:
        bench.progress.note(f"profile run failed: {error}")
    summaries = recording.finish()
    bench.progress.done(f"raw stacks in {', '.join(str(p) for p in recording.paths.values())}")
    for name, text in summaries.items():
        print(f"\n== {name}, Teleoperate at 1 kHz: {text}", file=sys.stderr)
