"""The generators behind :mod:`ros2lite.interfaces.cdr`: XCDR1 codecs as Python source, one
serializer and one deserializer per type and byte order, compiled once.

Speed comes from generating straight-line Python per type: nested structs are inlined, and
consecutive primitives whose alignment is statically known are packed or unpacked with a single
`struct.Struct` call. Primitive sequences move as `array` buffers in one copy. Alignment is
relative to the byte after the 4-byte encapsulation header, exactly as FastCDR does.
"""

from __future__ import annotations

import struct
from array import array
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from .classes import TYPECODES, Message, factory
from .errors import CdrError
from .parser import Field, FieldType, MessageDef, check_definition
from .registry import Registry

if TYPE_CHECKING:
    from ros2lite.type_support import Msg

HEADER_LE = b'\x00\x01\x00\x00'
# its first two bytes read as a little-endian uint16 (the options that follow are ignored)
(HEADER_LE_WORD,) = struct.unpack_from('<H', HEADER_LE)
# all four bytes as a little-endian uint32 (what the serializers pack in front of the body)
(HEADER_LE_UINT32,) = struct.unpack('<I', HEADER_LE)
# struct formats of the primitives: the array typecodes, plus bool and byte
_FMT = {**TYPECODES, 'bool': '?', 'byte': 'c'}
_SIZE = {k: struct.calcsize('<' + v) for k, v in _FMT.items()}
_DUMMY = Field('structure_needs_at_least_one_member', FieldType('uint8'))
_ZEROS = tuple(b'\x00' * i for i in range(8))
# Fixed primitive arrays longer than this leave the packed run and copy as one buffer.
_INLINE_ARRAY_MAX = 16


class _Gen:
    """Accumulates generated lines plus the pending run of statically aligned primitives."""

    def __init__(self, registry: Registry, endian: str) -> None:
        self.reg = registry
        self.endian = endian
        self.lines: list[str] = []
        self.indent = 1
        self.ns: dict[str, Any] = {'_array': array, '_Z': _ZEROS, '_CdrError': CdrError}
        self.counter = 0
        # alignment knowledge: offset ≡ rem (mod mod)
        self.mod = 8
        self.rem = 0
        self.run_fmt = ''
        self.run_items: list[tuple[str, str]] = []  # (kind, expression/target)

    def name(self, prefix: str) -> str:
        self.counter += 1
        return f'{prefix}{self.counter}'

    def emit(self, line: str) -> None:
        self.lines.append('    ' * self.indent + line)

    def const(self, prefix: str, value: object) -> str:
        n = self.name(prefix)
        self.ns[n] = value
        return n

    def forget(self, mod: int = 1) -> None:
        self.mod, self.rem = mod, 0

    def advance(self, nbytes: int) -> None:
        self.rem = (self.rem + nbytes) % self.mod

    def static_pad(self, align: int) -> int | None:
        """Padding needed for `align` if it is known at generation time."""
        if align <= 1:
            return 0
        if self.mod >= align:
            return (-self.rem) % align
        return None

    def check_bound(self, n: str, bound: int) -> None:
        self.emit(f'if {n} > {bound}: raise _CdrError("sequence exceeds bound {bound}")')

    def element_def(self, ft: FieldType) -> MessageDef:
        return checked_message(self.reg, ft.base)


def checked_message(reg: Registry, name: str) -> MessageDef:
    """A definition from `reg`, refused unless every name in it is an identifier: its names
    become generated source text, and a registry may hold definitions from a bag or the wire."""
    mdef = reg.message(name)
    check_definition(mdef)
    return mdef


class _Restart(Exception):
    """The serializer being generated needs a more general shape (see build_serializer)."""


