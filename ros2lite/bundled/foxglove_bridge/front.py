"""The bridge's front door: both names of the protocol on one port.

`foxglove-sdk` accepts only the subprotocol `foxglove.sdk.v1`; PlotJuggler, older Lichtblick
and `@foxglove/ws-protocol`'s default client offer `foxglove.websocket.v1`, the same protocol
under its older name, and get HTTP 400. The front listens where the bridge was told, reads
each connection's HTTP upgrade request (bounded in size and time), and when only the old name
is offered writes the new one into the request's `Sec-WebSocket-Protocol` and the old one
back into the answer's; everything else, and every byte after the handshake, passes
unchanged to the SDK's server on a loopback port of its own. One thread serves every
connection (a selector); a client that stops reading fills only its own bounded buffer, and
the SDK's own per-client queue then drops its oldest messages, as without the front.
"""

from __future__ import annotations

import contextlib
import errno
import selectors
import socket
import threading
import time
from collections.abc import Callable

__all__ = ['NEW_NAME', 'OLD_NAME', 'SubprotocolFront', 'offered', 'rewrite_request']

NEW_NAME = 'foxglove.sdk.v1'
OLD_NAME = 'foxglove.websocket.v1'
_HEAD_LIMIT = 16 * 1024  # an upgrade request or answer longer than this is refused
_HANDSHAKE_SECONDS = 10.0  # a connection that has not finished its handshake by then ends
_BUFFER_LIMIT = 1024 * 1024  # bytes queued towards one side before we stop reading the other
_CHUNK = 256 * 1024
_HEADER = b'sec-websocket-protocol'
_BAD_REQUEST = b'HTTP/1.1 400 Bad Request\r\nConnection: close\r\nContent-Length: 0\r\n\r\n'


def offered(head: bytes) -> list[str]:
    """The subprotocols an upgrade request's head offers, in order."""
    names: list[str] = []
    for line in head.split(b'\r\n')[1:]:
        key, colon, value = line.partition(b':')
        if colon and key.strip().lower() == _HEADER:
            names += [v.strip() for v in value.decode('latin-1').split(',') if v.strip()]
    return names


def rewrite_request(head: bytes) -> tuple[bytes, bool]:
    """The request head as the SDK will take it, and whether the answer must be rewritten
    (only the old name offered)."""
    names = offered(head)
    if NEW_NAME in names or OLD_NAME not in names:
        return head, False
    lines = [
        line
        for line in head.split(b'\r\n')
        if line.partition(b':')[0].strip().lower() != _HEADER or not line.partition(b':')[1]
    ]
    # the head ends with an empty line: the new header goes before it
    ends_empty = len(lines) >= 2 and lines[-1] == b'' and lines[-2] == b''
    end = len(lines) - 2 if ends_empty else len(lines)
    lines.insert(end, b'Sec-WebSocket-Protocol: ' + NEW_NAME.encode())
    return b'\r\n'.join(lines), True


def rewrite_answer(head: bytes) -> bytes:
    """The SDK's 101 answer naming the old name, as the client offered it."""
    out = []
    for line in head.split(b'\r\n'):
        key, colon, value = line.partition(b':')
        if colon and key.strip().lower() == _HEADER and value.strip() == NEW_NAME.encode():
            line = key + b': ' + OLD_NAME.encode()
        out.append(line)
    return b'\r\n'.join(out)


class _Side:
    """One socket of a connection and the bytes waiting to be written to it."""

    def __init__(self, sock: socket.socket) -> None:
        self.sock = sock
        self.out = bytearray()
        self.eof = False  # it will send no more
        self.shut = False  # we will write no more


class _Connection:
    def __init__(self, client: socket.socket) -> None:
        self.client = _Side(client)
        self.backend: _Side | None = None
        self.head = bytearray()  # the request's head while it is being read
        self.answer: bytearray | None = None  # the SDK's answer head, when it is rewritten
        self.deadline = time.monotonic() + _HANDSHAKE_SECONDS
        self.closed = False

    def sides(self) -> list[_Side]:
        return [self.client] if self.backend is None else [self.client, self.backend]


