"""The live server started from Python: ``Model.live`` gives a :class:`LiveServer`, the server the
``elastokin live`` command starts, serving the model's file on this machine until stopped."""

from __future__ import annotations

import html
from types import TracebackType
from typing import Optional, Tuple, Type

from . import _native

NOTEBOOK_ORIGINS: Tuple[str, ...] = ("http://localhost:*", "http://127.0.0.1:*")
"""The origins whose pages may show the live page in a frame by default: a notebook served on this
machine (Jupyter's ``http://localhost:8888``, at any port). Each is a Content-Security-Policy source:
``http`` or ``https``, a host, and a port or ``*``."""


class LiveServer:
    """A model file served live, as ``elastokin live`` serves it, on a thread of its own: open :attr:`url`
    in a browser (a notebook shows the page in a frame when the server is the cell's value), move a
    hardpoint or a rate there and every figure and chart answers; undo, redo and save from the page.

    Every request must carry the token in :attr:`url`, come for the server's own address and, when a
    browser sends an Origin, from the page itself: no other page or host can drive the server.
    :meth:`stop` (or leaving a ``with`` block, or the object being collected) stops it; its port is free
    when that returns.
    """

    __slots__ = ("_native", "_name")

    def __init__(self, native: "_native.LiveServer", name: str) -> None:
        self._native = native
        self._name = name

    @property
    def url(self) -> str:
        """The page's address, token included: ``http://127.0.0.1:PORT/TOKEN/``."""
        return self._native.address

    @property
    def port(self) -> int:
        """The port listened on."""
        return self._native.port

    @property
    def serving(self) -> bool:
        """Whether the server is serving (not yet stopped)."""
        return self._native.serving

    def stop(self) -> bool:
        """Stops the server: the request being served is finished, its thread ends and its port is free when
        this returns. Gives whether the edits since the last save were left unsaved (False when it was
        stopped already)."""
        return self._native.stop()

    def __enter__(self) -> "LiveServer":
        return self

    def __exit__(
        self,
        kind: Optional[Type[BaseException]],
        error: Optional[BaseException],
        traceback: Optional[TracebackType],
    ) -> None:
        self.stop()

    def _repr_html_(self) -> str:
        """The page in a frame, for a notebook (Jupyter shows a cell's value by it)."""
        if not self.serving:
            return f"<p>elastokin live: {html.escape(self._name)} is stopped.</p>"
        url = html.escape(self.url, quote=True)
        return (
            f'<iframe src="{url}" title="elastokin live: {html.escape(self._name, quote=True)}" '
            'width="100%" height="900" style="border: 1px solid #ddd"></iframe>'
        )

    def __repr__(self) -> str:
        state = self.url if self.serving else "stopped"
        return f"<elastokin.LiveServer {self._name!r}: {state}>"
