"""The command line, ``mcrun COMMAND``: the one parser, the one entry point and the one place
where a command's error becomes the line the user reads.

Each family of commands lives in its own module, which adds its subcommands to the parser
(``register``) and holds their command functions:

- ``mcrun.cli.shot``: ``shot``, ``bounce``, ``models``, ``turfs``
- ``mcrun.cli.run``: ``run`` (the local engine, or a Dask cluster), ``validate``, ``scenarios``
- ``mcrun.cli.replay``: ``replay``
- ``mcrun.cli.report``: ``plot``, ``report``
- ``mcrun.cli.paper``: ``paper``
- ``mcrun.cli.calibrate``: ``calibrate``
- ``mcrun.cli.hole``: ``hole``
- ``mcrun.cli.putt``: ``putt``
- ``mcrun.cli.warmup``: ``warm-up``

A mistake the user can make (``InputError`` and its kinds: ``OutputError``, ``UnitError``,
``hole.errors.HoleError`` among them; ``CommandError``) ends with one line,
``mcrun: error: <message>``, on stderr and exit code 2; Ctrl-C with ``mcrun: interrupted`` and
exit code 130, SIGTERM with 143 and SIGHUP with 129 (``mcrun.exits``); anything else is a bug
and raises. A command function returns its exit code and raises these; it prints no error
itself.
"""

import argparse
import contextlib
import importlib
import os
import re
import sys
import warnings

from mcrun import exits
from mcrun.errors import InputError


class CommandError(ValueError):
    """A mistake on the command line that neither the API nor the unit reader catches (an
    unwritable output file, a missing optional package); one line meant for the user."""


# The errors a user's input can cause: each ends a command with one line and exit code 2.
USER_ERRORS = (InputError, CommandError)


class Interrupted(KeyboardInterrupt):
    """Ctrl-C or SIGTERM during a command's step that says what the interruption left:
    ``mcrun: interrupted: <message>``."""


def write_all_or_nothing(write=None, picture=None, force=False):
    """A command's table and picture, all or nothing: the picture (``picture``: (path, draw,
    dpi), ``draw()`` its Figure) drawn under a temporary name, then the table written
    (``write()``) and the picture renamed into place, interrupts deferred. Ctrl-C: Interrupted,
    saying whether everything was written."""
    from mcrun import exits

    written = False
    try:
        with contextlib.ExitStack() as stack:
            pictures = None
            if picture is not None:
                from mcrun.report import style

                path, draw, dpi = picture
                pictures = stack.enter_context(style.Pictures(force=force))
                pictures.add(path, draw(), dpi)
            with exits.interrupts_deferred():
                if write is not None:
                    write()
                if pictures is not None:
                    pictures.commit()
                written = True
    except KeyboardInterrupt:
        said = "after writing everything" if written else "nothing was written"
        raise Interrupted(said) from None


# --- the parser --------------------------------------------------------------------------------

# A value with a leading minus and a unit or a comma (``-3mph,2mph``, ``-2.5deg``) looks like an
# option to argparse; plain negative numbers (``-5``, ``-2.5``) it already reads as values.
_NEGATIVE_VALUE = re.compile(r"-\.?\d")
_NEGATIVE_NUMBER = re.compile(r"-\d+|-\d*\.\d+")


def _attach_negative_values(argv):
    """Rewrite ``--opt -3mph,2mph`` as ``--opt=-3mph,2mph`` so that argparse reads the value."""
    out = []
    for token in argv:
        previous = out[-1] if out else ""
        if (
            previous.startswith("--")
            and "=" not in previous
            and _NEGATIVE_VALUE.match(token)
            and not _NEGATIVE_NUMBER.fullmatch(token)
        ):
            out[-1] = f"{previous}={token}"
        else:
            out.append(token)
    return out


class _Parser(argparse.ArgumentParser):
    """argparse with its usage errors on one line, in the same form as every other error."""

    def error(self, message):
        self.exit(2, f"mcrun: error: {message} (see '{self.prog} --help')\n")


