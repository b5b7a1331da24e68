"""The sweep on dask.distributed: a LocalCluster of 2 workers gives the local numbers exactly."""

from __future__ import annotations

import pytest
import xarray as xr

from rotorkin.io.config import load_config
from rotorkin.sweep import run_sweep

distributed = pytest.importorskip("distributed", reason="the [dask] extra is not installed")


@pytest.fixture(scope="module")
def client():
    from rotorkin.sweep.dask import local_client

    with local_client(2, processes=False) as c:
        yield c


def _dashboard_hosts(client) -> set:
    """The addresses the dashboard's sockets are bound to (tornado's listening sockets)."""
    server = client.cluster.scheduler.http_server
    return {sock.getsockname()[0] for sock in server._sockets.values()}


def test_the_local_cluster_listens_on_loopback_only(client):
    assert _dashboard_hosts(client) == {"127.0.0.1"}
    assert client.scheduler_info()["address"].startswith("inproc://")  # no socket at all


@pytest.mark.slow
def test_a_process_cluster_listens_on_loopback_only():
    from urllib.parse import urlparse

    from rotorkin.sweep.dask import local_client

    with local_client(1, processes=True) as c:
        info = c.scheduler_info()
        assert urlparse(info["address"]).hostname == "127.0.0.1"
        assert _dashboard_hosts(c) == {"127.0.0.1"}
        assert all(urlparse(w).hostname == "127.0.0.1" for w in info["workers"])


def test_dask_sweep_equals_the_local_sweep(client):
    _, raw, _ = load_config(None, "guide-bar-pump")
    vary = {"drive.lambda": "0.2:0.8:7", "drive.driver": "crank,guide",
            "machine.vane_angle": "40deg,50deg"}  # fmt: skip
    local = run_sweep(raw, vary, progress=False, samples=2001, chunk_size=5)
    remote = run_sweep(raw, vary, progress=False, samples=2001, chunk_size=5, client=client)
    xr.testing.assert_identical(local, remote)
    assert int((remote["reason"] != 0).sum()) >= 1  # inadmissible designs travel as well


def test_dask_sweep_with_a_store_and_curves(client, tmp_path):
    _, raw, _ = load_config(None, "wobble-cam-engine")
    vary = {"drive.plate_tilt": "30deg:50deg:4", "drive.roller_axis_angle": "85deg,95deg"}
    local = run_sweep(raw, vary, progress=False, samples=721, keep_curves=True)
    remote = run_sweep(raw, vary, progress=False, samples=721, keep_curves=True, chunk_size=3,
                       client=client, store=tmp_path)  # fmt: skip
    xr.testing.assert_identical(local.drop_attrs(), remote.drop_attrs())
    with xr.open_dataset(tmp_path / "sweep.nc", engine="scipy") as ds:
        xr.testing.assert_identical(ds.load(), remote)


@pytest.mark.slow
def test_cli_workers_option(tmp_path, capsys):
    from rotorkin.cli import main

    out = tmp_path / "dask"
    args = [
        "sweep",
        "-e",
        "eccentric-reactor",
        "--vary",
        "drive.eccentricity=10mm:70mm:4",
        "--angles",
        "721",
        "--workers",
        "2",
        "--out",
        str(out),
        "-q",
    ]
    assert main(args) == 0
    plain = tmp_path / "plain"
    assert main([*args[:-5], "--out", str(plain), "-q"]) == 0
    with xr.open_dataset(out / "sweep.nc", engine="scipy") as a, \
            xr.open_dataset(plain / "sweep.nc", engine="scipy") as b:  # fmt: skip
        xr.testing.assert_identical(a.load(), b.load())
