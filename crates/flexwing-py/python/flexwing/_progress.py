"""A tqdm progress bar as the ``progress=`` callback of an analysis or a batch (the optional
``tqdm`` extra, ``pip install "flexwing[tqdm]"``)::

    with flexwing.tqdm_progress(desc="case (b)") as bar:
        case.dynamics(progress=bar)           # done: the fraction of the analysis; the model shown
    with flexwing.tqdm_progress() as bar:
        flexwing.solve_many(cases, progress=bar)   # done of total cases

The same object serves both signatures: ``(done: float, label: str)`` of an analysis and
``(done: int, total: int)`` of ``solve_many``. The bar closes when the work is done, when the
``with`` block ends, or on ``close()``.
"""

from __future__ import annotations

from typing import Any


def _tqdm():
    try:
        from tqdm.auto import tqdm
    except ImportError as e:
        raise ImportError(
            'tqdm_progress() needs tqdm, an optional dependency of flexwing: pip install "flexwing[tqdm]" '
            "(or pip install tqdm)"
        ) from e
    return tqdm


class tqdm_progress:
    """A progress callback drawing a tqdm bar; keyword arguments go to ``tqdm`` (``desc``,
    ``file``, ``leave``, …)."""

    def __init__(self, **tqdm_kwargs: Any) -> None:
        self._tqdm = _tqdm()
        self._kwargs = tqdm_kwargs
        self.bar = None

    def __call__(self, done, second) -> None:
        if isinstance(second, str):
            # An analysis: `done` the fraction of the whole, `second` the model running.
            if self.bar is None:
                self.bar = self._tqdm(total=100, unit="%", **self._kwargs)
            self.bar.n = round(100 * float(done), 1)
            self.bar.set_postfix_str(second, refresh=False)
            self.bar.refresh()
            if done >= 1.0:
                self.close()
        else:
            # A batch: `done` of `second` cases.
            if self.bar is None:
                self.bar = self._tqdm(total=int(second), unit="case", **self._kwargs)
            self.bar.n = int(done)
            self.bar.refresh()
            if done >= second:
                self.close()

    def close(self) -> None:
        """Close the bar (idempotent); a later call starts a new one."""
        if self.bar is not None:
            self.bar.close()
            self.bar = None

    def __enter__(self) -> "tqdm_progress":
        return self

    def __exit__(self, *exc) -> None:
        self.close()
