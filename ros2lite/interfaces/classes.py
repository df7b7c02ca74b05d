"""Message, service and action classes that behave like rclpy's generated ones.

Each message class is generated Python source (slots, keyword constructor, validating
properties) compiled once per type. Codecs write the `_field` slots directly, so validation costs
only where user code assigns values.
"""

from __future__ import annotations

import contextlib
import math
import operator
import os
from array import array
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any, ClassVar

from .errors import FieldError, InterfaceError
from .parser import INT_RANGES, PRIMITIVES, Constant, FieldType, MessageDef, check_definition
from .registry import Registry, default_registry, normalize_name

# array typecodes for primitive sequences/arrays (as rclpy: array.array for numbers)
TYPECODES = {
    'int8': 'b',
    'uint8': 'B',
    'char': 'B',
    'int16': 'h',
    'uint16': 'H',
    'int32': 'i',
    'uint32': 'I',
    'int64': 'q',
    'uint64': 'Q',
    'float32': 'f',
    'float64': 'd',
}
# rosidl names as get_fields_and_field_types() reports them
ROSIDL_NAMES = {
    'bool': 'boolean',
    'byte': 'octet',
    'char': 'uint8',
    'float32': 'float',
    'float64': 'double',
}
FLOAT32_MAX = 3.4028234663852886e38  # exact FLT_MAX
# deepest nesting of message types accepted (real ones nest a handful of levels; the codecs
# inline nested types, so this also bounds the generated code)
MAX_NESTING = 32


class MessageMeta(type):
    """Marker metaclass so isinstance checks can tell ros2lite message classes apart."""


class Message(metaclass=MessageMeta):
    """Base of every generated message class."""

    __slots__ = ()
    _TYPE_NAME: ClassVar[str] = ''
    _DEF: ClassVar[MessageDef]
    # the classes of the message-typed fields, from the factory that built this one
    _NESTED: ClassVar[dict[str, type[Message]]] = {}
    SLOT_TYPES: tuple[FieldType, ...] = ()
    _fields_and_field_types: dict[str, str] = {}

    @classmethod
    def get_fields_and_field_types(cls) -> dict[str, str]:
        """Field name → rosidl type text, in definition order (rclpy's)."""
        return dict(cls._fields_and_field_types)

    def __repr__(self) -> str:
        args = []
        for name in self._fields_and_field_types:
            value = getattr(self, '_' + name)
            if isinstance(value, array):
                text = repr(value.tolist()) if len(value) else '[]'
            else:
                text = repr(value)
            args.append(f'{name}={text}')
        return f"{self._TYPE_NAME.replace('/', '.')}({', '.join(args)})"

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        slots: tuple[str, ...] = self.__slots__
        return all(getattr(self, s) == getattr(other, s) for s in slots)

    __hash__ = None  # type: ignore[assignment]  # mutable, like rclpy messages

    if TYPE_CHECKING:
        # fields are generated per type, so type checkers treat messages as dynamic
        def __init__(self, **kwargs: Any) -> None: ...


def rosidl_type_string(ft: FieldType) -> str:
    """Type text as rclpy's get_fields_and_field_types() gives it."""
    if ft.is_primitive:
        base = ROSIDL_NAMES.get(ft.base, ft.base)
        if ft.string_bound:
            base = f'{base}<={ft.string_bound}'
    else:
        pkg, _, name = ft.base.split('/')
        base = f'{pkg}/{name}'
    if ft.container == 'array':
        return f'{base}[{ft.size}]'
    if ft.container == 'bounded':
        return f'sequence<{base}, {ft.size}>'
    if ft.container == 'sequence':
        return f'sequence<{base}>'
    return base


def constant_value(constant: Constant) -> Any:
    """A constant's value as the class holds it: rosidl's Python classes make a `byte`
    constant `bytes` (`DiagnosticStatus.WARN == b'\\x01'`), ready to assign to a byte field;
    `char` is uint8 there, an int like the rest."""
    if constant.type == 'byte' and isinstance(constant.value, int):
        return bytes((constant.value,))
    return constant.value


