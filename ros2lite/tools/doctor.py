"""`doctor`: checks of a ros2lite setup and the reports behind them (ros2doctor's shape).

Six checks, each a *category* (what ``Failed modules:`` names):

- ``platform`` — an operating system ros2lite is tested on, and a `python3` on PATH that
  can import ros2lite;
- ``network`` — a Zenoh router answers at the endpoint every session uses;
- ``middleware`` — ``ROS_DOMAIN_ID``, the ``ZENOH_*`` variables and ``RMW_IMPLEMENTATION``
  make a valid session configuration that talks to rmw_zenoh nodes;
- ``topic`` — one-sided topics and nodes of rmw_zenoh 0.2.0-0.2.2 are warnings; endpoints
  disagreeing on the type or its RIHS01 hash are errors (rmw_zenoh keys data by both);
- ``qos`` — pairs rmw_zenoh's QoS rule calls incompatible (none: the report shows its warning);
- ``package`` — source workspace packages colcon would refuse are errors, each one line with
  file and line: a package.xml that is not XML or lacks a name, version or build type; a
  setup.py that is not Python, calls no `setup()` or has an entry point that does not parse;
  a `.msg`/`.srv`/`.action` that does not parse. A C++ package is a warning (it is not
  broken, but ros2lite will not run it).

The graph is read once, from the router (the daemon is never started by a diagnosis). A
finding remembers the file and line that raised it, as ros2doctor's Python warnings do.

`doctor hello` (:class:`Hello`) checks two hosts can talk: each publishes and multicasts a
hello naming its host and counts the hellos of other hosts, by topic and by multicast.
"""

from __future__ import annotations

import contextlib
import os
import platform
import socket
import sys
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import ros2lite
from ros2lite.util.domain import DDS_MAX_DOMAIN_ID

if TYPE_CHECKING:
    from ros2lite.daemon.control import DaemonStatus
    from ros2lite.graph import Entity
    from ros2lite.qos import Compatibility

__all__ = [
    'CATEGORIES',
    'CheckResult',
    'Diagnosis',
    'Finding',
    'Report',
]

CATEGORIES = ('platform', 'network', 'middleware', 'topic', 'qos', 'package')
_QUIET_TOPICS = ('/parameter_events', '/rosout')  # every node has them; not worth a warning
_GRAPH_TIMEOUT = 3.0


@dataclass(frozen=True)
class Finding:
    """A warning or an error, with where in ros2lite it was found."""

    severity: str  # 'warning' or 'error'
    message: str
    filename: str
    lineno: int


@dataclass
class CheckResult:
    """The findings of one check category (`doctor` prints them; errors make it fail)."""

    category: str
    findings: list[Finding] = field(default_factory=list)

    @property
    def errors(self) -> list[Finding]:
        """The findings of severity 'error'."""
        return [f for f in self.findings if f.severity == 'error']

    @property
    def warnings(self) -> list[Finding]:
        """The findings of severity 'warning'."""
        return [f for f in self.findings if f.severity == 'warning']

    def failed(self, include_warnings: bool = False) -> bool:
        """Whether the check failed: any error, or any warning when `include_warnings`."""
        return bool(self.errors or (include_warnings and self.warnings))

    def _add(self, severity: str, message: str) -> None:
        frame = sys._getframe(2)
        self.findings.append(Finding(severity, message, frame.f_code.co_filename, frame.f_lineno))

    def warn(self, message: str) -> None:
        """Record a warning, with the file and line that raised it."""
        self._add('warning', message)

    def error(self, message: str) -> None:
        """Record an error, with the file and line that raised it."""
        self._add('error', message)


@dataclass
class Report:
    """A titled list of key/value lines (`doctor --report`)."""

    name: str
    category: str
    items: list[tuple[str, str]] = field(default_factory=list)

    def add(self, key: str, value: object) -> None:
        """Add a line; the value is shown as text."""
        self.items.append((key, str(value)))


