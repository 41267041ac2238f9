"""phasekit's documentation machinery, as one Sphinx extension.

* ``{pk}`group.name``` (role) and ``{pk-table} group.name`` (directive): numbers and tables
  generated from the committed study outputs in ``figures/`` and the reports in ``docs/data/``
  (:mod:`pkdocs.facts`); config ``pk_figures``, ``pk_data`` point elsewhere (tests use copies).
  The pages hold these values in place between ``<!-- pk:NAME -->`` markers (:mod:`pkdocs.inplace`),
  which the build reads back as the role and the directives (``source-read``).
* ``{pk-event-table}``: the table of events, from the declarations in ``phasekit/core/system.py``.
* ``{pk-cli-schema} COMMAND``: the JSON a CLI command prints, from real runs at build time.
* the gallery (``docs/gallery/``, generated): every script in ``examples/`` run and shown.

Config ``pk_execute = False`` skips running the examples and the CLI (pages say so).
"""

from __future__ import annotations

import json
import time

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective, SphinxRole

from . import cli_schema, events, facts, gallery, inplace
from .sources import DOCS, Sources

LOG = logging.getLogger(__name__)


def sources(app) -> Sources:
    if getattr(app, "_pk_sources", None) is None:
        app._pk_sources = Sources(app.config.pk_figures or None, app.config.pk_data or None)
    return app._pk_sources


def _note(env, src: Sources):
    for p in sorted(src.read):
        env.note_dependency(str(p))


def _markdown(directive: SphinxDirective, text: str) -> list[nodes.Node]:
    """Parse generated Markdown in place (the pages using these directives are MyST)."""
    box = nodes.container()
    directive.state.nested_parse(StringList(text.splitlines()), directive.content_offset, box)
    return box.children


class PkRole(SphinxRole):
    """An inline generated value: {pk}`steady.spheroid_classes`."""

    def run(self):
        src = sources(self.env.app)
        try:
            value = facts.lookup(src, self.text.strip())
        except Exception as e:  # noqa: BLE001 -- any failure to compute a number is a build error
            msg = self.inliner.reporter.error(f"pk: {self.text}: {type(e).__name__}: {e}", line=self.lineno)
            return [self.inliner.problematic(self.rawtext, self.rawtext, msg)], [msg]
        _note(self.env, src)
        return [nodes.Text(value)], []


class PkTable(SphinxDirective):
    """A generated block (a Markdown table): ```{pk-table} maps.table```."""

    required_arguments = 1

    def run(self):
        src = sources(self.env.app)
        try:
            text = facts.lookup(src, self.arguments[0])
        except Exception as e:  # noqa: BLE001
            raise self.error(f"pk-table {self.arguments[0]}: {type(e).__name__}: {e}") from e
        _note(self.env, src)
        return _markdown(self, text)


class PkEventTable(SphinxDirective):
    """The events of the hybrid system, generated from ``phasekit.core.system.declare``."""

    def run(self):
        import phasekit.core.system as system

        self.env.note_dependency(system.__file__)
        return _markdown(self, events.event_table())


class PkCliSchema(SphinxDirective):
    """The JSON of one command, merged from the runs made at build time."""

    required_arguments = 1

    def run(self):
        command = self.arguments[0]
        runs = [r for r in getattr(self.env.app, "_pk_cli_runs", []) if r.command == command]
        if not runs:
            if self.env.app.config.pk_execute:
                raise self.error(f"no runs of `phasekit {command}` (known: {', '.join(cli_schema.RUNS)})")
            return _markdown(self, "*(not run in this build: `pk_execute = False`)*")
        rec = cli_schema.record(runs)
        schema_dir = DOCS / "_generated" / "schemas"
        schema_dir.mkdir(parents=True, exist_ok=True)
        (schema_dir / f"{command}.schema.json").write_text(json.dumps(cli_schema.schema_of(rec, command), indent=1))
        LOG.info(f"pkdocs: wrote _generated/schemas/{command}.schema.json and the {command} table")
        link = f"{{download}}`{command}.schema.json </_generated/schemas/{command}.schema.json>`"
        text = cli_schema.page_block(rec, command, "The runs (made when these pages were built):", link)
        return _markdown(self, text + "\n")


def _source_read(app, docname, source):
    # the committed values between <!-- pk:NAME --> markers are read as the roles and directives
    # that compute them: the site shows the values of the data it is pointed at (pk_figures)
    source[0] = inplace.to_directives(source[0])


def _builder_inited(app):
    app._pk_sources = None
    execute, jobs = app.config.pk_execute, app.config.pk_jobs
    t0 = time.perf_counter()
    if execute:
        import concurrent.futures as cf

        n_cli = sum(len(r) for r in cli_schema.RUNS.values())
        LOG.info(f"pkdocs: running the {len(gallery.scripts())} examples and {n_cli} CLI runs "
                 f"({jobs} at a time); a line as each ends")
        # the examples and the CLI runs share the worker budget: both are subprocesses
        with cf.ThreadPoolExecutor(max_workers=2) as ex:
            cli = ex.submit(cli_schema.run_all, max(1, jobs // 2), LOG.info)
            runs = gallery.build(DOCS, execute=True, jobs=max(1, jobs - jobs // 2), log=LOG.info)
            app._pk_cli_runs = cli.result()
    else:
        runs = gallery.build(DOCS, execute=False, log=LOG.info)
        app._pk_cli_runs = []
    for r in runs.values():
        if r.missing:  # e.g. jq for the shell example: said on its page, as tests/contracts/test_examples.py skips it
            LOG.info(f"gallery: examples/{r.name} not run: {r.missing} is not installed")
    failed = [r for r in runs.values() if r.returncode != 0 and not r.missing]
    for r in failed:
        LOG.warning(f"gallery: examples/{r.name} failed (exit {r.returncode}):\n{r.stderr[-2000:]}")
    app._pk_gallery_runs = runs
    LOG.info(f"pkdocs: gallery ({len(runs)} scripts) and CLI runs in {time.perf_counter() - t0:.1f} s")


def _env_get_outdated(app, env, added, changed, removed):
    # generated pages depend on data the environment cannot see: always re-read them
    return [d for d in env.found_docs if d.startswith(("gallery/", "results/", "cli")) or d in ("architecture",)]


def setup(app):
    app.add_config_value("pk_figures", "", "env")
    app.add_config_value("pk_data", "", "env")
    app.add_config_value("pk_execute", True, "env")
    app.add_config_value("pk_jobs", 2, "env")
    app.add_role("pk", PkRole())
    app.add_directive("pk-table", PkTable)
    app.add_directive("pk-event-table", PkEventTable)
    app.add_directive("pk-cli-schema", PkCliSchema)
    app.connect("builder-inited", _builder_inited)
    app.connect("source-read", _source_read)
    app.connect("env-get-outdated", _env_get_outdated)
    return {"version": "1", "parallel_read_safe": False, "parallel_write_safe": True}
