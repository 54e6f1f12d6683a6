"""The `matloom` command: one click group, subcommands loaded lazily (fast start-up)."""

from __future__ import annotations

import importlib
import sys

import click

#: subcommand -> "module:attribute"; modules are imported only when the command runs.
COMMANDS: dict[str, str] = {
    "check": "matloom.cli.lang_cmds:check_cmd",
    "fmt": "matloom.cli.lang_cmds:fmt_cmd",
    "seeds": "matloom.cli.lang_cmds:seeds_cmd",
    "render": "matloom.cli.engine_cmds:render_cmd",
    "random": "matloom.cli.engine_cmds:random_cmd",
    "preview": "matloom.cli.render_cmds:preview_cmd",
    "stats": "matloom.cli.render_cmds:stats_cmd",
    "sweep": "matloom.cli.render_cmds:sweep_cmd",
    "generate": "matloom.cli.generate_cmd:generate_cmd",
    "prompt": "matloom.cli.generate_cmd:prompt_cmd",
    "gallery": "matloom.cli.gallery_cmd:gallery_cmd",
    "demo": "matloom.cli.demo_cmd:demo_cmd",
    "scorer": "matloom.cli.generate_cmd:scorer_cmd",
    "blender": "matloom.cli.blender_cmd:blender_cmd",
    "library": "matloom.cli.library_cmd:library_cmd",
}


class LazyGroup(click.Group):
    def invoke(self, ctx: click.Context) -> object:
        from matloom.io.outdir import OutputError

        try:
            return super().invoke(ctx)
        except OutputError as err:  # an unsafe or failed write: one line, nothing lost
            raise click.ClickException(str(err)) from None

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(n for n in COMMANDS if self._load(n) is not None)

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        return self._load(name)

    @staticmethod
    def _load(name: str) -> click.Command | None:
        target = COMMANDS.get(name)
        if target is None:
            return None
        module, attr = target.split(":")
        try:
            return getattr(importlib.import_module(module), attr)
        except (ImportError, AttributeError):
            return None


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="matloom")
def cli() -> None:
    """MatLoom: layered material programs -> PBR texture maps."""
    from matloom.cli.progress import kernel_start_up

    kernel_start_up()  # first-run kernel compilation: progress on stderr, numpy meanwhile


def main() -> None:
    try:
        cli.main(standalone_mode=True)
    except KeyboardInterrupt:
        click.echo("interrupted", err=True)
        sys.exit(130)


if __name__ == "__main__":
    main()
