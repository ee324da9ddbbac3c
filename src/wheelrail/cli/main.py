"""Entry point of the ``wheelrail`` command.

Adding a sub-command
--------------------
Write a module ``wheelrail/cli/<name>.py`` that defines

* ``HELP`` — a one-line description shown by ``wheelrail --help``;
* ``add_arguments(parser)`` — adds its arguments to an ``argparse`` parser;
* ``run(args, console) -> int`` — does the work, prints with the ``rich``
  ``console`` and returns the exit code (0 on success).

and add one line ``("<command-name>", "wheelrail.cli.<name>")`` to
:data:`COMMANDS` below. Keep heavy imports (numpy solvers, matplotlib) inside
``run`` so that ``wheelrail --help`` stays fast.

Errors
------
A command raises exceptions; :func:`main` turns them into one line on stderr,
``wheelrail: error: ...``, and the exit code 2 for bad input
(:class:`~wheelrail.errors.InputError`, :class:`~wheelrail.errors.CaseFileError`,
:class:`~wheelrail.errors.ProfileError`, a missing file, bad arguments) or 1
for anything else. ``--debug`` shows the traceback instead.
"""

from __future__ import annotations

import argparse
import importlib
import sys

#: Sub-commands: (name, module). One line per command.
COMMANDS = [
    ("solve", "wheelrail.cli.solve"),
    ("creep-curve", "wheelrail.cli.creep_curve"),
    ("demo", "wheelrail.cli.demo"),
    ("geometry", "wheelrail.cli.geometry"),
    ("wheelset", "wheelrail.cli.wheelset"),
    ("fe", "wheelrail.cli.fe"),
    ("sweep", "wheelrail.cli.sweep"),
    ("compare", "wheelrail.cli.compare"),
    ("transient", "wheelrail.cli.transient"),
    ("dynamics", "wheelrail.cli.dynamics"),
    ("wear", "wheelrail.cli.wear"),
    ("validate", "wheelrail.cli.validate"),
    ("build-table", "wheelrail.cli.build_table"),
    ("compile", "wheelrail.cli.compile"),
]

EXIT_OK, EXIT_ERROR, EXIT_USAGE = 0, 1, 2


class _UsageError(Exception):
    """Bad command-line arguments (exit code 2)."""


class _Parser(argparse.ArgumentParser):
    """An ArgumentParser whose errors are one line and do not exit the interpreter."""

    def error(self, message):
        raise _UsageError(f"{message} (see '{self.prog} --help')")


def build_parser(argv=None) -> argparse.ArgumentParser:
    """The ``wheelrail`` parser with every sub-command of :data:`COMMANDS`.

    With ``argv`` (the command line to parse), only the sub-command it names gets its
    options; the others are listed with their help but not built. Building a
    sub-command's options may import the library (``build-table`` shows the table
    builder's defaults), so a run builds only the command it runs.
    """
    from .. import __version__

    parser = _Parser(prog="wheelrail",
                     description="Wheel-rail contact mechanics: normal contact, creep forces, "
                                 "case files (SI units, Kalker's sign convention).")
    parser.add_argument("--version", action="version", version=f"wheelrail {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    parser.add_argument("--memory-limit", metavar="SIZE", default=None,
                        help="refuse boundary-element solves estimated to need more memory "
                             "(e.g. 8GB, 500MB, off; default min(4 GiB, half the RAM))")
    parser.add_argument("--time-limit", metavar="DURATION", default=None,
                        help="refuse jobs (sweeps, transient runs, boundary-element and exact "
                             "grids) estimated to take longer (e.g. 3h, 30min, off; default 1h)")
    parser.add_argument("--no-plausibility-checks", action="store_true",
                        help="accept values outside the wheel-rail range (e.g. mu > 2, a patch "
                             "larger than the radii) without warning or refusal")
    only = None if argv is None else _command_of(argv, parser)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name, module_name in COMMANDS:
        module = importlib.import_module(module_name)
        p = sub.add_parser(name, help=module.HELP, description=module.HELP)
        if only is not None and name != only:
            continue
        p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                       help="show tracebacks on errors")
        module.add_arguments(p)
        if not any(a.dest == "estimate_only" for a in p._actions):
            p.add_argument("--estimate-only", action="store_true",
                           help="print the time and memory estimate of the first long "
                                "computation and stop (nothing is computed or written)")
        p.set_defaults(_run=module.run)
    return parser


def _command_of(argv, parser) -> str:
    """The sub-command ``argv`` asks for: its first word that is neither an option nor the
    value of one of ``parser``'s options ("" when there is none, as in ``wheelrail
    --help``)."""
    it = iter(argv)
    for a in it:
        action = parser._option_string_actions.get(a)
        if action is not None and action.nargs != 0:
            next(it, None)              # the option's value
        elif not a.startswith("-"):
            return a
    return ""


def _exit_code(exc: BaseException) -> int:
    from ..errors import CaseFileError, InputError, ProfileError

    if isinstance(exc, (_UsageError, InputError, CaseFileError, ProfileError, FileNotFoundError,
                        IsADirectoryError)):
        return EXIT_USAGE
    return EXIT_ERROR


