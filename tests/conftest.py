import os

import pytest

# Every diagnostic reported while the tests run (in this process and in the children the
# tests start) is checked against rapidgen/codes.py: code registered, severity allowed.
os.environ["RAPIDGEN_CHECK_CODES"] = "1"


def pytest_addoption(parser):
    parser.addoption("--update-golden", action="store_true", default=False,
                     help="rewrite golden expectations from the current output")


@pytest.fixture
def update_golden(request) -> bool:
    return bool(request.config.getoption("--update-golden"))
