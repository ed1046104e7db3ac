"""Commands about the catalogue and its documentation: components, docs."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from morsec.cli.common import console, fail, on_terminal
from morsec.errors import MorsecError


def components(name: Annotated[str | None, typer.Argument(help="a component id or builder class name")] = None) -> None:
    """List the catalogue (built-in and this project's components), or describe one component."""
    from morsec.app.describe import catalogue_listing, describe_component
    from morsec.component.catalogue import load_catalogue
    try:
        cat = load_catalogue()
        text = catalogue_listing(cat) if name is None else describe_component(cat, name)
    except MorsecError as err:
        fail(err)
    if name is not None and on_terminal():
        from rich.markdown import Markdown
        console().print(Markdown(text))
    else:
        typer.echo(text)


def docs(
    out: Annotated[Path, typer.Option("-o", "--out", help="docs folder to write the generated pages into")] = (
        Path("docs")),
    pictures: Annotated[bool, typer.Option(help="also render the gallery's pictures (slow: one scene each)")] = False,
) -> None:
    """Regenerate the reference pages (scene-format.md, components.md, the component gallery) from the
    models and the catalogue; with --pictures, the gallery's pictures too."""
    from morsec.app.docsgen import write_docs
    from morsec.component.catalogue import load_catalogue
    try:
        cat = load_catalogue()
        written = write_docs(out, cat)
        if pictures:
            from rich.progress import Progress

            from morsec.app.gallery import picture_count, render_pictures
            err = console(stderr=True)
            with Progress(console=err, transient=True, disable=not err.is_terminal) as progress:
                task = progress.add_task("rendering pictures", total=picture_count(cat))
                written += render_pictures(cat, out, advance=lambda: progress.advance(task))
        typer.echo(f"wrote {len(written)} files in {out}")
    except MorsecError as err:
        fail(err)
    except OSError as err:
        fail(MorsecError(f"{out}: cannot write the docs: {err.strerror or err}"))
