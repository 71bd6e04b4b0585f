import pytest

from plxtools.model.workspace import Workspace


@pytest.fixture(scope="session")
def workspace():
    return Workspace()
