"""Shared test settings.

Under CI (``CI`` set in the environment) every optional tool is installed by
``.ci/run``, so a test that skips there hides a gap: it is turned into a failure.
On a developer's machine without, say, chromium or build123d, such tests skip
and say why.
"""

from __future__ import annotations

import os

import pytest


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if os.environ.get("CI") and report.skipped and call.when in ("setup", "call"):
        reason = report.longrepr[-1] if isinstance(report.longrepr, tuple) else report.longrepr
        report.outcome = "failed"
        report.longrepr = f"skipped under CI, where everything must run: {reason}"


def pytest_collection_modifyitems(config, items):
    """A test that needs the browser or build123d is slow: ``-m "not slow"`` leaves it out."""
    for item in items:
        if item.get_closest_marker("browser") or item.get_closest_marker("cad"):
            item.add_marker(pytest.mark.slow)


# Property tests draw the same examples on every run under CI, so that a red run can be
# reproduced; on a developer's machine they explore new examples each time.
from hypothesis import settings as _settings  # noqa: E402

_settings.register_profile("ci", derandomize=True)
if os.environ.get("CI"):
    _settings.load_profile("ci")