class _SerGen(_Gen):
    """Generates the body of `def ser(m)`; `o` is the body offset, one final join.

    Straight-line code (no loops, no conditional padding) keeps each chunk in a local and
    joins one tuple, which is cheaper than growing a list for small messages; otherwise
    chunks go to list `p`. Code that never reads the offset does not track it. Emitting
    something the chosen shape can't hold raises _Restart."""

    def __init__(self, registry: Registry, straight: bool, track_offset: bool) -> None:
        super().__init__(registry, '<')
        self.straight = straight
        self.track_offset = track_offset
        self.parts: list[str] = []
        self.header_written = False

    def chunk(self, expr: str) -> None:
        if self.straight:
            c = self.name('c')
            self.emit(f'{c} = {expr}')
            self.parts.append(c)
        else:
            self.emit(f'p.append({expr})')

    def moved(self, nbytes: object) -> None:
        if self.track_offset:
            self.emit(f'o += {nbytes}')

    def reads_offset(self) -> None:
        if not self.track_offset:
            raise _Restart

    def opens_block(self) -> None:
        if self.straight:
            raise _Restart

    def flush(self) -> None:
        if not self.run_fmt:
            if not self.header_written:  # a blob or loop comes first: the header goes alone
                self.header_written = True
                self.chunk('_HEADER')
            return
        fmt, args = self.run_fmt, ', '.join(e for _, e in self.run_items)
        header = not self.header_written  # the first run carries the encapsulation header
        if header:
            fmt, args = 'I' + fmt, f'{HEADER_LE_UINT32}, {args}'
            self.header_written = True
        st = struct.Struct(self.endian + fmt)
        s = self.const('_S', st.pack)
        self.chunk(f'{s}({args})')
        self.moved(st.size - 4 if header else st.size)  # offsets count from the body
        self.run_fmt, self.run_items = '', []

    def align_now(self, align: int) -> None:
        """Runtime padding to `align` (the pending run must be flushed)."""
        self.reads_offset()
        k = self.name('k')
        self.emit(f'{k} = -o & {align - 1}')
        self.chunk(f'_Z[{k}]')
        self.moved(k)

    def add(self, fmt: str, size: int, align: int, expr: str | None) -> None:
        pad = self.static_pad(align)
        if pad is None:
            self.flush()
            self.align_now(align)
            self.forget(align)
            pad = 0
        self.run_fmt += 'x' * pad + fmt
        if expr is not None:
            self.run_items.append(('v', expr))
        self.advance(pad + size)

    def struct(self, mdef: MessageDef, expr: str) -> None:
        for f in mdef.fields or [_DUMMY]:
            fexpr = f'{expr}._{f.name}' if mdef.fields else '0'
            self.field(f.type, fexpr)

    def blob(self, expr: str, nbytes: str) -> None:
        self.chunk(expr)
        self.moved(nbytes)

    def field(self, ft: FieldType, expr: str) -> None:
        base = ft.base
        if not ft.is_container:
            if base in _FMT:
                self.add(_FMT[base], _SIZE[base], _SIZE[base], expr)
            elif base == 'string':
                s = self.name('s')
                self.emit(f'{s} = {expr}.encode()')
                self.add('I', 4, 4, f'len({s}) + 1')
                self.flush()
                self.chunk(s)
                self.blob('_NUL', f'len({s}) + 1')
                self.forget()
            elif base == 'wstring':
                w = self.name('w')
                self.emit(f"{w} = _array('H', {expr}.encode('utf-16-le'))")
                self.add('I', 4, 4, f'len({w})')
                self.flush()
                self.blob(f"_array('I', {w})", f'4 * len({w})')
                self.forget(4)
            else:
                self.struct(self.element_def(ft), expr)
            return
        if (
            ft.container == 'array'
            and base in _FMT
            and base != 'byte'
            and ft.size <= _INLINE_ARRAY_MAX
        ):
            self.add(f'{ft.size}{_FMT[base]}', ft.size * _SIZE[base], _SIZE[base], '*' + expr)
            return
        if ft.container == 'array' and base == 'byte':
            self.add(f'{ft.size}c', ft.size, 1, '*' + expr)
            return
        n = self.name('n')
        if ft.container == 'array':
            self.emit(f'{n} = {ft.size}')
            self.emit(
                f'if len({expr}) != {ft.size}: '
                f'raise _CdrError("array field needs {ft.size} elements")'
            )
        else:
            self.emit(f'{n} = len({expr})')
            if ft.container == 'bounded':
                self.check_bound(n, ft.size)
            self.add('I', 4, 4, n)
        self.flush()
        if base in TYPECODES:
            size = _SIZE[base]
            pad = self.static_pad(size)
            if pad is None:
                self.reads_offset()
                k = self.name('k')
                self.emit(f'{k} = -o & {size - 1} if {n} else 0')
                self.chunk(f'_Z[{k}]')
                self.moved(k)
            elif pad:
                self.opens_block()
                self.emit(f'if {n}:')
                self.emit(f'    p.append(_Z[{pad}])')
                self.emit(f'    o += {pad}')
            self.blob(expr, f'{n} * {size}')
            self.forget(size if ft.container == 'array' else min(size, 4))
            return
        if base == 'bool':
            self.blob(f'bytes({expr})', n)
            self.forget()
            return
        if base == 'byte':
            self.blob(f"b''.join({expr})", n)
            self.forget()
            return
        self.opens_block()
        e = self.name('e')
        self.emit(f'for {e} in {expr}:')
        self.indent += 1
        self.forget()
        self.field(ft.element, e)
        self.flush()
        self.indent -= 1
        self.forget()


