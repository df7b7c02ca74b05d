"""A node's `~/get_type_description` service (REP-2011, as rcl offers it from Jazzy on): the
full description, and optionally the source text, of any type the node's endpoints use.

It is on unless the node's read-only parameter `start_type_description_service` is false
(tools' hidden nodes turn it off). Descriptions come from the same code that computes the
RIHS01 hashes (:mod:`ros2lite.interfaces.hashing`), so a description always matches its hash.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypedDict, cast

if TYPE_CHECKING:
    from ros2lite.msgs.type_description_interfaces.msg import (
        Field,
        FieldType,
        IndividualTypeDescription,
        TypeDescription,
        TypeSource,
    )
    from ros2lite.msgs.type_description_interfaces.srv import (
        GetTypeDescription_Request,
        GetTypeDescription_Response,
    )
    from ros2lite.node_interface import NodeInterface
    from ros2lite.service import Service

__all__ = ['START_TYPE_DESCRIPTION_SERVICE_PARAM', 'TypeDescriptionService']

START_TYPE_DESCRIPTION_SERVICE_PARAM = 'start_type_description_service'
SERVICE_TYPE = 'type_description_interfaces/srv/GetTypeDescription'
_ENCODING = {'msg': 'msg', 'srv': 'srv', 'action': 'action'}


class TypeDescriptionService:
    """Declares the parameter and, if it is true, serves the descriptions on `node`."""

    def __init__(self, node: NodeInterface) -> None:
        from ros2lite.parameters.store import descriptor

        self._node = node
        self._service: Service[GetTypeDescription_Request, GetTypeDescription_Response] | None
        self._service = None
        param = node.declare_parameter(
            START_TYPE_DESCRIPTION_SERVICE_PARAM,
            True,
            descriptor(
                description='If true, the node offers ~/get_type_description',
                read_only=True,
            ),
        )
        if param.value:
            self._service = node.create_service(
                SERVICE_TYPE, f'{node.get_name()}/get_type_description', self._describe
            )

    def _types_in_use(self) -> set[str]:
        node = self._node
        topics = [*node.publishers, *node.subscriptions]
        services = [*node.services, *node.clients]
        return {e.endpoint.type_name for e in topics} | {e.endpoint.type_name for e in services}

    def _describe(
        self, request: GetTypeDescription_Request, response: GetTypeDescription_Response
    ) -> GetTypeDescription_Response:
        from ros2lite.interfaces import type_hash
        from ros2lite.interfaces.errors import InterfaceError

        name = request.type_name
        if name not in self._types_in_use():
            response.successful = False
            response.failure_reason = 'Type not currently in use by this node'
            return response
        try:
            ours = type_hash(name)
        except InterfaceError as e:
            response.successful = False
            response.failure_reason = str(e)
            return response
        if request.type_hash and request.type_hash != ours:
            response.successful = False
            response.failure_reason = f'Type hash mismatch: this node uses {ours}'
            return response
        response.type_description = description_message(name)
        if request.include_type_sources:
            response.type_sources = type_sources(response.type_description)
        response.successful = True
        return response

    def destroy(self) -> None:
        """Withdraw the service (the node is going away)."""
        if self._service is not None:
            self._node.destroy_service(self._service)
            self._service = None


class _FieldTypeFields(TypedDict):
    """A field's type as :func:`ros2lite.interfaces.hashing.type_description` gives it."""

    type_id: int
    capacity: int
    string_capacity: int
    nested_type_name: str


def description_message(name: str) -> TypeDescription:
    """type_description_interfaces/msg/TypeDescription of `name` and what it refers to."""
    from ros2lite.interfaces import get_interface
    from ros2lite.interfaces.hashing import type_description

    field_type: type[FieldType] = get_interface('type_description_interfaces/msg/FieldType')
    field: type[Field] = get_interface('type_description_interfaces/msg/Field')
    individual: type[IndividualTypeDescription] = get_interface(
        'type_description_interfaces/msg/IndividualTypeDescription'
    )

    def convert(desc: object) -> IndividualTypeDescription:
        d = cast('dict[str, object]', desc)
        fields = cast('list[dict[str, object]]', d['fields'])
        return individual(
            type_name=str(d['type_name']),
            fields=[
                field(name=str(f['name']), type=field_type(**cast(_FieldTypeFields, f['type'])))
                for f in fields
            ],
        )

    tree = type_description(name)
    referenced = cast('list[object]', tree['referenced_type_descriptions'])
    description: type[TypeDescription] = get_interface(
        'type_description_interfaces/msg/TypeDescription'
    )
    return description(
        type_description=convert(tree['type_description']),
        referenced_type_descriptions=[convert(d) for d in referenced],
    )


def type_sources(description: TypeDescription) -> list[TypeSource]:
    """The definition file of each type in a description; types generated from a service or
    an action file (requests, goals, …) have none of their own: 'implicit', as in rcl."""
    from ros2lite.interfaces import get_interface
    from ros2lite.interfaces.registry import default_registry

    source: type[TypeSource] = get_interface('type_description_interfaces/msg/TypeSource')
    registry = default_registry()
    out = []
    for desc in [description.type_description, *description.referenced_type_descriptions]:
        name = desc.type_name
        if registry.exists(name):
            kind = name.split('/')[1]
            text = registry.interface_text(name)
            out.append(source(type_name=name, encoding=_ENCODING[kind], raw_file_contents=text))
        else:
            out.append(source(type_name=name, encoding='implicit', raw_file_contents=''))
    return out