def _scalar_default(ft: FieldType) -> str:
    """Source text for a fresh scalar default of an element type."""
    base = ft.base
    if base == 'bool':
        return 'False'
    if base == 'byte':
        return "b'\\x00'"
    if base in ('float32', 'float64'):
        return '0.0'
    if base in ('string', 'wstring'):
        return "''"
    if base in PRIMITIVES:
        return '0'
    return f'_C[{base!r}]()'


def _default_source(ft: FieldType, default: Any, values: list[object]) -> str:
    """Source of an expression building a field's default value (a new object every time).
    A value from the definition is appended to `values` (the class's `_D`) and read from
    there, never written into the source: no repr has to round-trip (`inf`, `nan`)."""
    if default is not None:
        if ft.base == 'byte':
            default = [bytes([v]) for v in default] if ft.is_container else bytes([default])
        values.append(default)
        ref = f'_D[{len(values) - 1}]'
        if ft.is_container and ft.base in TYPECODES:
            return f'_array({TYPECODES[ft.base]!r}, {ref})'
        if ft.is_container:
            return f'list({ref})'
        return ref
    if not ft.is_container:
        return _scalar_default(ft)
    if ft.container == 'array':
        if ft.base in TYPECODES:
            return f'_array({TYPECODES[ft.base]!r}, [{_scalar_default(ft)}]) * {ft.size}'
        return f'[{_scalar_default(ft)} for _ in _range({ft.size})]'
    if ft.base in TYPECODES:
        return f'_array({TYPECODES[ft.base]!r})'
    return '[]'


def _check_scalar_source(ft: FieldType, name: str, var: str) -> list[str]:
    """Validation lines for one scalar value held in `var` (may rebind `var`)."""
    base = ft.base
    if base == 'bool':
        return [f'if not isinstance({var}, bool): raise _err({name!r}, "must be of type \'bool\'")']
    if base in INT_RANGES and base != 'byte':
        lo, hi = INT_RANGES[base]
        return [
            f'if not isinstance({var}, int): raise _err({name!r}, "must be of type \'int\'")',
            f'if not {lo} <= {var} <= {hi}:'
            f' raise _err({name!r}, "must be an integer in [{lo}, {hi}]")',
        ]
    if base == 'byte':
        return [
            f'if isinstance({var}, int) and 0 <= {var} <= 255: {var} = bytes(({var},))',
            f'if not isinstance({var}, (bytes, bytearray)) or len({var}) != 1:'
            f' raise _err({name!r}, "must be of type \'bytes\' with length 1")',
            f'{var} = bytes({var})',
        ]
    if base in ('float32', 'float64'):
        lines = [
            f'if isinstance({var}, int) and not isinstance({var}, bool): {var} = float({var})',
            f'if not isinstance({var}, float): raise _err({name!r}, "must be of type \'float\'")',
        ]
        if base == 'float32':
            lines.append(
                f'if ({var} < -{FLOAT32_MAX!r} or {var} > {FLOAT32_MAX!r}) and not _isinf({var}):'
                f' raise _err({name!r}, "must be a float in [-{FLOAT32_MAX!r}, {FLOAT32_MAX!r}]")'
            )
        return lines
    if base in ('string', 'wstring'):
        lines = [f'if not isinstance({var}, str): raise _err({name!r}, "must be of type \'str\'")']
        if ft.string_bound:
            lines.append(
                f'if len({var}) > {ft.string_bound}: raise _err({name!r},'
                f' "must be string value not longer than {ft.string_bound}")'
            )
        return lines
    return [
        f'if type({var}) is not _C[{base!r}] and not _same_type({var}, {base!r}):'
        f' raise _err({name!r}, "must be a sub message of type \'{base}\'")',
    ]


def _unchecked_source(ft: FieldType) -> list[str]:
    """What an assignment still does with checks off (as rosidl's Jazzy classes): bring
    sequences to the stored form (`array` of numbers, list otherwise), nothing else."""
    if not ft.is_container:
        return []
    if ft.base in TYPECODES:
        code = TYPECODES[ft.base]
        return [f'if type(v) is not _array or v.typecode != {code!r}: v = _array({code!r}, v)']
    if ft.base == 'byte':
        return ['v = [bytes((x,)) for x in v] if isinstance(v, (bytes, bytearray)) else list(v)']
    return ['v = list(v)']


