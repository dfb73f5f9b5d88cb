from tests.world.conftest import world_factory  # noqa: F401 - shared fixture