class SubprotocolFront:
    """Accepts on (`host`, `port`) and passes each connection to the SDK at `backend_port`
    on loopback, the subprotocol name rewritten where only the old one was offered."""

    def __init__(
        self,
        host: str,
        port: int,
        backend_port: int,
        *,
        warn: Callable[[str], object] = print,
        log: Callable[[str], object] | None = None,
    ) -> None:
        self._backend = ('127.0.0.1', backend_port)
        self._warn = warn
        self._log = log  # (must not block: the front's one thread serves every client)
        family, kind, proto, _, address = socket.getaddrinfo(
            host, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE
        )[0]
        self._listener = socket.socket(family, kind, proto)
        self._listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            self._listener.bind(address)
            self._listener.listen(128)
        except OSError as e:
            self._listener.close()
            raise RuntimeError(f'cannot listen on {host}:{port}: {e.strerror}') from None
        self._listener.setblocking(False)
        self._selector = selectors.DefaultSelector()
        self._selector.register(self._listener, selectors.EVENT_READ, None)
        self._wake_r, self._wake_w = socket.socketpair()
        self._wake_r.setblocking(False)
        self._selector.register(self._wake_r, selectors.EVENT_READ, None)
        self._connections: set[_Connection] = set()
        self._stopping = False
        self._thread = threading.Thread(target=self._run, name='foxglove-front', daemon=True)

    @property
    def address(self) -> tuple[str, int]:
        """Where the front listens (host, port)."""
        host, port = self._listener.getsockname()[:2]
        return str(host), int(port)

    @property
    def port(self) -> int:
        """The port the front listens on (the chosen one when asked for 0)."""
        return int(self._listener.getsockname()[1])

    def start(self) -> None:
        """Serve on a thread of its own."""
        self._thread.start()

    def close(self) -> None:
        """Stop accepting and end every connection."""
        self._stopping = True
        with contextlib.suppress(OSError):
            self._wake_w.send(b'x')
        if self._thread.is_alive():
            self._thread.join(5.0)
        for conn in list(self._connections):
            self._end(conn)
        for sock in (self._listener, self._wake_r, self._wake_w):
            sock.close()
        self._selector.close()

    # -- the loop ------------------------------------------------------------------------------
    def _run(self) -> None:
        swept = time.monotonic()
        while not self._stopping:
            for key, events in self._selector.select(timeout=1.0):
                if key.fileobj is self._listener:
                    self._accept()
                elif key.fileobj is self._wake_r:
                    with contextlib.suppress(OSError):
                        self._wake_r.recv(64)
                else:
                    conn, side = key.data
                    try:
                        self._serve(conn, side, events)
                    except OSError:
                        self._end(conn)
            now = time.monotonic()
            if now >= swept + 1.0:
                swept = now
                for conn in list(self._connections):
                    if conn.deadline and now > conn.deadline:
                        self._end(conn)  # a handshake that never finished (slowloris)

    def _accept(self) -> None:
        for _ in range(64):
            try:
                sock, _ = self._listener.accept()
            except BlockingIOError:
                return
            except OSError as e:  # out of descriptors: say so, keep serving the others
                if e.errno in (errno.EMFILE, errno.ENFILE):
                    self._warn(f'foxglove_bridge: cannot accept a connection: {e.strerror}')
                return
            sock.setblocking(False)
            sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            conn = _Connection(sock)
            self._connections.add(conn)
            self._selector.register(sock, selectors.EVENT_READ, (conn, conn.client))

    def _serve(self, conn: _Connection, side: _Side, events: int) -> None:
        if events & selectors.EVENT_WRITE:
            self._flush(conn, side)
        if events & selectors.EVENT_READ and not conn.closed:
            try:
                data = side.sock.recv(_CHUNK)
            except (BlockingIOError, InterruptedError):
                data = None
            if data == b'':
                side.eof = True
            elif data:
                if side is conn.client:
                    self._from_client(conn, data)
                else:
                    self._from_backend(conn, data)
        if not conn.closed:
            self._update(conn)

    def _from_client(self, conn: _Connection, data: bytes) -> None:
        if conn.backend is not None:
            conn.backend.out += data
            return
        conn.head += data
        end = conn.head.find(b'\r\n\r\n')
        if end < 0:
            if len(conn.head) > _HEAD_LIMIT:
                conn.client.out += _BAD_REQUEST
                conn.client.eof = True
            return
        head, rest = bytes(conn.head[: end + 4]), bytes(conn.head[end + 4 :])
        conn.head = bytearray()
        head, rewrite = rewrite_request(head)
        backend = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        backend.setblocking(False)
        backend.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        result = backend.connect_ex(self._backend)
        if result not in (0, errno.EINPROGRESS):
            backend.close()
            raise OSError(result, 'the bridge server does not answer')
        conn.backend = _Side(backend)
        conn.backend.out += head + rest
        if self._log is not None:
            # the SDK sees every client as the front: say which address stands for whom
            peer = _address(conn.client.sock.getpeername())
            local = _address(backend.getsockname())
            self._log(f'Client {peer} connected (the server sees it as {local})')
        conn.answer = bytearray() if rewrite else None
        if not rewrite:
            conn.deadline = 0.0
        self._selector.register(backend, selectors.EVENT_WRITE, (conn, conn.backend))

    def _from_backend(self, conn: _Connection, data: bytes) -> None:
        if conn.answer is None:
            conn.client.out += data
            return
        conn.answer += data
        end = conn.answer.find(b'\r\n\r\n')
        if end < 0 and len(conn.answer) <= _HEAD_LIMIT:
            return
        if end >= 0:
            data = rewrite_answer(bytes(conn.answer[: end + 4])) + bytes(conn.answer[end + 4 :])
        else:
            data = bytes(conn.answer)
        conn.answer = None
        conn.deadline = 0.0
        conn.client.out += data

    def _flush(self, conn: _Connection, side: _Side) -> None:
        if side.out:
            sent = side.sock.send(side.out)
            del side.out[:sent]

    def _update(self, conn: _Connection) -> None:
        """Interest in each socket: write while bytes wait for it, read while the other side's
        buffer has room; half-closes passed on once drained; the end when both are done."""
        for side in conn.sides():
            other = conn.backend if side is conn.client else conn.client
            if side.eof and other is not None and not other.out and not other.shut:
                other.shut = True
                with contextlib.suppress(OSError):
                    other.sock.shutdown(socket.SHUT_WR)
        if conn.client.eof and conn.backend is None and not conn.client.out:
            self._end(conn)
            return
        if all(s.eof and s.shut for s in conn.sides()) and conn.backend is not None:
            self._end(conn)
            return
        for side in conn.sides():
            other = conn.backend if side is conn.client else conn.client
            mask = 0
            room = other is None or len(other.out) < _BUFFER_LIMIT
            if not side.eof and room:
                mask |= selectors.EVENT_READ
            if side.out:
                mask |= selectors.EVENT_WRITE
            key = self._selector.get_map().get(side.sock)
            if mask == 0:
                if key is not None:
                    self._selector.unregister(side.sock)
            elif key is None:
                self._selector.register(side.sock, mask, (conn, side))
            elif key.events != mask:
                self._selector.modify(side.sock, mask, (conn, side))

    def _end(self, conn: _Connection) -> None:
        if conn.closed:
            return
        conn.closed = True
        self._connections.discard(conn)
        for side in conn.sides():
            with contextlib.suppress(KeyError, ValueError):
                self._selector.unregister(side.sock)
            side.sock.close()


def _address(name: tuple[object, ...] | str) -> str:
    if isinstance(name, tuple) and len(name) >= 2:
        host = str(name[0])
        return f'[{host}]:{name[1]}' if ':' in host else f'{host}:{name[1]}'
    return str(name)
