"""The local cluster of ``pinframes batch`` admits only its own client: TLS with keys made
for that cluster. Another process on the machine reaches 127.0.0.1 too; over plain TCP, it
could run any code in a worker."""

from __future__ import annotations

import asyncio

import pytest
from distributed import Client
from distributed.comm import connect
from distributed.security import Security

from pinframes.batch._engine import local_cluster

# a Dask cluster per test: in the slow set (CI runs it)
pytestmark = pytest.mark.slow


def _refused(address: str, security: Security | None) -> bool:
    """Whether a connection to ``address`` that then asks for the peer's identity fails."""
    async def attempt() -> None:
        arguments = {} if security is None else security.get_connection_args("client")
        comm = await connect(address, timeout=5, **arguments)
        try:
            await comm.write({"op": "identity", "reply": True})
            await comm.read()
        finally:
            comm.abort()

    try:
        asyncio.run(attempt())
    except (OSError, asyncio.TimeoutError):
        return True
    return False


@pytest.fixture(scope="module")
def cluster():
    with local_cluster(1) as running, Client(running) as client:
        assert client.submit(sum, [20, 22]).result() == 42  # its own client works
        yield running, list(client.scheduler_info()["workers"])


def test_the_local_cluster_speaks_only_tls(cluster):
    running, workers = cluster
    assert running.scheduler_address.startswith("tls://127.0.0.1:")
    assert workers and all(address.startswith("tls://127.0.0.1:") for address in workers)


def test_a_plain_tcp_client_is_refused_by_the_scheduler_and_the_workers(cluster):
    running, workers = cluster
    for address in [running.scheduler_address, *workers]:
        assert _refused(address.replace("tls://", "tcp://"), None), address
    with pytest.raises(OSError):
        Client(running.scheduler_address.replace("tls://", "tcp://"), timeout=5)


def test_a_tls_client_with_keys_of_another_authority_is_refused(cluster):
    running, workers = cluster
    stranger = Security.temporary()
    for address in [running.scheduler_address, *workers]:
        assert _refused(address, stranger), address
    assert not _refused(running.scheduler_address, running.security)  # the check can pass
