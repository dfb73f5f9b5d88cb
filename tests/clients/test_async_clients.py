"""The asyncio clients (grpc.aio): the same methods, awaited, against the real processes."""

from __future__ import annotations

import asyncio

import grpc
import numpy as np
import pytest

from clients.python import (
    AbortedError,
    AsyncDecisionClient,
    AsyncProxyRobotClient,
    AsyncStereoCameraClient,
    CommandOutcome,
    ControlMode,
    InvalidArgumentError,
    RobotState,
    RobotStatus,
)
from services.stereo_camera.pattern import read_tick
from telerobot.v1 import decision_server_pb2 as pb
from tests.clients.conftest import CAMERA_WIDTH_PX

pytestmark = pytest.mark.e2e


def test_async_decision_client_lease_teleoperate_and_streams(station):
    async def main():
        async with AsyncDecisionClient(station.address) as client:
            with pytest.raises(InvalidArgumentError) as error:
                await client.acquire_control("ann", ControlMode.UNSPECIFIED)
            assert error.value.reason == "BAD_MODE"
            assert error.value.code is grpc.StatusCode.INVALID_ARGUMENT
            lease = await client.acquire_control("ann")
            assert client.lease is lease
            await asyncio.to_thread(station.ready_at_home,
                                    [("telerobot-lease-id", lease.lease_id)])
            state = await client.robot.get_state()
            assert isinstance(state, RobotState) and state.joint_positions.shape == (6,)

            acks = []
            async with await client.teleoperate(watchdog_timeout_s=0.5,
                                                on_ack=acks.append) as session:
                ack = await session.send((0, 0, 0.002))
                assert ack.sequence == 1 and ack.outcome is CommandOutcome.APPLIED
                assert (await session.send((0, 0, 0.002), clutch=True)).outcome \
                    is CommandOutcome.INDEXED
                assert await session.send_nowait((0, 0.001, 0)) == 3
                heartbeat = await session.heartbeat()
                assert heartbeat.outcome is CommandOutcome.HEARTBEAT
                assert [a.sequence for a in acks] == [1, 2, 3, 0]
            assert session.closed and session.error is None

            async with client.robot.stream_state(0.01, timeout=10) as states:
                sequences = []
                async for sample in states:
                    sequences.append(sample.sequence)
                    if len(sequences) == 3:
                        break
            assert sequences == sorted(set(sequences))
            await asyncio.to_thread(station.wait_status, RobotStatus.READY)
        # async with released the lease and closed the channel
        holders = station.decisions.GetControlState(pb.GetControlStateRequest()).state.holders
        assert not holders
        with pytest.raises(RuntimeError, match="closed"):
            await client.get_control_state()

    asyncio.run(main())


def test_async_session_ends_with_aborted_when_the_lease_is_lost(station):
    async def main():
        async with AsyncDecisionClient(station.address) as client:
            lease = await client.acquire_control("ann")
            await asyncio.to_thread(station.ready_at_home,
                                    [("telerobot-lease-id", lease.lease_id)])
            session = await client.teleoperate(watchdog_timeout_s=0.5)
            assert (await session.heartbeat()).outcome is CommandOutcome.HEARTBEAT
            await client.release_control()
            with pytest.raises(AbortedError) as error:
                await session.send((0, 0, 0.001))
            assert error.value.reason == "CONTROL_LOST"
            with pytest.raises(AbortedError):
                await session.send((0, 0, 0.001))
            await session.close()

    asyncio.run(main())


def test_async_proxy_robot_and_camera(station, backends, camera_address):
    async def main():
        async with AsyncProxyRobotClient(backends.proxy_address) as robot:
            with pytest.raises(InvalidArgumentError) as error:
                await robot.move_joints(np.full(6, np.nan))
            assert error.value.reason == "NOT_FINITE"
            assert (await robot.get_status()).status in set(RobotStatus)
        async with AsyncStereoCameraClient(camera_address) as camera:
            snapshot = await camera.get_snapshot()
            assert read_tick(snapshot.left) == read_tick(snapshot.right) == snapshot.sequence
            async with camera.stream_pairs(timeout=20) as stream:
                async for frame in stream:
                    assert frame.header.width_px == CAMERA_WIDTH_PX
                    assert read_tick(frame.left) == frame.sequence
                    break
            with pytest.raises(InvalidArgumentError):
                async for _ in camera.stream_pairs(max_fps=-1, timeout=20):
                    pass

    asyncio.run(main())
