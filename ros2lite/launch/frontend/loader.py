"""Reading XML and YAML launch files into launch descriptions."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from ros2lite.util.files import read_bounded
from ros2lite.util.safe_yaml import YamlInputError, load

from ..actions import LaunchDescription
from ..errors import InvalidFrontendLaunchFileError
from ..sources import FRONTEND_EXTENSIONS
from .builders import build_all
from .entity import XmlEntity, yaml_root

__all__ = ['FRONTEND_EXTENSIONS', 'load_frontend_file']

_MAX_BYTES = 4 << 20


def load_frontend_file(path: Path, kind: str | None = None) -> LaunchDescription:
    """The launch description of an XML or YAML launch file (`kind` 'xml'/'yaml', else by
    extension)."""
    kind = kind or FRONTEND_EXTENSIONS.get(path.suffix.lower())
    where = str(path)
    data = read_bounded(path, _MAX_BYTES, InvalidFrontendLaunchFileError, 'a launch file')
    if kind == 'xml':
        try:
            root = ET.fromstring(data)
        except ET.ParseError as e:
            raise InvalidFrontendLaunchFileError(f'{where}: not valid XML ({e})') from None
        if root.tag != 'launch':
            raise InvalidFrontendLaunchFileError(
                f'{where}: the root element is <{root.tag}>, not <launch>'
            )
        entities = XmlEntity(root, where).children()
    elif kind == 'yaml':
        try:
            document = load(data.decode('utf-8'), where)
        except UnicodeDecodeError:
            raise InvalidFrontendLaunchFileError(f'{where}: not UTF-8 text') from None
        except YamlInputError as e:
            raise InvalidFrontendLaunchFileError(str(e)) from None
        entities = yaml_root(document, where)
    else:
        raise InvalidFrontendLaunchFileError(f'{where}: not an XML or YAML launch file')
    description = LaunchDescription(build_all(entities))
    description.source_path = str(path.resolve())
    return description