def _inputs(args) -> str:
    """The command and its file arguments (case, profiles, outputs) for an unexpected error."""
    if args is None or getattr(args, "command", None) is None:
        return ""
    parts = [args.command]
    for key in ("case", "wheel", "rail", "out", "json", "plot", "csv"):
        v = getattr(args, key, None)
        if isinstance(v, (str, bytes)) or hasattr(v, "__fspath__"):
            parts.append(f"{key}={str(v)!r}" if key != "case" else repr(str(v)))
    return " ".join(parts)


def _message(exc: BaseException, args=None) -> str:
    from ..errors import WheelrailError, tidy

    text = tidy(" ".join(str(exc).split())) or type(exc).__name__
    if isinstance(exc, (WheelrailError, _UsageError)):
        return text
    if isinstance(exc, OSError) and exc.filename is not None:
        return f"{exc.strerror or text}: {exc.filename}"
    where = _inputs(args)
    where = f"internal error in 'wheelrail {where}': " if where else ""
    return f"{where}{type(exc).__name__}: {text} (run with --debug for the traceback)"


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """One line per warning on stderr, without the source line Python would print."""
    from ..errors import tidy

    text = tidy(" ".join(str(message).split()))
    print(f"wheelrail: warning: {text} ({category.__name__})", file=file or sys.stderr)


#: Modules with numba kernels (``cache=True``) that nearly every command uses (FASTSIM, the
#: contact search); without their cache files the first run compiles (about 10–20 s).
KERNEL_MODULES = ("tangential/_fastsim_kernel", "geometry/_search_kernels")
#: Commands that may compile kernels (not --help, not build-table's workers alone).
_KERNEL_COMMANDS = ("solve", "creep-curve", "demo", "geometry", "wheelset", "sweep", "compare",
                    "transient", "validate")


def uncompiled_kernels() -> list[str]:
    """Kernel modules without a numba cache file yet (their first use compiles them)."""
    import os
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    extra = os.environ.get("NUMBA_CACHE_DIR")
    missing = []
    for mod in KERNEL_MODULES:
        path = root / f"{mod}.py"
        stem = path.stem
        places = [path.parent / "__pycache__"]
        if extra:
            places.append(Path(extra))
        if not any(any(d.rglob(f"{stem}.*.nbi")) for d in places if d.is_dir()):
            missing.append(mod)
    return missing


def _compile_note(console, command) -> None:
    """One line before the first use of the kernels (numba compiles them, about 10–20 s)."""
    if command not in _KERNEL_COMMANDS or not getattr(console, "is_terminal", False):
        return
    try:
        missing = uncompiled_kernels()
    except OSError:  # pragma: no cover - unreadable install directory
        return
    if missing:
        console.print("note: compiling numerical kernels on first use (about 10–20 s, once; "
                      "cached afterwards)", markup=False, highlight=False)


def make_console():
    """The rich console of the commands: no highlighting; no wrapping when piped.

    On a terminal rich wraps at the terminal width; in a pipe or file it
    would wrap at 80 columns and split long lines (suggested commands, file
    names), so there the output is not wrapped.
    """
    from rich.console import Console

    if sys.stdout.isatty():
        return Console(highlight=False)
    return Console(highlight=False, soft_wrap=True, width=200)


def main(argv=None) -> int:
    """Run ``wheelrail`` with ``argv`` (default ``sys.argv[1:]``) and return the exit code."""
    import warnings

    argv = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in argv
    saved = warnings.showwarning
    if not debug:
        warnings.showwarning = _show_warning
    try:
        return _main(argv, debug)
    finally:
        warnings.showwarning = saved


def _main(argv, debug) -> int:
    args = None
    try:
        parser = build_parser(argv)
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:  # --help, --version
            return int(exc.code or 0)
        if args.command is None:
            parser.print_help()
            return EXIT_USAGE
        import contextlib

        from .. import _resources

        console = make_console()
        with contextlib.ExitStack() as stack:
            if args.memory_limit is not None:
                stack.enter_context(_resources.limit(_resources.parse_size(args.memory_limit)))
            if args.time_limit is not None:
                stack.enter_context(_resources.time_limit_set(
                    _resources.parse_duration(args.time_limit)))
            if getattr(args, "estimate_only", False) and args.command != "fe":
                stack.enter_context(_resources.estimating())
            if getattr(args, "no_plausibility_checks", False):
                from ..plausibility import disabled

                stack.enter_context(disabled())
            stack.enter_context(_resources.reporting(console))
            _compile_note(console, args.command)
            try:
                code = int(args._run(args, console) or 0)
            except _resources.EstimateOnly as est:
                console.print(f"estimate: {est}", markup=False, highlight=False)
                return EXIT_OK
            if getattr(args, "estimate_only", False) and args.command != "fe":
                console.print("estimate: no long computation (below the guards' thresholds)",
                              markup=False, highlight=False)
            return code
    except KeyboardInterrupt:
        print("wheelrail: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # noqa: BLE001 - the CLI boundary
        if debug:
            raise
        print(f"wheelrail: error: {_message(exc, args)}", file=sys.stderr)
        return _exit_code(exc)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
