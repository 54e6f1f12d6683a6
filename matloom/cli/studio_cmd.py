"""`matloom studio`: open the browser workspace (the optional ``[studio]`` extra)."""

from __future__ import annotations

import click

#: A TCP port; 0 lets the system choose a free one.
PORT = click.IntRange(0, 65535)


@click.command("studio")
@click.argument("target", required=False, metavar="[FILE|FOLDER]")
@click.option("--port", type=PORT, default=0, show_default=True, help="Port (0: a free one).")
@click.option(
    "--host",
    default="127.0.0.1",
    show_default=True,
    help="Address to listen on; requests must name it (or the loopback) as their Host. Other "
    "than the loopback, anyone who can reach it and has the URL can use the studio.",
)
@click.option("--no-browser", is_flag=True, help="Print the URL; do not open a browser.")
@click.option(
    "--link",
    metavar="PERMALINK",
    help="Open the program of a studio permalink (a URL ending in #p=..., from any machine).",
)
def studio_cmd(
    target: str | None, port: int, host: str, no_browser: bool, link: str | None
) -> None:
    """Open the studio on FILE (its folder is the workspace), on FOLDER's programs, or, with no
    argument, on a copy of the demo material in ./matloom-studio/ (made if missing)."""
    try:
        import starlette  # noqa: F401 - the studio's server
        import uvicorn  # noqa: F401
    except ImportError as err:
        name = getattr(err, "name", None) or "starlette"
        raise click.ClickException(
            f"`matloom studio` needs {name}, which is not installed: pip install 'matloom[studio]'"
        ) from None
    from matloom.studio.permalink import PermalinkError, decode, encode
    from matloom.studio.server import serve
    from matloom.studio.workspace import DEMO_FOLDER, Workspace, WorkspaceError

    if host in ("0.0.0.0", "::", ""):
        raise click.ClickException(
            f"--host {host or repr(host)} would listen on every address, but the studio checks that "
            "each request names the address it serves: give one address (e.g. this machine's "
            "LAN address), or leave the default 127.0.0.1"
        )
    fragment = ""
    if link is not None:
        try:
            fragment = encode(decode(link))
        except PermalinkError as err:
            raise click.ClickException(str(err)) from None
    try:
        workspace = Workspace.open(target)
    except WorkspaceError as err:
        raise click.ClickException(str(err)) from None
    if target is None:
        click.echo(
            f"matloom: no FILE or FOLDER given: working in ./{DEMO_FOLDER}/ on a copy of the "
            "demo material (saves go there)",
            err=True,
        )
    try:
        serve(workspace, host=host, port=port, open_browser=not no_browser, fragment=fragment)
    except OSError as err:
        raise click.ClickException(
            f"cannot listen on {host}:{port}: {err.strerror or err}"
        ) from None