# The module of each command. Those of the commands other than the core ones bring pandas,
# pyarrow or matplotlib: imported only when the command line may need them, so that `mcrun shot`
# starts quickly.
COMMAND_MODULES = {
    "shot": "mcrun.cli.shot",
    "bounce": "mcrun.cli.shot",
    "models": "mcrun.cli.shot",
    "turfs": "mcrun.cli.shot",
    "run": "mcrun.cli.run",
    "validate": "mcrun.cli.run",
    "scenarios": "mcrun.cli.run",
    "replay": "mcrun.cli.replay",
    "calibrate": "mcrun.cli.calibrate",
    "paper": "mcrun.cli.paper",
    "plot": "mcrun.cli.report",
    "report": "mcrun.cli.report",
    "hole": "mcrun.cli.hole",
    "aim": "mcrun.cli.aim",
    "putt": "mcrun.cli.putt",
    "play": "mcrun.cli.play",
    "rate": "mcrun.cli.rate",
    "warm-up": "mcrun.cli.warmup",
}
CORE_COMMANDS = ("shot", "bounce", "models", "turfs")


def build_parser(command=None):
    """The ``mcrun`` argument parser: every subcommand, or only the core ones when ``command``
    (the first word of the command line) is one of them."""
    parser = _Parser(
        prog="mcrun",
        description="Golf shots: flight, compliant-turf bounce (Penner 2002) and roll.",
        allow_abbrev=False,
    )
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    commands = CORE_COMMANDS if command in CORE_COMMANDS else COMMAND_MODULES
    for module in dict.fromkeys(COMMAND_MODULES[c] for c in commands):
        importlib.import_module(module).register(subparsers)
    return parser


# --- compiling the kernels ---------------------------------------------------------------------


# The ground of the kernel each simulating command runs before it has read its input: the
# batch kernel on the plane, which a single shot runs too. A command whose ground depends on
# its scenario compiles the kernel of that ground alone once it has read it (``mcrun run``:
# the plane's or a hole's; ``mcrun aim``: a hole's), before its timed work.
SIMULATING_COMMANDS = {
    "shot": "plane",
    "calibrate": "plane",
    "paper": "plane",
    "replay": "plane",
}


def _kernel_cached(ground, kernels=("batch",)):
    """Whether the ``kernels`` for ``ground`` are compiled or in numba's on-disk cache (None
    when it cannot be told)."""
    from mcrun.engine.warmup import kernel_cached

    return kernel_cached(ground, kernels)


def kernels_of(args, general=None):
    """The kernels (``engine.warmup.KERNELS``) a command runs with ``args``: the batch, and the
    traced batch where it records a path (that alone for one shot's path), and the run from a
    landing for the paper's figures; their general kinds where its shots fly in the general
    lanes (``general``, or, when None, the aerodynamic model and wind profile its options
    name)."""
    if args.command == "paper":
        kernels = ("batch", "traced", "landed")
    elif args.command == "shot" and getattr(args, "trajectory", None):
        kernels = ("traced",)
    elif getattr(args, "trajectory", None) or getattr(args, "trajectories", None):
        kernels = ("batch", "traced")
    else:
        kernels = ("batch",)
    if general is None:
        aero, profile = getattr(args, "aero", None), getattr(args, "wind_profile", None)
        general = aero is not None and profile is not None and _general_flight(aero, profile)
    if general:
        from mcrun.engine.warmup import general as general_kinds

        kernels = general_kinds(kernels)
    return kernels


def _general_flight(aero, profile):
    """Whether shots of the model and profile named fly in the general lanes (False for a name
    that is not one: the command refuses it itself, in one line)."""
    from mcrun.engine.batch import general_flight

    try:
        return general_flight(aero, profile)
    except ValueError:
        return False


def compile_if_needed(ground, kernels=("batch",)):
    """When the ``kernels`` for ``ground`` ("plane" or "terrain") are not in Numba's on-disk
    cache yet (the first run after an install or an upgrade compiles them, which takes a while),
    compile them now, saying so on stderr with the time it took: a command's time and rate that
    follow are then its own. Returns the seconds the compile took (0.0 when none was needed).
    ``ground`` "green": the green's kernels (``putting.warmup.KERNELS``)."""

    def say(line):
        print(line, file=sys.stderr, flush=True)

    if ground == "green":
        from mcrun.putting.warmup import compile_announced

        return compile_announced(kernels, say)
    if _kernel_cached(ground, kernels) is not False:
        return 0.0
    from mcrun.engine import warmup

    what, when = warmup.KERNEL_NAMES[ground]
    return warmup.announced(what, when, lambda: warmup.warm_up((ground,), kernels), say)