def _setter_source(name: str, ft: FieldType) -> list[str]:
    lines = [f'def _set_{name}(self, v):']
    unchecked = _unchecked_source(ft)
    lines += ['    if not _CHECK.on and not _CHECK.forced:']
    lines += ['        ' + s for s in unchecked]
    lines += [f'        self._{name} = v', '        return']
    body: list[str] = []
    if not ft.is_container:
        body += _check_scalar_source(ft, name, 'v')
    else:
        body.append(
            'if isinstance(v, (str, dict)) or not hasattr(v, "__len__"):'
            f' raise _err({name!r}, "must be a set or sequence")'
        )
        if ft.base in TYPECODES:
            code = TYPECODES[ft.base]
            body.append(
                f'if type(v) is not _array or v.typecode != {code!r}:'
                f' v = _to_array({code!r}, v, {name!r}, {ft.base == "float32"})'
            )
        else:
            if ft.base == 'byte':
                body.append('if isinstance(v, (bytes, bytearray)): v = [bytes((x,)) for x in v]')
            body.append('v = list(v)')
            body.append('for i, e in enumerate(v):')
            inner = _check_scalar_source(ft.element, name, 'e')
            body += ['    ' + s for s in inner]
            body.append('    v[i] = e')
        if ft.container == 'array':
            body.append(
                f'if len(v) != {ft.size}: raise _err({name!r},'
                f' "must have exactly {ft.size} elements")'
            )
        elif ft.container == 'bounded':
            body.append(
                f'if len(v) > {ft.size}: raise _err({name!r},'
                f' "must have at most {ft.size} elements")'
            )
    body.append(f'self._{name} = v')
    return lines + ['    ' + s for s in body]


class _FieldChecks:
    """Whether assignments to message fields are checked (types, ranges, sizes).

    On by default; `ROS_PYTHON_CHECK_FIELDS=0` turns it off, as rosidl's Jazzy classes are
    unless that variable is `1` (`ros2lite env` sets 0 unless the shell chose). Code that
    fills messages from outside input forces checks on with :func:`checked_fields`."""

    def __init__(self) -> None:
        self.on = os.environ.get('ROS_PYTHON_CHECK_FIELDS', '1') != '0'
        self.forced = 0


_CHECK = _FieldChecks()


@contextlib.contextmanager
def checked_fields() -> Iterator[None]:
    """Check every field assignment within the block, whatever the default."""
    _CHECK.forced += 1
    try:
        yield
    finally:
        _CHECK.forced -= 1


def _err(name: str, what: str) -> FieldError:
    return FieldError(f"The '{name}' field {what}")


def _to_array(code: str, value: Any, name: str, f32: bool) -> array:
    try:
        if code in 'fd':
            value = [
                float(x) if isinstance(x, int) and not isinstance(x, bool) else x for x in value
            ]
            if not all(isinstance(x, float) for x in value):
                raise TypeError
            if f32 and any(
                (x < -FLOAT32_MAX or x > FLOAT32_MAX) and not math.isinf(x) for x in value
            ):
                raise OverflowError
        elif not all(isinstance(x, int) for x in value):
            raise TypeError
        return array(code, value)
    except OverflowError:
        raise _err(name, 'has a value out of its element range') from None
    except TypeError:
        kind = 'float' if code in 'fd' else 'int'
        raise _err(name, f"must be a set or sequence and each value of type '{kind}'") from None


