"""A component container that is *not* ros2lite: a bare zenoh session answering
composition_interfaces' three services as rclcpp_components' container does over
rmw_zenoh_cpp (ids from 1, rclcpp's error texts, a node announced per component).

Keys, tokens, type hashes, attachments and CDR are written out here from the rmw_zenoh
reference with no ros2lite code, so `ros2lite component` is checked against an independent
peer. It knows one component: `alien_pkg::Widget` (default node name `widget`).
"""

from __future__ import annotations

import struct
import threading
from dataclasses import dataclass, field
from typing import Any

from tests.action.alien import Cdr, reply_attachment

HASHES = {  # RIHS01 of the service types, from the Jazzy reference table
    'LoadNode': 'RIHS01_2e521ef6066fba6d7fc3a3b175d486709f01b4d738d9a59188858546fc8e5acd',
    'UnloadNode': 'RIHS01_dce562f83adc735ddcfe9dfb927b89293d4dd0fe2b8fc91e772fb83e970a43b0',
    'ListNodes': 'RIHS01_13f30d73a74c844ee4bacf78f3680f08777cad137f10fbd6a648544cc7b59d2a',
}
SERVICE_QOS = '::,10:,:,:,,'


class Reader:
    """Just enough of an XCDR1 little-endian reader (alignment counted from the body)."""

    def __init__(self, data: bytes) -> None:
        self.body = data[4:]
        self.pos = 0

    def get(self, fmt: str) -> Any:
        size = struct.calcsize('<' + fmt)
        self.pos += -self.pos % size
        (value,) = struct.unpack_from('<' + fmt, self.body, self.pos)
        self.pos += size
        return value

    def string(self) -> str:
        length = self.get('I')
        text = self.body[self.pos : self.pos + length - 1].decode()
        self.pos += length
        return text

    def strings(self) -> list[str]:
        return [self.string() for _ in range(self.get('I'))]

    def parameter(self) -> tuple[str, Any]:
        """rcl_interfaces/Parameter: name, then a ParameterValue (all fields, in order)."""
        name = self.string()
        kind = self.get('B')
        values: list[Any] = [self.get('?'), self.get('q'), self.get('d'), self.string()]
        values.append(bytes(self.get('B') for _ in range(self.get('I'))))
        values.append([self.get('?') for _ in range(self.get('I'))])
        values.append([self.get('q') for _ in range(self.get('I'))])
        values.append([self.get('d') for _ in range(self.get('I'))])
        values.append(self.strings())
        return name, (values[kind - 1] if 1 <= kind <= 9 else None)


def string(cdr: Cdr, text: str) -> Cdr:
    data = text.encode() + b'\x00'
    return cdr.put('I', len(data)).raw(data)


@dataclass
class LoadRequest:
    package: str
    plugin: str
    node_name: str
    node_namespace: str
    log_level: int
    remap_rules: list[str]
    parameters: list[tuple[str, Any]]
    extra_arguments: list[tuple[str, Any]]


@dataclass
class AlienContainer:
    session: Any
    domain_id: int
    name: str = 'alien_container'
    requests: list[LoadRequest] = field(default_factory=list)

    def __post_init__(self) -> None:
        d, zid = self.domain_id, str(self.session.info.zid())
        self.lv = f'@ros2_lv/{d}/{zid}'
        self.lock = threading.Lock()
        self.loaded: dict[int, tuple[str, Any]] = {}  # id -> (full name, node token)
        self.next_id = 1
        self.next_node = 1
        liveliness = self.session.liveliness()
        self.entities = [liveliness.declare_token(f'{self.lv}/0/0/NN/%/%/{self.name}')]
        for eid, (service, callback) in enumerate(
            (
                ('load_node', self._on_load),
                ('unload_node', self._on_unload),
                ('list_nodes', self._on_list),
            ),
            start=1,
        ):
            type_name = ''.join(part.title() for part in service.split('_'))
            dds = f'composition_interfaces::srv::dds_::{type_name}_'
            hsh = HASHES[type_name]
            self.entities.append(
                self.session.declare_queryable(
                    f'{d}/{self.name}/_container/{service}/{dds}/{hsh}', callback, complete=True
                )
            )
            self.entities.append(
                liveliness.declare_token(
                    f'{self.lv}/0/{eid}/SS/%/%/{self.name}/%{self.name}%_container%{service}/'
                    f'{dds}/{hsh}/{SERVICE_QOS}'
                )
            )

    def close(self) -> None:
        with self.lock:
            for _name, token in self.loaded.values():
                token.undeclare()
            self.loaded.clear()
        for entity in reversed(self.entities):
            entity.undeclare()

    def _reply(self, query: Any, cdr: Cdr) -> None:
        query.reply(
            query.key_expr, cdr.bytes(), attachment=reply_attachment(query.attachment.to_bytes())
        )

    def _on_load(self, query: Any) -> None:
        r = Reader(query.payload.to_bytes())
        request = LoadRequest(
            r.string(), r.string(), r.string(), r.string(), r.get('B'), [], [], []
        )
        request.remap_rules = r.strings()
        request.parameters = [r.parameter() for _ in range(r.get('I'))]
        request.extra_arguments = [r.parameter() for _ in range(r.get('I'))]
        self.requests.append(request)
        error = ''
        if request.package != 'alien_pkg':
            error = 'Could not find requested resource in ament index'
        elif request.plugin != 'alien_pkg::Widget':
            error = 'Failed to find class with the requested plugin name.'
        if error:
            self._reply(query, string(string(Cdr().put('?', False), error), '').put('Q', 0))
            return
        ns = request.node_namespace.rstrip('/')
        node = request.node_name or 'widget'
        with self.lock:
            uid, self.next_id = self.next_id, self.next_id + 1
            nid, self.next_node = self.next_node, self.next_node + 1
            token = self.session.liveliness().declare_token(
                f'{self.lv}/{nid}/0/NN/%/{ns.replace("/", "%") or "%"}/{node}'
            )
            self.loaded[uid] = (f'{ns}/{node}', token)
        self._reply(query, string(string(Cdr().put('?', True), ''), f'{ns}/{node}').put('Q', uid))

    def _on_unload(self, query: Any) -> None:
        uid = Reader(query.payload.to_bytes()).get('Q')
        with self.lock:
            found = self.loaded.pop(uid, None)
        if found is not None:
            found[1].undeclare()
            self._reply(query, string(Cdr().put('?', True), ''))
        else:
            self._reply(
                query, string(Cdr().put('?', False), f'No node found with unique_id: {uid}')
            )

    def _on_list(self, query: Any) -> None:
        with self.lock:
            items = sorted(self.loaded.items())
        cdr = Cdr().put('I', len(items))
        for _uid, (name, _token) in items:
            string(cdr, name)
        cdr.put('I', len(items))
        for uid, _ in items:
            cdr.put('Q', uid)
        self._reply(query, cdr)
