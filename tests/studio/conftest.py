"""A real studio server for the API tests: uvicorn on 127.0.0.1 (a free port) in a thread, on
a temporary workspace holding a copy of the demo material, and a small http.client helper."""

from __future__ import annotations

import http.client
import json
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

DEMO = "black_ceramic_tiles.mat"


@dataclass
class Reply:
    status: int
    headers: dict[str, str]
    body: bytes

    def json(self) -> Any:
        return json.loads(self.body)


@dataclass
class StudioServer:
    """The running server: its port, token and workspace root."""

    port: int
    token: str
    root: Path
    app: Any

    def request(
        self,
        method: str,
        path: str,
        body: Any = None,
        *,
        token: str | None = "",
        headers: dict[str, str] | None = None,
        timeout: float = 60,
    ) -> Reply:
        """One request; ``token=""`` sends the right token, None none, else that token."""
        sent = {"Host": f"127.0.0.1:{self.port}", "Content-Type": "application/json"}
        if token is not None:
            sent["X-MatLoom-Token"] = token or self.token
        sent.update(headers or {})
        data = None if body is None else (body if isinstance(body, bytes) else json.dumps(body))
        conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=timeout)
        try:
            conn.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
            for name, value in sent.items():
                conn.putheader(name, value)
            payload = data.encode() if isinstance(data, str) else data
            conn.putheader("Content-Length", str(len(payload or b"")))
            conn.endheaders(payload)
            response = conn.getresponse()
            return Reply(
                response.status,
                {k.lower(): v for k, v in response.getheaders()},
                response.read(),
            )
        finally:
            conn.close()

    def post(self, path: str, body: Any, **kwargs: Any) -> Reply:
        return self.request("POST", path, body, **kwargs)

    def get(self, path: str, **kwargs: Any) -> Reply:
        return self.request("GET", path, **kwargs)


@pytest.fixture(scope="session")
def studio(tmp_path_factory: pytest.TempPathFactory) -> Iterator[StudioServer]:
    pytest.importorskip("starlette", reason="the studio needs the [studio] extra (starlette)")
    uvicorn = pytest.importorskip("uvicorn", reason="the studio needs the [studio] extra")

    from matloom.engine.session import Session
    from matloom.examples import example_text
    from matloom.studio.app import create_app
    from matloom.studio.security import new_token
    from matloom.studio.server import bind
    from matloom.studio.workspace import Workspace

    root = tmp_path_factory.mktemp("workspace").resolve()
    (root / DEMO).write_text(example_text("black_ceramic_tiles"), encoding="utf-8")
    config = tmp_path_factory.mktemp("config") / "matloom.toml"
    config.write_text("", encoding="utf-8")  # no model: generate and edit run offline
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("MATLOOM_CONFIG", str(config))
        sock = bind("127.0.0.1", 0)
        port = sock.getsockname()[1]
        token = new_token()
        # numpy: the same maps as numba, and no kernel compilation in the middle of a test
        app = create_app(Workspace(root, DEMO), token, port=port, session=Session(backend="numpy"))
        server = uvicorn.Server(uvicorn.Config(app, log_level="warning", lifespan="on"))
        thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
        thread.start()
        deadline = time.monotonic() + 30
        while not server.started and time.monotonic() < deadline:
            time.sleep(0.02)
        assert server.started, "the studio server did not start"
        try:
            yield StudioServer(port, token, root, app)
        finally:
            server.should_exit = True
            thread.join(timeout=10)
            sock.close()