class ClassFactory:
    """Builds and caches classes for one registry."""

    def __init__(self, registry: Registry) -> None:
        self.registry = registry
        self.classes: dict[str, type[Message]] = {}

    def same_type(self, value: object, name: str) -> bool:
        """Whether `value` is a message of type `name` (of whichever factory)."""
        return getattr(type(value), '_TYPE_NAME', None) == name

    def message_class(self, name: str) -> type[Message]:
        """The class of a message type, built (with its nested types) on first use."""
        cls = self.classes.get(name)
        if cls is not None:
            return cls
        return self._message_class(name, [])

    def _message_class(self, name: str, outer: list[str]) -> type[Message]:
        """Build `name` after the types it nests; `outer` are the types that contain it, so a
        type that contains itself (a crafted bag can say so) is an error, not a recursion."""
        cls = self.classes.get(name)
        if cls is not None:
            return cls
        if name in outer or len(outer) >= MAX_NESTING:
            chain = ' -> '.join([*outer, name])
            why = 'contains itself' if name in outer else f'nests deeper than {MAX_NESTING} levels'
            raise InterfaceError(f"type '{outer[0]}' {why} ({chain})")
        mdef = self.registry.message(name)
        outer.append(name)
        for f in mdef.fields:
            if not f.type.is_primitive:
                self._message_class(f.type.base, outer)
        outer.pop()
        cls = self._build(mdef)
        self.classes[name] = cls
        if mdef.name != name:
            self.classes[mdef.name] = cls
        return cls

    def _build(self, mdef: MessageDef) -> type[Message]:
        check_definition(mdef)  # only identifiers ever reach the generated source
        short = mdef.short_name
        names = [f.name for f in mdef.fields]
        src = [f'class {short}(_Message):', f'    __slots__ = {tuple("_" + n for n in names)!r}']
        # values from the definition are bound through the namespace, not written as text
        constants = tuple(constant_value(c) for c in mdef.constants)
        for i, c in enumerate(mdef.constants):
            src.append(f'    {c.name} = _K[{i}]')
        defaults: list[object] = []
        params = ''.join(f', {n}=_MISSING' for n in names)
        src.append(f'    def __init__(self{params}):')
        if not names:
            src.append('        pass')
        for f in mdef.fields:
            default = _default_source(f.type, f.default, defaults)
            src.append(f'        if {f.name} is _MISSING: self._{f.name} = {default}')
            src.append(f'        else: self.{f.name} = {f.name}')
        for f in mdef.fields:
            src += ['    ' + s for s in _setter_source(f.name, f.type)]
            # a C-level getter: reading a field costs a third less than through a lambda;
            # `_property`: a field may be named `property` (the class body would then see it)
            src.append(
                f"    {f.name} = _property(_getter('_{f.name}'), _set_{f.name}, "
                f"doc={rosidl_type_string(f.type)!r})"
            )
        ns: dict[str, Any] = {
            '_Message': Message,
            '_MISSING': _MISSING,
            '_C': self.classes,
            '_array': array,
            '_err': _err,
            '_to_array': _to_array,
            '_isinf': math.isinf,
            '_same_type': self.same_type,
            '_getter': operator.attrgetter,
            '_property': property,
            '_CHECK': _CHECK,
            '_K': constants,
            '_D': tuple(defaults),
            # the __init__ body's only builtin, under a name no field can take
            '_range': range,
        }
        exec(compile('\n'.join(src), f'<ros2lite {mdef.name}>', 'exec'), ns)
        cls: type[Message] = ns[short]
        cls._TYPE_NAME = mdef.name
        cls._DEF = mdef
        cls.SLOT_TYPES = tuple(f.type for f in mdef.fields)
        cls._fields_and_field_types = {f.name: rosidl_type_string(f.type) for f in mdef.fields}
        cls._NESTED = {
            f.name: self.classes[f.type.base] for f in mdef.fields if not f.type.is_primitive
        }
        pkg, kind, _ = mdef.name.split('/')
        cls.__module__ = f'ros2lite.msgs.{pkg}.{kind}'
        cls.__qualname__ = short
        return cls


def field_class(cls: type[Message], name: str) -> type[Message]:
    """The class of a message-typed field's elements, built by the same factory (so a type
    from a workspace registry finds its nested types where it found itself)."""
    return cls._NESTED[name]


class _Missing:
    def __repr__(self) -> str:
        return '<missing>'


_MISSING = _Missing()


class ServiceType:
    """A service class: a namespace holding Request, Response and Event like rosidl's."""

    _TYPE_NAME: ClassVar[str] = ''
    Request: type[Message]
    Response: type[Message]
    Event: type[Message]

    def __init__(self) -> None:
        raise NotImplementedError('Service classes can not be instantiated')