def _version(dist: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(dist)
    except PackageNotFoundError:
        return 'not installed'


class Diagnosis:
    """One look at this setup; facts are gathered once and shared by checks and reports."""

    def __init__(self, *, router: str | None = None, env: dict[str, str] | None = None) -> None:
        self.router = router
        self.env = dict(os.environ if env is None else env)
        self._status: DaemonStatus | None = None
        self._endpoint: str | None = None
        self._endpoint_error: str | None = None
        self._graph: list[Entity] | None = None
        self._graph_error: str | None = None
        self._graph_read = False

    # -- facts -----------------------------------------------------------------------------------
    def endpoint(self) -> str | None:
        """The router endpoint to check (None when the configuration is invalid)."""
        if self._endpoint is None and self._endpoint_error is None:
            from ros2lite.daemon.security import secured_endpoint
            from ros2lite.transport.errors import ConfigError

            try:
                self._endpoint = secured_endpoint(self.router, self.env)
            except ConfigError as e:
                self._endpoint_error = str(e)
        return self._endpoint

    def router_status(self) -> DaemonStatus | None:
        """The daemon module's status of the endpoint (None when the endpoint is invalid)."""
        if self._status is None and self.endpoint() is not None:
            from ros2lite import daemon
            from ros2lite.exceptions import Ros2liteError

            try:
                self._status = daemon.status(self.endpoint(), sessions=True)
            except Ros2liteError:  # e.g. a bad ROS_DOMAIN_ID: the middleware check says so
                self._status = daemon.status(self.endpoint())
        return self._status

    def graph(self) -> list[Entity] | None:
        """Every entity of the domain, or None (see :attr:`graph_error`)."""
        if not self._graph_read:
            self._graph_read = True
            status = self.router_status()
            if status is None or not status.running:
                self._graph_error = 'no Zenoh router answers'
                return None
            from ros2lite.exceptions import Ros2liteError
            from ros2lite.tools.connection import Connection

            try:
                with Connection(router=self.router, autostart=False) as conn:
                    self._graph = conn.entities(timeout=_GRAPH_TIMEOUT)
            except Ros2liteError as e:
                self._graph_error = str(e)
        return self._graph

    @property
    def graph_error(self) -> str | None:
        """Why the graph could not be read (None when it was, or was not tried)."""
        return self._graph_error

    def _topics(self) -> dict[str, list[Entity]]:
        from ros2lite.graph import EntityKind
        from ros2lite.names import is_hidden_name

        topics: dict[str, list[Entity]] = {}
        for e in self.graph() or []:
            endpoint = e.kind in (EntityKind.PUBLISHER, EntityKind.SUBSCRIPTION)
            if endpoint and e.topic_name and not is_hidden_name(e.topic_name):
                topics.setdefault(e.topic_name, []).append(e)
        return dict(sorted(topics.items()))

    # -- checks ----------------------------------------------------------------------------------
    def check_platform(self) -> CheckResult:
        """Warn about an untested platform, or a python3 on PATH that cannot import ros2lite."""
        import shutil

        result = CheckResult('platform')
        if platform.system() not in ('Linux', 'Darwin'):
            result.warn(f'{platform.system()} is not a platform ros2lite is tested on')
        python3 = shutil.which('python3', path=self.env.get('PATH'))
        if python3 is not None and os.path.realpath(python3) != os.path.realpath(sys.executable):
            import subprocess

            try:
                found = (
                    subprocess.run(
                        [python3, '-c', 'import ros2lite'], capture_output=True, timeout=10
                    ).returncode
                    == 0
                )
            except (OSError, subprocess.SubprocessError):
                found = False
            if not found:
                result.warn(
                    f'python3 on PATH ({python3}) cannot import ros2lite, which runs in '
                    f'{sys.executable}: scripts started as `python3 script.py` will not find '
                    'it (use `ros2lite run`, or that interpreter)'
                )
        return result

    def check_network(self) -> CheckResult:
        """Check that the router endpoint is valid and reachable."""
        result = CheckResult('network')
        if self._endpoint_error is not None or self.endpoint() is None:
            result.error(f'the router endpoint is invalid: {self._endpoint_error}')
            return result
        status = self.router_status()
        assert status is not None  # the endpoint is valid
        if not status.running:
            if status.ours:
                result.error(
                    f'the ros2lite daemon (pid {status.pid}) does not answer at {status.endpoint}'
                )
            else:
                result.error(
                    f'No Zenoh router answers at {status.endpoint}: start one with '
                    '`ros2lite daemon start` (or rmw_zenohd)'
                )
        return result

    def check_middleware(self) -> CheckResult:
        """Check the Zenoh session configuration and that RMW_IMPLEMENTATION is rmw_zenoh_cpp."""
        from ros2lite.transport.config import domain_id, router_check_attempts, session_config
        from ros2lite.transport.errors import ConfigError

        result = CheckResult('middleware')
        for read_setting in (domain_id, router_check_attempts):
            try:
                read_setting(self.env)
            except ConfigError as e:
                result.error(str(e))
        raw = self.env.get('ROS_DOMAIN_ID', '')
        with contextlib.suppress(ConfigError):
            domain = domain_id(self.env)
            if domain > DDS_MAX_DOMAIN_ID:
                result.warn(
                    f'ROS_DOMAIN_ID {raw!r} is domain {domain}: rmw_zenoh nodes join it, but '
                    f'DDS-based ROS 2 nodes only reach domains 0..{DDS_MAX_DOMAIN_ID}'
                )
            elif raw.strip() and raw.strip() != str(domain):
                result.warn(
                    f'ROS_DOMAIN_ID {raw!r} reads as domain {domain} (as rcl reads it: '
                    'a leading 0 is octal, 0x hex, and what follows the number is ignored)'
                )
        if self.endpoint() is not None:
            try:
                session_config(self.router, self.env, mode='peer')
            except ConfigError as e:
                result.error(f'the Zenoh session configuration is invalid: {e}')
        rmw = self.env.get('RMW_IMPLEMENTATION', '')
        if rmw and rmw != 'rmw_zenoh_cpp':
            result.warn(
                f'RMW_IMPLEMENTATION is {rmw}: ROS 2 nodes started from this shell will not '
                'see ros2lite nodes (ros2lite speaks rmw_zenoh_cpp)'
            )
        return result

    def check_topic(self) -> CheckResult:
        """Warn about one-sided topics and old peers; report type and type hash mismatches."""
        from ros2lite.graph import OLD_RMW_ZENOH, EntityKind, old_rmw_zenoh_nodes

        result = CheckResult('topic')
        if self.graph() is None:
            result.warn(f'topics not checked: {self.graph_error}')
            return result
        for name in old_rmw_zenoh_nodes(self.graph() or []):
            result.warn(f'node {name}: {OLD_RMW_ZENOH}')
        for topic, endpoints in self._topics().items():
            pubs = [e for e in endpoints if e.kind == EntityKind.PUBLISHER]
            subs = [e for e in endpoints if e.kind == EntityKind.SUBSCRIPTION]
            if topic not in _QUIET_TOPICS:
                if pubs and not subs:
                    result.warn(f'Publisher without subscriber detected on {topic}.')
                elif subs and not pubs:
                    result.warn(f'Subscriber without publisher detected on {topic}.')
            types = sorted({e.type_name or '?' for e in endpoints})
            if len(types) > 1:
                result.error(
                    f'Type mismatch on {topic}: '
                    + ', '.join(f'{t} ({_who(endpoints, type_name=t)})' for t in types)
                )
                continue
            hashes = sorted({e.type_hash or '?' for e in endpoints})
            if len(hashes) > 1:
                result.error(
                    f'Type hash mismatch on {topic} ({types[0]}): '
                    + ', '.join(f'{h} ({_who(endpoints, type_hash=h)})' for h in hashes)
                    + '; these endpoints never exchange a message'
                )
        return result

    def check_qos(self) -> CheckResult:
        """Warn about publisher/subscriber pairs whose QoS cannot connect."""
        result = CheckResult('qos')
        if self.graph() is None:
            result.warn(f'QoS not checked: {self.graph_error}')
            return result
        for topic, pub, sub, compat in self._pairs():
            if not compat.compatible:
                result.warn(
                    f'QoS incompatibility on {topic}: publisher {_node(pub)}, subscription '
                    f'{_node(sub)}: {compat.reason}'
                )
        return result

    def check_package(self) -> CheckResult:
        """Fail on workspace packages whose files colcon would refuse; warn about C++ ones."""
        from ros2lite.interfaces.errors import InterfaceError
        from ros2lite.interfaces.registry import Registry
        from ros2lite.pkg.errors import NotHereError, PackageFileError
        from ros2lite.pkg.executables import package_executables
        from ros2lite.pkg.index import ORIGIN_WORKSPACE, PackageIndex

        result = CheckResult('package')
        index = PackageIndex(self.env)
        workspace_packages = index.packages_from(ORIGIN_WORKSPACE)
        for problem in index.problems:
            result.error(f'workspace package skipped: {problem}')
        registry = Registry()
        for name, pkg in workspace_packages.items():
            try:
                package_executables(pkg)
            except PackageFileError as e:
                result.error(f'workspace package {name}: {e}')
            except NotHereError as e:
                result.warn(str(e))
            if pkg.interfaces is None or index.find(name) is not pkg:
                continue
            for interface in registry.package_interfaces(name):
                try:
                    if '/srv/' in interface:
                        registry.service(interface)
                    elif '/action/' in interface:
                        registry.action(interface)
                    else:
                        registry.message(interface)
                except InterfaceError as e:
                    result.error(f'workspace package {name}: {e}')
        return result

    def _pairs(self) -> list[tuple[str, Entity, Entity, Compatibility]]:
        from ros2lite.graph import EntityKind
        from ros2lite.qos import zenoh_check_compatible as check_compatible

        pairs = []
        for topic, endpoints in self._topics().items():
            pubs = [e for e in endpoints if e.kind == EntityKind.PUBLISHER and e.qos]
            subs = [e for e in endpoints if e.kind == EntityKind.SUBSCRIPTION and e.qos]
            for pub in pubs:
                for sub in subs:
                    assert pub.qos is not None and sub.qos is not None
                    pairs.append((topic, pub, sub, check_compatible(pub.qos, sub.qos)))
        return pairs

    def run_checks(self, *, exclude: tuple[str, ...] = ()) -> list[CheckResult]:
        """Every check not excluded, in CATEGORIES order."""
        checks = {
            'platform': self.check_platform,
            'network': self.check_network,
            'middleware': self.check_middleware,
            'topic': self.check_topic,
            'qos': self.check_qos,
            'package': self.check_package,
        }
        return [checks[c]() for c in CATEGORIES if c not in exclude]

    # -- reports ---------------------------------------------------------------------------------
    def reports(self, categories: set[str] | None = None) -> list[Report]:
        """The reports (of `categories` only, when given), in ros2doctor's order."""
        makers = [
            ('platform', self._report_platform),
            ('platform', self._report_ros2lite),
            ('network', self._report_network),
            ('middleware', self._report_middleware),
            ('topic', self._report_topics),
            ('qos', self._report_qos),
            ('package', self._report_packages),
        ]
        return [make() for cat, make in makers if categories is None or cat in categories]

    def _report_platform(self) -> Report:
        r = Report('PLATFORM INFORMATION', 'platform')
        r.add('system', platform.system())
        r.add('platform info', platform.platform())
        r.add('release', platform.release())
        r.add('processor', platform.processor() or platform.machine())
        r.add('python version', platform.python_version())
        r.add('python executable', sys.executable)
        return r

    def _report_ros2lite(self) -> Report:
        from ros2lite.pkg.index import PackageIndex

        r = Report('ROS2LITE INFORMATION', 'platform')
        r.add('ros2lite version', _version('ros2lite'))
        # the directory holding the package, wherever this module sits inside it
        r.add('installed at', os.path.dirname(os.path.dirname(os.path.abspath(ros2lite.__file__))))
        r.add('middleware', 'rmw_zenoh_cpp (wire-compatible)')
        workspaces = PackageIndex(self.env).workspaces()
        r.add('source workspaces', ', '.join(map(str, workspaces)) or 'none')
        r.add('AMENT_PREFIX_PATH', self.env.get('AMENT_PREFIX_PATH') or 'not set')
        return r

    def _report_network(self) -> Report:
        r = Report('NETWORK CONFIGURATION', 'network')
        r.add('router endpoint', self.endpoint() or f'invalid ({self._endpoint_error})')
        status = self.router_status()
        if status is not None:
            r.add('router answers', 'yes' if status.running else 'no')
            if status.running and status.ours:
                r.add('router', f'ros2lite daemon (pid {status.pid})')
                if status.info is not None and status.info.listen:
                    r.add('router listens on', ', '.join(status.info.listen))
            elif status.running:
                r.add('router', 'a Zenoh router not started by ros2lite (e.g. rmw_zenohd)')
            if status.sessions is not None:
                r.add('connected sessions', len(status.sessions))
        try:
            names = [name for _index, name in socket.if_nameindex()]
        except OSError:
            names = []
        r.add('interfaces', ', '.join(names) or 'unknown')
        r.add('hostname', socket.gethostname())
        return r

    def _report_middleware(self) -> Report:
        r = Report('RMW MIDDLEWARE', 'middleware')
        r.add('middleware name', 'rmw_zenoh_cpp')
        r.add('zenoh version', _version('eclipse-zenoh'))
        r.add('ROS_DOMAIN_ID', self.env.get('ROS_DOMAIN_ID') or '0 (not set)')
        for name in (
            'RMW_IMPLEMENTATION',
            'ZENOH_CONFIG_OVERRIDE',
            'ZENOH_SESSION_CONFIG_URI',
            'ZENOH_ROUTER_CONFIG_URI',
            'ZENOH_ROUTER_CHECK_ATTEMPTS',
            'ROS2LITE_ROUTER',
        ):
            r.add(name, self.env.get(name) or 'not set')
        return r

    def _report_topics(self) -> Report:
        from ros2lite.graph import EntityKind

        r = Report('TOPIC LIST', 'topic')
        if self.graph() is None:
            r.add('topic', f'unknown ({self.graph_error})')
            return r
        topics = self._topics()
        if not topics:
            r.add('topic', 'none')
        for topic, endpoints in topics.items():
            r.add('topic', topic)
            r.add('publisher count', sum(e.kind == EntityKind.PUBLISHER for e in endpoints))
            r.add('subscriber count', sum(e.kind == EntityKind.SUBSCRIPTION for e in endpoints))
        return r

    def _report_qos(self) -> Report:
        r = Report('QOS COMPATIBILITY LIST', 'qos')
        if self.graph() is None:
            r.add('compatibility status', f'unknown ({self.graph_error})')
            return r
        pairs = self._pairs()
        if not pairs:
            r.add('compatibility status', 'No publisher/subscriber pairs found')
        for topic, pub, sub, compat in pairs:
            r.add('topic [type]', f'{topic} [{pub.type_name}]')
            r.add('publisher node', _node(pub))
            r.add('subscriber node', _node(sub))
            status = 'OK' if compat.compatible and not compat.reason else compat.reason
            r.add('compatibility status', status)
        return r

    def _report_packages(self) -> Report:
        r = Report('PACKAGE VERSIONS', 'package')
        for dist in ('ros2lite', 'eclipse-zenoh', 'click', 'rich', 'pyyaml', 'mcap', 'xxhash'):
            r.add(dist, _version(dist))
        return r


def _node(e: Entity) -> str:
    ns = e.namespace if e.namespace.endswith('/') else e.namespace + '/'
    return f'{ns}{e.node_name}'


def _who(endpoints: list[Entity], **match: str) -> str:
    names = sorted(
        {_node(e) for e in endpoints if all((getattr(e, k) or '?') == v for k, v in match.items())}
    )
    return ', '.join(names)