class _DesGen(_Gen):
    """Generates `def des(d, o) -> (msg, o)` reading from bytes `d` at offset `o`."""

    def __init__(self, registry: Registry, endian: str, lenient: bool) -> None:
        super().__init__(registry, endian)
        self.decode = "decode('utf-8', 'replace')" if lenient else 'decode()'
        self.uses_mv = False
        # a line to emit right after the first unpack (the fast decoder's header check)
        self.after_first: str | None = None

    def flush(self) -> None:
        if not self.run_fmt:
            return
        st = struct.Struct(self.endian + self.run_fmt)
        s = self.const('_S', st.unpack_from)
        targets = self.run_items
        if targets and all(kind == 'v' for kind, _ in targets):
            # plain values: unpack straight into their targets (no temporary tuple indexing)
            self.emit(f'{", ".join(t for _, t in targets)}, = {s}(d, o)')
            self.emit(f'o += {st.size}')
            self.run_fmt, self.run_items = '', []
            self._after_first()
            return
        t = self.name('t')
        self.emit(f'{t} = {s}(d, o)')
        self.emit(f'o += {st.size}')
        i = 0
        for kind, target in targets:
            if kind == 'v':
                self.emit(f'{target} = {t}[{i}]')
                i += 1
            else:  # fixed array: kind is 'a:<count>:<typecode or list>'
                _, count, code = kind.split(':')
                c = int(count)
                if code == 'list':
                    self.emit(f'{target} = list({t}[{i}:{i + c}])')
                else:
                    self.emit(f'{target} = _array({code!r}, {t}[{i}:{i + c}])')
                i += c
        self.run_fmt, self.run_items = '', []
        self._after_first()

    def _after_first(self) -> None:
        if self.after_first is not None:
            self.emit(self.after_first)
            self.after_first = None

    def add(self, fmt: str, size: int, align: int, kind: str, target: str | None) -> None:
        pad = self.static_pad(align)
        if pad is None:
            self.flush()
            self.emit(f'o += (4 - o) & {align - 1}')
            self.forget(align)
            pad = 0
        self.run_fmt += 'x' * pad + fmt
        if target is not None:
            self.run_items.append((kind, target))
        self.advance(pad + size)

    def runtime_align(self, align: int) -> None:
        pad = self.static_pad(align)
        if pad is None:
            self.emit(f'o += (4 - o) & {align - 1}')
            self.forget(align)
        elif pad:
            self.emit(f'o += {pad}')
            self.advance(pad)

    def new_object(self, mdef: MessageDef) -> str:
        cls = self.const('_C', factory(self.reg).message_class(mdef.name))
        v = self.name('v')
        self.emit(f'{v} = _new({cls})')
        return v

    def struct(self, mdef: MessageDef) -> str:
        """Emit code that builds one message; returns the variable holding it."""
        v = self.new_object(mdef)
        if not mdef.fields:
            self.add('x', 1, 1, 'v', None)
        for f in mdef.fields:
            self.field(f.type, f'{v}._{f.name}')
        return v

    def field(self, ft: FieldType, target: str) -> None:
        base = ft.base
        if not ft.is_container:
            if base in _FMT:
                self.add(_FMT[base], _SIZE[base], _SIZE[base], 'v', target)
            elif base == 'string':
                n = self.name('n')
                self.add('I', 4, 4, 'v', n)
                self.flush()
                self.emit(f'{target} = d[o:o + {n} - 1].{self.decode}')
                self.emit(f'o += {n}')
                self.forget()
            elif base == 'wstring':
                self.wstring(target)
            else:
                v = self.struct(self.element_def(ft))
                self.emit(f'{target} = {v}')
            return
        if ft.container == 'array' and base in TYPECODES and ft.size <= _INLINE_ARRAY_MAX:
            code = TYPECODES[base]
            self.add(
                f'{ft.size}{_FMT[base]}',
                ft.size * _SIZE[base],
                _SIZE[base],
                f'a:{ft.size}:{code}',
                target,
            )
            return
        if ft.container == 'array' and base in ('bool', 'byte'):
            self.add(f'{ft.size}{_FMT[base]}', ft.size, 1, f'a:{ft.size}:list', target)
            return
        n = self.name('n')
        if ft.container == 'array':
            self.emit(f'{n} = {ft.size}')
        else:
            self.add('I', 4, 4, 'v', n)
            self.flush()
            if ft.container == 'bounded':
                self.check_bound(n, ft.size)
        self.flush()
        if base in TYPECODES:
            size = _SIZE[base]
            code = TYPECODES[base]
            a = self.name('a')
            self.emit(f'{a} = _array({code!r})')
            self.emit(f'if {n}:')
            self.indent += 1
            if size > 1:
                self.runtime_align(size)
            self.emit(f'{a}.frombytes(mv[o:o + {n} * {size}])')
            self.uses_mv = True
            if size > 1 and self.endian == '>':
                self.emit(f'{a}.byteswap()')
            self.emit(f'o += {n} * {size}')
            self.indent -= 1
            self.emit(f'{target} = {a}')
            self.forget(min(size, 4) if size > 1 else 1)
            if ft.container == 'array' and size > 1:
                self.forget(size)
            return
        if base == 'bool':
            self.emit(f'{target} = [x != 0 for x in d[o:o + {n}]]')
            self.emit(f'o += {n}')
            self.forget()
            return
        if base == 'byte':
            # over the slice, not a range: a hostile length cannot outrun the data
            self.emit(f'{target} = [bytes((x,)) for x in d[o:o + {n}]]')
            self.emit(f'o += {n}')
            self.forget()
            return
        lst = self.name('l')
        self.emit(f'{lst} = []')
        self.emit(f'for _ in range({n}):')
        self.indent += 1
        self.forget()
        e = self.name('e')
        self.field(ft.element, e)
        self.flush()
        self.emit(f'{lst}.append({e})')
        self.indent -= 1
        self.forget()
        self.emit(f'{target} = {lst}')

    def wstring(self, target: str) -> None:
        n = self.name('n')
        self.add('I', 4, 4, 'v', n)
        self.flush()
        u = self.name('u')
        self.emit(f"{u} = _array('I')")
        self.emit(f'{u}.frombytes(mv[o:o + 4 * {n}])')
        self.uses_mv = True
        if self.endian == '>':
            self.emit(f'{u}.byteswap()')
        self.emit(f"{target} = _array('H', {u}).tobytes().decode('utf-16-le', 'replace')")
        self.emit(f'o += 4 * {n}')
        self.forget(4)