def as_service_class(cls: object) -> type[ServiceType]:
    """`cls` itself, checked to be a service class (library code reads its parts through
    this nominal type; users' code sees the :class:`ros2lite.type_support.Srv` protocol)."""
    if isinstance(cls, type) and issubclass(cls, ServiceType):
        return cls
    raise TypeError(f'not a ros2lite service type: {cls!r}')


class ActionImpl:
    """What rcl_action builds an action from (rosidl's `<Action>.Impl`): its three services
    and two topics' types."""

    SendGoalService: type[ServiceType]
    GetResultService: type[ServiceType]
    CancelGoalService: type[ServiceType]
    FeedbackMessage: type[Message]
    GoalStatusMessage: type[Message]


class ActionType:
    """An action class: Goal/Result/Feedback plus the generated transport types."""

    _TYPE_NAME: ClassVar[str] = ''
    Goal: type[Message]
    Result: type[Message]
    Feedback: type[Message]
    FeedbackMessage: type[Message]
    SendGoal: type[ServiceType]
    GetResult: type[ServiceType]
    Impl: type[ActionImpl]

    def __init__(self) -> None:
        raise NotImplementedError('Action classes can not be instantiated')


_FACTORIES: dict[int, ClassFactory] = {}


def factory(reg: Registry | None = None) -> ClassFactory:
    """The class factory of a registry (the default one unless given)."""
    reg = reg or default_registry()
    f = _FACTORIES.get(id(reg))
    if f is None or f.registry is not reg:
        f = _FACTORIES[id(reg)] = ClassFactory(reg)
    return f


def _service_class(name: str, fac: ClassFactory) -> type[ServiceType]:
    cls = fac.classes.get(name)
    if cls is None:
        attrs = {
            '_TYPE_NAME': name,
            'Request': fac.message_class(name + '_Request'),
            'Response': fac.message_class(name + '_Response'),
            'Event': fac.message_class(name + '_Event'),
        }
        pkg, kind, short = name.split('/')
        cls = type(short, (ServiceType,), attrs)
        cls.__module__ = f'ros2lite.msgs.{pkg}.{kind}'
        fac.classes[name] = cls
    return cls  # type: ignore[return-value]


def _action_class(name: str, fac: ClassFactory) -> type[ActionType]:
    cls = fac.classes.get(name)
    if cls is None:
        send_goal = _service_class(name + '_SendGoal', fac)
        get_result = _service_class(name + '_GetResult', fac)
        feedback_message = fac.message_class(name + '_FeedbackMessage')
        impl = type(
            'Impl',
            (ActionImpl,),
            {
                'SendGoalService': send_goal,
                'GetResultService': get_result,
                'FeedbackMessage': feedback_message,
                'CancelGoalService': _service_class('action_msgs/srv/CancelGoal', fac),
                'GoalStatusMessage': fac.message_class('action_msgs/msg/GoalStatusArray'),
            },
        )
        pkg, kind, short = name.split('/')
        cls = type(
            short,
            (ActionType,),
            {
                '_TYPE_NAME': name,
                'Goal': fac.message_class(name + '_Goal'),
                'Result': fac.message_class(name + '_Result'),
                'Feedback': fac.message_class(name + '_Feedback'),
                'FeedbackMessage': feedback_message,
                'SendGoal': send_goal,
                'GetResult': get_result,
                'Impl': impl,
            },
        )
        cls.__module__ = f'ros2lite.msgs.{pkg}.{kind}'
        fac.classes[name] = cls
    return cls  # type: ignore[return-value]


def get_interface(name: str, reg: Registry | None = None) -> Any:
    """The class for any message, service, action or generated sub-type name."""
    fac = factory(reg)
    name = normalize_name(name)
    cached = fac.classes.get(name)
    if cached is not None:
        return cached
    kind = fac.registry.kind_of(name)
    if kind == 'service':
        return _service_class(name, fac)
    if kind == 'action':
        return _action_class(name, fac)
    return fac.message_class(name)
