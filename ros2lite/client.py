"""Service clients, on rmw_zenoh's wire: one query per request through a querier (target
ALL_COMPLETE, no consolidation), with a per-client sequence number and the client's GID in the
attachment (rmw_zenoh.md §5).

`call_async` futures complete on the executor of the client's node, so done-callbacks and
awaiting coroutines run there. `call` does not need an executor at all: the reply wakes the
calling thread directly, which is why it also works inside a callback; it refuses only where
waiting could never end (the server is ours and cannot run until the caller returns).

A request that no server answers stays pending, as with rclpy on rmw_zenoh (a server may come
later; `remove_pending_request` gives up on it). Tools that would rather know at once create
the client with `fail_without_server=True`: such a request then ends in ServiceCallError.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING, Generic, NoReturn, cast, overload

from ros2lite.callback_groups import ReentrantCallbackGroup
from ros2lite.exceptions import Ros2liteError
from ros2lite.qos import QoSProfile
from ros2lite.runtime.endpoint import Endpoint
from ros2lite.runtime.executable import Executable, current_execution
from ros2lite.service_introspection import IntrospectionMixin, ServiceEventType, ServiceNode
from ros2lite.task import Future
from ros2lite.transport.attachment import pack_attachment
from ros2lite.transport.keys import EntityKind
from ros2lite.type_support import SrvRequestT, SrvResponseT

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.graph import Entity
    from ros2lite.interfaces.cdr import Codec
    from ros2lite.task import Task
    from ros2lite.transport.session import Querier
    from ros2lite.type_support import Srv

__all__ = ['Client', 'ServiceCallError']

# rmw_zenoh waits for a get_result reply without a time limit (PR #685); other queries time
# out after the session's queries_default_timeout (600 s)
_UNLIMITED = 10 * 365 * 24 * 3600.0


class ServiceCallError(Ros2liteError, RuntimeError):
    """A request ended without a response (no server answered, or the query failed)."""


class Client(IntrospectionMixin, Executable, Generic[SrvRequestT, SrvResponseT]):
    """Calls the service `srv_name` of type `srv_type`; `call()` gives its Response."""

    # completing a future runs no user callback here: it must not wait for the group, or a
    # coroutine holding that group while awaiting this very future would never resume
    needs_group = False
    _node: ServiceNode  # a client always belongs to a node

    def __init__(
        self,
        node: ServiceNode,
        srv_type: type[Srv[SrvRequestT, SrvResponseT]] | str,
        srv_name: str,
        qos: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        fail_without_server: bool = False,
    ) -> None:
        from ros2lite.transport.session import declare_querier

        super().__init__(node, callback_group)
        self.fail_without_server = fail_without_server
        self._ep = _ClientEndpoint(node, srv_type, srv_name, qos)
        self.srv_type: type[Srv[SrvRequestT, SrvResponseT]] = self._ep.msg_class
        self.srv_name = self._ep.topic_name
        self.qos_profile = self._ep.qos
        self._gid = self._ep.gid
        self._lock = threading.Lock()
        self._seq = 0
        self._pending: dict[int, Future[SrvResponseT]] = {}
        # (sequence number, response bytes or None, error text) from Zenoh threads
        self._responses: deque[tuple[int, bytes | None, str]] = deque()
        self._codec_pair: tuple[Codec, Codec] | None = None
        timeout = _UNLIMITED if '/_action/get_result' in self.srv_name else None
        self._querier: Querier | None = declare_querier(
            node.context.require(), self._ep.key, timeout
        )
        self._ep.announce()

    @property
    def service_name(self) -> str:
        """The fully resolved service name."""
        return self.srv_name

    def _codecs(self) -> tuple[Codec, Codec]:
        """(request codec, response codec), looked up on first use."""
        if self._codec_pair is None:
            from ros2lite.interfaces.cdr import service_codecs

            self._codec_pair = service_codecs(self._ep.type_name)
        return self._codec_pair

    def _request_bytes(self, request: SrvRequestT) -> bytes:
        """The CDR bytes of `request` (TypeError for a request of another service type)."""
        if getattr(request, '_TYPE_NAME', None) != f'{self._ep.type_name}_Request':
            raise TypeError(
                f"client of '{self._ep.type_name}' got {type(request).__name__}; "
                f'expected {self._ep.type_name}_Request'
            )
        return self._codecs()[0].serialize(request)

    def _send(self, request: SrvRequestT, future: Future[SrvResponseT]) -> None:
        """Serialize and send, `future` registered under the request's sequence number;
        `_on_response(seq, data or None, error)` follows once, on a Zenoh thread."""
        on_response = self._on_response
        data = self._request_bytes(request)
        with self._lock:
            self._seq = seq = self._seq + 1
            self._pending[seq] = future
        answered = threading.Event()

        def reply(payload: bytes, attachment: bytes | None) -> None:
            if not answered.is_set():  # one response per request, as rmw_zenoh takes it
                answered.set()
                on_response(seq, payload, '')

        def end(error: str | None) -> None:
            # the query ended without a reply: no server (or it dropped the request)
            if not answered.is_set() and self.fail_without_server:
                answered.set()
                on_response(seq, None, error or f"no server of '{self.srv_name}' answered")

        try:
            querier = self._querier
            if querier is None:
                raise RuntimeError('client has been destroyed')
            querier.get(data, pack_attachment(seq, time.time_ns(), self._gid), reply, end)
        except BaseException:
            with self._lock:
                self._pending.pop(seq, None)
            raise
        self._introspect(ServiceEventType.REQUEST_SENT, seq, self._gid, request)

    # -- asynchronous: completed by the executor ---------------------------------------------------
    def call_async(self, request: SrvRequestT) -> Future[SrvResponseT]:
        """Send `request`; the future completes with the response on the node's executor."""
        future: Future[SrvResponseT] = Future()
        self._send(request, future)
        return future

    def _on_response(self, seq: int, data: bytes | None, error: str) -> None:
        self._responses.append((seq, data, error))
        self._notify()

    def has_work(self) -> bool:
        return bool(self._responses)

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        while self._responses:
            seq, data, error = self._responses.popleft()
            with self._lock:
                future = self._pending.pop(seq, None)
            if future is None or future.done():
                continue  # given up on (remove_pending_request) or cancelled
            if data is None:
                future.set_exception(ServiceCallError(error))
                continue
            try:
                response = self._codecs()[1].deserialize(data)
            except Exception as e:
                future.set_exception(ServiceCallError(f'undecodable response: {e}'))
                continue
            self._introspect(ServiceEventType.RESPONSE_RECEIVED, seq, self._gid, response)
            future.set_result(cast('SrvResponseT', response))
        return None

    def remove_pending_request(self, future: Future[SrvResponseT]) -> None:
        """Give up on a call_async future: a response that still comes is dropped."""
        with self._lock:
            for seq, pending in list(self._pending.items()):
                if pending is future:
                    del self._pending[seq]

    # -- synchronous: the reply wakes the caller ---------------------------------------------------
    @overload
    def call(self, request: SrvRequestT, timeout_sec: None = None) -> SrvResponseT:
        """Without a timeout: the response (or ServiceCallError)."""

    @overload
    def call(self, request: SrvRequestT, timeout_sec: float) -> SrvResponseT | None:
        """With a timeout: the response, or None when it passed first."""

    def call(self, request: SrvRequestT, timeout_sec: float | None = None) -> SrvResponseT | None:
        """Send and wait for the response; None when `timeout_sec` passes first (as rclpy).
        Unlike rclpy, no executor needs to spin the node meanwhile."""
        self._refuse_deadlock()
        data = self._request_bytes(request)
        querier = self._querier
        if querier is None:
            raise RuntimeError('client has been destroyed')
        with self._lock:
            self._seq = seq = self._seq + 1
        self._introspect(ServiceEventType.REQUEST_SENT, seq, self._gid, request)
        # the calling thread waits in the query's reply channel: the reply wakes it once,
        # straight from Zenoh (no callback thread, no event)
        start = time.monotonic()
        answer = querier.ask(data, pack_attachment(seq, time.time_ns(), self._gid), timeout_sec)
        if isinstance(answer, str):  # the query ended unanswered
            left = None if timeout_sec is None else timeout_sec - (time.monotonic() - start)
            if left is not None and left < 0.005:
                return None  # the time passed first
            if self.fail_without_server:  # no server, or it dropped the request
                raise ServiceCallError(answer or f"no server of '{self.srv_name}' answered")
            # the request stays pending, as with rclpy (a default client hears no answer)
            if left is None:
                _forever()
            time.sleep(left)
            return None
        response = self._codecs()[1].deserialize(answer[0])
        self._introspect(ServiceEventType.RESPONSE_RECEIVED, seq, self._gid, response)
        return cast('SrvResponseT', response)

    def _refuse_deadlock(self) -> None:
        """Inside a callback, a server of ours on the same executor may be unable to run
        until that callback returns: then waiting would never end, so say so instead."""
        executor, entity = current_execution()
        if executor is None:
            return
        server = self._node.context.local_services.get(self._ep.key)
        if server is None or not server.runs_on(executor):
            return
        # only a multi-threaded executor has threads to spare
        blocked = getattr(executor, 'num_threads', 1) < 2
        group = server.callback_group
        if not blocked and entity is not None and group is entity.callback_group:
            blocked = not isinstance(group, ReentrantCallbackGroup)
        if blocked:
            raise RuntimeError(
                f"Client.call('{self.srv_name}') inside a callback would deadlock: its "
                'server runs on the same executor and cannot run until this callback '
                'returns. Await client.call_async() in an async callback, or use a '
                'MultiThreadedExecutor with the callbacks in different callback groups '
                '(or a ReentrantCallbackGroup).'
            )

    # -- availability -----------------------------------------------------------------------------
    def _server_count(self, entities: list[Entity]) -> int:
        return sum(
            1
            for e in entities
            if e.kind == EntityKind.SERVICE
            and e.topic_name == self.srv_name
            and e.type_name == self._ep.type_name
            and e.type_hash == self._ep.type_hash
        )

    def service_is_ready(self) -> bool:
        """Whether a server of this name and type is on the graph now."""
        return self._server_count(self._node.context.graph.entities()) > 0

    def wait_for_service(self, timeout_sec: float | None = None) -> bool:
        """Wait until a server is in the graph; False if `timeout_sec` passed first."""
        context = self._node.context
        context.graph.wait_for(
            lambda entities: self._server_count(entities) > 0 or not context.ok(), timeout_sec
        )
        return context.ok() and self.service_is_ready()

    def destroy(self) -> None:
        """Cancel pending calls and withdraw the querier and its token."""
        self._destroy_introspection()
        with self._lock:
            pending, self._pending = self._pending, {}
        for future in pending.values():
            future.cancel()
        self._ep.undeclare(self._querier)
        self._querier = None


class _ClientEndpoint(Endpoint):
    kind = EntityKind.CLIENT


def _forever() -> NoReturn:
    """Wait for good (Ctrl-C still ends it): a call nobody will ever answer."""
    while True:
        threading.Event().wait()
