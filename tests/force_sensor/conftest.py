from tests.proxy_robot.conftest import world_factory  # noqa: F401 - shared fixture