def build_serializer(name: str, reg: Registry) -> Callable[[Msg], bytes]:
    # the cheapest shape the type allows: straight-line without offset, straight-line with
    # offset, and the general list-building form (which always tracks the offset)
    """Generate and compile `ser(msg) -> bytes` for one type."""
    for straight, track_offset in ((True, False), (True, True), (False, True)):
        gen = _SerGen(reg, straight, track_offset)
        try:
            gen.struct(checked_message(reg, name), 'm')
            gen.flush()
        except _Restart:
            continue
        break
    gen.ns['_join'] = b''.join
    gen.ns['_NUL'] = b'\x00'
    gen.ns['_HEADER'] = HEADER_LE
    head = ['    o = 0'] if track_offset else []
    # every type has a first run of primitives (a length at least), which packs the header
    assert gen.header_written
    if straight:
        parts = gen.parts
        done = parts[0] if len(parts) == 1 else f'_join(({", ".join(parts)},))'
        body = [*head, *gen.lines, f'    return {done}']
    else:
        body = ['    p = []', *head, *gen.lines, '    return _join(p)']
    src = 'def ser(m):\n' + '\n'.join(body)
    exec(compile(src, f'<cdr ser {name}>', 'exec'), gen.ns)
    fn: Callable[[Msg], bytes] = gen.ns['ser']
    fn.__doc__ = src
    return fn


