"""The exceptions flexwing raises: one base class, and the data of each error as attributes.

The tree::

    FlexwingError                     every error of the package
    ├── InputError (ValueError)       a value the model cannot use: .field, .reason
    │   └── CaseFileError             a case (file, TOML text or dict) that cannot be read:
    │                                 .file, .line, .column, .key (= .field), .reason
    ├── ArgumentTypeError (TypeError) an argument of the wrong type or dtype, an unknown
    │                                 keyword: .field (the argument), .reason
    ├── SolverError (RuntimeError)    a solver that stopped: .stop (where and why, a dict),
    │                                 .result (the partial result, or None), .model
    ├── ReentrancyError (RuntimeError) a call from inside another call that cannot be served:
    │                                 .field (the object or argument), .reason
    └── InternalError (RuntimeError)  a bug of flexwing (a Rust panic caught at the boundary)

Every exception pickles with its attributes, so that it travels back from a worker process
(Dask, multiprocessing) intact.

Not renamed: an exception raised by the caller's own code inside a call propagates as itself —
a ``KeyboardInterrupt`` (Ctrl-C, which stops a long call at its next check and carries the
partial result as its ``result`` attribute), a ``MemoryError`` or any other exception raised in
a ``__float__``, ``__index__`` or ``__array__`` method of an argument or in a progress callback
(which stops the call in the same way, with ``result``). Only a ``TypeError``, ``ValueError``
or ``OverflowError`` raised while an argument is converted becomes the ``ArgumentTypeError`` or
``InputError`` naming that argument.
"""

from __future__ import annotations

from typing import Any, Optional

__all__ = [
    "FlexwingError",
    "InputError",
    "CaseFileError",
    "ArgumentTypeError",
    "SolverError",
    "ReentrancyError",
    "InternalError",
]


class FlexwingError(Exception):
    """Base class of every error raised by flexwing."""

    def __init__(self, message: str = "", **attributes: Any) -> None:
        super().__init__(message)
        for name, value in attributes.items():
            setattr(self, name, value)

    @property
    def message(self) -> str:
        """The one-line message."""
        return str(self.args[0]) if self.args else ""


class InputError(FlexwingError, ValueError):
    """A value the model cannot use (also a ``ValueError``).

    Attributes:
        field: the name of the offending value, as the caller gave it: an argument
            (``"y"``, ``"EI[3]"``) or a case-file key (``"beam.section.EI"``, ``"loads[2].fy"``).
        reason: what is wrong with it.
    """

    field: Optional[str] = None
    reason: str = ""


class CaseFileError(InputError):
    """A case that cannot be read, parsed or turned into an analysis.

    Attributes (each ``None`` when not known):
        file: the case file, as given.
        line, column: 1-based position of the offending text (TOML syntax and schema errors).
        key: the dotted key, e.g. ``"loads[2].time.t"`` (also ``field``).
        reason: what is wrong.
    """

    file: Optional[str] = None
    line: Optional[int] = None
    column: Optional[int] = None
    key: Optional[str] = None


class ArgumentTypeError(FlexwingError, TypeError):
    """An argument of the wrong type or dtype, or an unknown keyword (also a ``TypeError``).

    Attributes:
        field: the argument.
        reason: what is wrong with it.
    """

    field: Optional[str] = None
    reason: str = ""


class SolverError(FlexwingError, RuntimeError):
    """A solver stopped before the end (also a ``RuntimeError``).

    Attributes:
        model: the label of the model whose run stopped first (``"full"``, ``"reduced-r2"``),
            or ``None`` for a failure before any model ran (the modal analysis the reduced
            models need).
        stop: where and why it stopped, as data: a dict with ``"reason"`` and the values it
            stopped at (``"time"`` in s, ``"load_factor"``, ``"scale"``, ``"point"``, …) and
            ``"message"``; ``None`` if unknown.
        result: the partial result, with every model's output up to where it stopped (the
            result object the analysis would have returned), or ``None``.
    """

    model: Optional[str] = None
    stop: Optional[dict] = None
    result: Any = None


class ReentrancyError(FlexwingError, RuntimeError):
    """A call made from inside another flexwing call that cannot be served (also a
    ``RuntimeError``): a method of a ``Stepper`` called from a signal handler or callback run
    during that stepper's own ``step()`` on the same thread (it would wait for itself), or an
    analysis started from a progress callback nested more than 16 deep.

    Attributes:
        field: the object or argument (``"Stepper"``, ``"progress"``).
        reason: what happened.
    """

    field: Optional[str] = None
    reason: str = ""


class InternalError(FlexwingError, RuntimeError):
    """A bug of flexwing: a Rust panic caught at the boundary (please report it with the input
    that caused it). The interpreter is not affected."""