# --- running a command -------------------------------------------------------------------------


def main(argv=None):
    """Run ``mcrun`` with ``argv`` (default: the process's arguments); return the exit code."""
    argv = sys.argv[1:] if argv is None else list(argv)
    problem = exits.environment_problem()  # (before a command's module imports Numba)
    if problem:
        return _error(problem)
    try:  # (a command's modules take seconds to import: Ctrl-C then was a traceback)
        parser = build_parser(argv[0] if argv else None)
        args = parser.parse_args(_attach_negative_values(argv))
    except SystemExit as exit_:  # --help, or a usage error argparse has already reported
        return exit_.code if isinstance(exit_.code, int) else int(exit_.code is not None)
    except KeyboardInterrupt:
        print("mcrun: interrupted", file=sys.stderr)
        return exits.EXIT_INTERRUPTED
    except RuntimeError as err:  # (Numba looks for its cache as a module of kernels imports)
        if not exits.is_cache_unwritable(err):
            raise
        return _error(exits.CACHE_UNWRITABLE)
    blank = _blank_argument(parser, args)
    if blank is not None:
        return _error(f"{blank}: empty: give a value (see 'mcrun {args.command} --help')")
    # SIGTERM and SIGHUP stop a command as Ctrl-C does (the commands clean up on
    # KeyboardInterrupt).
    with exits.sigterm_interrupts() as terminated, _warnings_as_lines():
        code = _run_command(args)
    if terminated and code == exits.EXIT_INTERRUPTED:
        return exits.exit_code(terminated[0])
    return code


@contextlib.contextmanager
def _warnings_as_lines():
    """Python's warnings while a command runs (a library's: matplotlib's, Dask's) each as one
    line, ``mcrun: warning: <message>``, without the file, line and source Python shows; the
    same message once."""
    shown, said = warnings.showwarning, set()

    def show(message, category, filename, lineno, file=None, line=None):
        text = " ".join(str(message).split())
        if text not in said:
            said.add(text)
            print(f"mcrun: warning: {text}", file=file or sys.stderr)

    warnings.showwarning = show
    try:
        yield
    finally:
        warnings.showwarning = shown


def _blank_argument(parser, args):
    """The name of an argument given as empty text (or blanks), or None: no option takes one,
    and some read it as the current folder (``-o ''`` wrote there) or as not given
    (``--plot ''`` drew nothing, ``--dir ''`` listed the library)."""
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    command = commands.choices.get(getattr(args, "command", None))
    for action in [] if command is None else command._actions:
        value = getattr(args, action.dest, None)
        if isinstance(value, str) and not value.strip() and value != action.default:
            return action.option_strings[0] if action.option_strings else (
                action.metavar or action.dest.upper())  # fmt: skip
    return None


def _run_command(args):
    """``args.func(args)``, with every error a user can cause as one line and exit code 2."""
    try:
        if args.command in SIMULATING_COMMANDS:
            compile_if_needed(SIMULATING_COMMANDS[args.command], kernels_of(args))
        return args.func(args)
    except USER_ERRORS as err:
        return _error(" ".join(str(err).split()))
    except BrokenPipeError:  # e.g. `mcrun shot ... | head -3`: the reader has gone, not a bug
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return 1
    except OSError as err:
        if exits.is_name_too_long(err):
            return _error(exits.name_too_long(err))
        refused = exits.system_refusal(err)  # (a full disk was a traceback; the run cleaned up)
        if refused is None:
            raise
        return _error(refused)
    except RuntimeError as err:
        if not exits.is_cache_unwritable(err):
            raise
        return _error(exits.CACHE_UNWRITABLE)
    except Interrupted as err:
        _say(f"mcrun: interrupted: {err}")
        return exits.EXIT_INTERRUPTED
    except exits.Terminated as err:
        _say(f"mcrun: terminated ({err.signum.name})")
        return exits.exit_code(err.signum)
    except KeyboardInterrupt:
        _say("mcrun: interrupted")
        return exits.EXIT_INTERRUPTED


def _say(line):
    """``line`` on stderr, if it can still be written (after SIGHUP the terminal is gone)."""
    with contextlib.suppress(OSError):
        print(line, file=sys.stderr)


def _error(line):
    """Print ``mcrun: error: <line>`` on stderr; return the exit code 2."""
    print(f"mcrun: error: {line}", file=sys.stderr)
    return 2
