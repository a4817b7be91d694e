"""Shared by the package's tests: every test asserts the Vulkan validation layer (on in
run_pytest.cmake) reported nothing while it ran."""
import pytest

import strata


@pytest.fixture(autouse=True)
def no_validation_errors():
    before = strata.validation_errors()
    yield
    assert strata.validation_errors() == before, "Vulkan validation errors during the test"