Des = Callable[[bytes, int], tuple[Message, int]]


def _des_body(
    name: str, reg: Registry, little: bool, lenient: bool, indent: int, header: bool = False
) -> tuple[_DesGen, str]:
    """Generated lines that build one `name` message from `d` at offset `o`, and the variable
    that holds it at the end. With `header`, `o` starts at 0 and the encapsulation header is
    read by the first unpack (checked right after it: little-endian CDR, or ValueError)."""
    gen = _DesGen(reg, '<' if little else '>', lenient)
    gen.indent = indent
    gen.ns['_new'] = object.__new__
    if header:
        # the 4 header bytes ride along in the first run without moving the body's
        # alignment (which is relative to the byte after them)
        gen.run_fmt, gen.run_items = 'H2x', [('v', '_h')]
        gen.after_first = f'if _h != {HEADER_LE_WORD}: raise ValueError'
    v = gen.struct(checked_message(reg, name))
    gen.flush()
    if gen.uses_mv:
        gen.lines.insert(0, '    ' * indent + 'mv = memoryview(d)')
    return gen, v


def build_deserializer(name: str, reg: Registry, little: bool = True, lenient: bool = False) -> Des:
    """Generate and compile `des(data, offset) -> (msg, end)` for one type and byte order."""
    gen, v = _des_body(name, reg, little, lenient, 1)
    src = 'def des(d, o):\n' + '\n'.join(gen.lines) + f'\n    return {v}, o'
    exec(compile(src, f'<cdr des {name}>', 'exec'), gen.ns)
    fn: Des = gen.ns['des']
    fn.__doc__ = src
    return fn


def build_fast_decoder(
    name: str, reg: Registry, slow: Callable[[bytes], Message]
) -> Callable[[bytes], Message]:
    """`decode(d)` for whole little-endian payloads with the header check inlined (one call
    per message on the subscription hot path); anything unusual goes to `slow`, which gives
    the precise error or handles big-endian and bad UTF-8."""
    gen, v = _des_body(name, reg, True, False, 2, header=True)
    gen.ns['_slow'] = slow
    src = '\n'.join(
        [
            'def decode(d):',
            '    try:',
            '        o = 0',
            *gen.lines,
            '    except Exception:',
            '        return _slow(d)',
            f'    return {v} if o <= len(d) else _slow(d)',
        ]
    )
    exec(compile(src, f'<cdr decode {name}>', 'exec'), gen.ns)
    fn: Callable[[bytes], Message] = gen.ns['decode']
    fn.__doc__ = src
    return fn
