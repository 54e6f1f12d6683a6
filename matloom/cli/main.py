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
    "params": "matloom.cli.param_cmds:params_cmd",
    "set": "matloom.cli.param_cmds:set_cmd",
    "edit": "matloom.cli.edit_cmd:edit_cmd",
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
    "studio": "matloom.cli.studio_cmd:studio_cmd",
    "dataset": "matloom.cli.dataset_cmd:dataset_cmd",
    "bench": "matloom.cli.bench_cmd:bench_cmd",
}


#: top-level module of an optional dependency -> the extra of pyproject.toml that installs it.
EXTRAS: dict[str, str] = {
    "numba": "fast",
    "llvmlite": "fast",
    "openai": "llm",
    "MaterialX": "interop",
    "pxr": "interop",
    "torch": "clip",
    "torchvision": "clip",
    "open_clip": "clip",
    "starlette": "studio",
    "uvicorn": "studio",
    "distributed": "dask",
    "pyarrow": "dask",
    "scipy": "bench",
    "matplotlib": "bench",
    "cma": "polish",
}


def missing_dependency(command: str, err: ImportError) -> str:
    """One line for a command whose module failed to import: the missing module and the extra
    (or the reinstall) that provides it."""
    if isinstance(err, ModuleNotFoundError) and err.name:
        extra = EXTRAS.get(err.name.split(".")[0])
        fix = (
            f"install the extra: pip install 'matloom[{extra}]'"
            if extra is not None
            else "reinstall matloom with its dependencies"
        )
        return f"`matloom {command}` needs the module '{err.name}', which is not installed: {fix}"
    reason = " ".join(str(err).split())  # one line
    return f"`matloom {command}` could not be loaded ({reason}): reinstall matloom"


def _is_module_of(err: ImportError, module: str) -> bool:
    """Whether ``err`` says that ``module`` itself (or a package above it) does not exist, not
    something ``module`` imports."""
    return isinstance(err, ModuleNotFoundError) and (
        err.name is not None and (module == err.name or module.startswith(err.name + "."))
    )


class LazyGroup(click.Group):
    def invoke(self, ctx: click.Context) -> object:
        from matloom.io.outdir import OutputError

        try:
            return super().invoke(ctx)
        except OutputError as err:  # an unsafe or failed write: one line, nothing lost
            raise click.ClickException(str(err)) from None

    def list_commands(self, ctx: click.Context) -> list[str]:
        """The commands that load (one whose dependencies are missing is left out of --help)."""
        names = []
        for name in sorted(COMMANDS):
            try:
                if self.load(name) is not None:
                    names.append(name)
            except click.ClickException:
                continue
        return names

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        return self.load(name)

    @staticmethod
    def load(name: str) -> click.Command | None:
        """The command ``name``, imported now; None when there is no such command (click then
        says "No such command"). Raises :class:`click.ClickException`, one line naming the
        missing module and the extra to install, when a module the command imports is missing.
        """
        target = COMMANDS.get(name)
        if target is None:
            return None
        module, attr = target.split(":")
        try:
            loaded = importlib.import_module(module)
        except ImportError as err:
            if _is_module_of(err, module):
                return None
            raise click.ClickException(missing_dependency(name, err)) from None
        command = getattr(loaded, attr, None)
        return command if isinstance(command, click.Command) else None


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="matloom")
def cli() -> None:
    """MatLoom: layered material programs -> PBR texture maps."""
    from matloom.cli.progress import command_session

    command_session()  # the command's session: kernel compilation on stderr, numpy meanwhile


def main() -> None:
    try:
        cli.main(standalone_mode=True)
    except KeyboardInterrupt:
        click.echo("interrupted", err=True)
        sys.exit(130)


if __name__ == "__main__":
    main()
