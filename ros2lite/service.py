"""Service servers, on rmw_zenoh's wire: a complete queryable on the service key, one reply per
request carrying the request's sequence number and client GID (rmw_zenoh.md §5).

Requests arrive on Zenoh threads and wait in the service's queue; the executor runs the callback.
"""

from __future__ import annotations

import logging
import time
from collections import deque
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Generic, cast

from ros2lite.qos import QoSProfile
from ros2lite.runtime.endpoint import Endpoint
from ros2lite.runtime.executable import Executable
from ros2lite.service_introspection import IntrospectionMixin, ServiceEventType, ServiceNode
from ros2lite.transport.attachment import pack_attachment, unpack_attachment
from ros2lite.transport.keys import EntityKind
from ros2lite.type_support import SrvRequestT, SrvResponseT

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.interfaces.cdr import Codec
    from ros2lite.task import Task
    from ros2lite.transport.handles import Handle
    from ros2lite.transport.session import Request
    from ros2lite.type_support import Srv

__all__ = ['RequestHeader', 'Service']

_log = logging.getLogger('ros2lite.service')


@dataclass
class RequestHeader:
    """Who asked (client GID) and which of its requests this is (sequence number)."""

    sequence_number: int
    client_gid: bytes
    source_timestamp: int
    _request: Request | None = field(default=None, repr=False, compare=False)

    def take_request(self) -> Request | None:
        """The query to answer, handed out once (None once answered or abandoned)."""
        request, self._request = self._request, None
        return request


ServiceCallback = (
    Callable[[SrvRequestT, SrvResponseT], SrvResponseT | Awaitable[SrvResponseT]]
    | Callable[[SrvRequestT, RequestHeader], object]
)
"""`callback(request, response)` returning the response (or a coroutine giving it); with
`deferred=True`, `callback(request, header)` that answers later with `send_response`."""


class Service(IntrospectionMixin, Executable, Generic[SrvRequestT, SrvResponseT]):
    """Serves `srv_name`; `callback(request, response)` returns the response to send.

    With `deferred=True` the callback is `callback(request, header)` and the owner answers
    later with `send_response(response, header)` (the action server's get_result does)."""

    _node: ServiceNode  # a server always belongs to a node

    def __init__(
        self,
        node: ServiceNode,
        srv_type: type[Srv[SrvRequestT, SrvResponseT]] | str,
        srv_name: str,
        callback: ServiceCallback[SrvRequestT, SrvResponseT],
        qos: QoSProfile | int,
        *,
        callback_group: CallbackGroup | None = None,
        deferred: bool = False,
    ) -> None:
        from ros2lite.interfaces.classes import as_service_class
        from ros2lite.transport.session import declare_queryable

        super().__init__(node, callback_group)
        self._ep = _ServiceEndpoint(node, srv_type, srv_name, qos)
        self.srv_type: type[Srv[SrvRequestT, SrvResponseT]] = self._ep.msg_class
        self._response_class = as_service_class(self._ep.msg_class).Response
        self.srv_name = self._ep.topic_name
        self.qos_profile = self._ep.qos
        self.callback = callback
        self._deferred = deferred
        self._requests: deque[Request] = deque()
        self._destroyed = False
        self._codec_pair: tuple[Codec, Codec] | None = None
        self._queryable: Handle | None = declare_queryable(
            node.context.require(), self._ep.key, self._on_request
        )
        self._ep.announce()
        node.context.local_services[self._ep.key] = self

    @property
    def service_name(self) -> str:
        """The fully resolved service name."""
        return self.srv_name

    def _on_request(self, request: Request) -> None:
        """Zenoh thread: queue the request for the executor."""
        if self._destroyed:
            request.drop()
            return
        self._requests.append(request)
        self._notify()

    def has_work(self) -> bool:
        return bool(self._requests)

    def _codecs(self) -> tuple[Codec, Codec]:
        """(request codec, response codec), looked up on first use."""
        if self._codec_pair is None:
            from ros2lite.interfaces.cdr import service_codecs

            self._codec_pair = service_codecs(self._ep.type_name)
        return self._codec_pair

    def _take(self) -> tuple[SrvRequestT, RequestHeader] | None:
        """The next well-formed request as (message, header); malformed ones are dropped
        as rmw_zenoh drops them (no attachment, negative sequence number, bad CDR)."""
        while self._requests:
            request = self._requests.popleft()
            fields = unpack_attachment(request.attachment) if request.attachment else None
            if fields is None or fields[0] < 0 or fields[1] < 0:
                _log.debug('%s: request without a valid attachment dropped', self.srv_name)
                request.drop()
                continue
            try:
                message = self._codecs()[0].deserialize(request.payload)
            except Exception as e:
                _log.warning('%s: undecodable request dropped: %s', self.srv_name, e)
                request.drop()
                continue
            header = RequestHeader(fields[0], fields[2], fields[1], request)
            return cast('SrvRequestT', message), header
        return None

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        taken = self._take()
        if taken is None:
            return None
        message, header = taken
        self._introspect(
            ServiceEventType.REQUEST_RECEIVED, header.sequence_number, header.client_gid, message
        )
        try:
            if self._deferred:
                return self._call(self.callback, message, header)
            return self._call(
                self.callback,
                message,
                self._response_class(),
                then=lambda response: self.send_response(response, header),
            )
        except BaseException:
            self._abandon(header)
            raise

    def _abandon(self, header: RequestHeader) -> None:
        """The callback failed: end the query so the client is not left waiting."""
        request = header.take_request()
        if request is not None:
            request.drop()

    def send_response(self, response: SrvResponseT, header: RequestHeader) -> None:
        """Answer the request `header` came with (once)."""
        request = header.take_request()
        if request is None:
            raise RuntimeError('this request has already been answered')
        if getattr(response, '_TYPE_NAME', None) != f'{self._ep.type_name}_Response':
            request.drop()
            raise TypeError(
                f"service '{self.srv_name}' callback must return a "
                f'{self._ep.type_name}_Response, got {type(response).__name__}'
            )
        try:
            data = self._codecs()[1].serialize(response)
        except BaseException:
            request.drop()
            raise
        request.reply(
            data, pack_attachment(header.sequence_number, time.time_ns(), header.client_gid)
        )
        self._introspect(
            ServiceEventType.RESPONSE_SENT, header.sequence_number, header.client_gid, response
        )

    def destroy(self) -> None:
        """Stop serving: queued requests end unanswered; the queryable and token go."""
        self._destroyed = True
        self._destroy_introspection()
        self._node.context.local_services.pop(self._ep.key, None)
        while self._requests:
            self._requests.popleft().drop()
        self._ep.undeclare(self._queryable)
        self._queryable = None


class _ServiceEndpoint(Endpoint):
    kind = EntityKind.SERVICE
