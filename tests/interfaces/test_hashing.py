"""RIHS01 hashes against the table made with the official rosidl generator."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from ros2lite.interfaces import type_hash
from ros2lite.interfaces.hashing import type_description

# a copy of the project reference table (shared/reference/rihs01_jazzy.json), kept with the
# tests so a clean clone checks every hash instead of skipping
TABLE_PATH = Path(__file__).resolve().parent / 'data' / 'rihs01_jazzy.json'


def load_table() -> dict[str, str]:
    table: dict[str, str] = json.loads(TABLE_PATH.read_text())
    return table


def test_all_410_reference_hashes_match() -> None:
    table = load_table()
    assert len(table) == 410
    wrong = {name: type_hash(name) for name in table if type_hash(name) != table[name]}
    assert wrong == {}


@pytest.mark.parametrize(
    ('name', 'expected'),
    [
        (
            'std_msgs/msg/String',
            'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18',
        ),
        (
            'example_interfaces/srv/AddTwoInts',
            'RIHS01_e118de6bf5eeb66a2491b5bda11202e7b68f198d6f67922cf30364858239c81a',
        ),
    ],
)
def test_published_hashes(name: str, expected: str) -> None:
    # the two values quoted by rmw_zenoh's design document; no table needed
    assert type_hash(name) == expected


def test_nav_msgs_goals_is_bundled_as_jazzy_has_it() -> None:
    # added to Jazzy's nav_msgs (5.3.6) after the reference table was made; the value is the
    # one in that release's share/nav_msgs/msg/Goals.json
    assert type_hash('nav_msgs/msg/Goals') == (
        'RIHS01_02305a51633b5c04d8979b878a7577cafd422f8a07465c878b17a920af3759e9'
    )


def test_short_message_name_is_accepted() -> None:
    assert type_hash('std_msgs/String') == type_hash('std_msgs/msg/String')


def test_description_of_service_lists_sorted_references() -> None:
    d = type_description('example_interfaces/srv/AddTwoInts')
    assert [f['name'] for f in d['type_description']['fields']] == [
        'request_message',
        'response_message',
        'event_message',
    ]
    names = [r['type_name'] for r in d['referenced_type_descriptions']]
    assert (
        names
        == sorted(names)
        == [
            'builtin_interfaces/msg/Time',
            'example_interfaces/srv/AddTwoInts_Event',
            'example_interfaces/srv/AddTwoInts_Request',
            'example_interfaces/srv/AddTwoInts_Response',
            'service_msgs/msg/ServiceEventInfo',
        ]
    )


def test_char_maps_to_uint8_and_empty_struct_gets_dummy() -> None:
    char = type_description('std_msgs/msg/Char')['type_description']['fields'][0]
    assert char['type']['type_id'] == 3
    empty = type_description('std_msgs/msg/Empty')['type_description']['fields']
    assert empty == [
        {
            'name': 'structure_needs_at_least_one_member',
            'type': {'type_id': 3, 'capacity': 0, 'string_capacity': 0, 'nested_type_name': ''},
        }
    ]


def test_rosbags_agrees_on_ordinary_messages() -> None:
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.ROS2_JAZZY)
    for name in ('geometry_msgs/msg/Twist', 'sensor_msgs/msg/Imu', 'tf2_msgs/msg/TFMessage'):
        assert store.hash_rihs01(name) == type_hash(name)


def test_each_registry_hashes_its_own_definitions(tmp_path: Path) -> None:
    """A registry made after another one was dropped (as reload_registry does) must not be
    handed the hashes of the old definitions, whatever id() the new object gets."""
    from ros2lite.interfaces.hashing import type_hash as hash_in
    from ros2lite.interfaces.registry import Registry

    versions = ('uint8 years\n', 'uint8 years\nuint8 months\n', 'uint16 years\n')
    seen = set()
    for i, fields in enumerate(versions * 2):
        msg = tmp_path / str(i) / 'lesson_msgs' / 'msg'
        msg.mkdir(parents=True)
        (msg / 'Age.msg').write_text(fields)
        # each registry is dropped at once: the next one may well get the same id()
        seen.add((fields, hash_in('lesson_msgs/msg/Age', Registry([tmp_path / str(i)]))))
    assert len(seen) == 3  # one hash per definition, the same each time
    assert len({h for _, h in seen}) == 3


def test_kilted_hashes_equal_jazzys() -> None:
    """`ROS_DISTRO=kilted` changes names, not the wire: the hashes in Kilted's own type
    descriptions (the `.json` files of the ros-kilted-{std,geometry,sensor}-msgs and
    builtin-interfaces wheels, 5.5.1/2.3.0) are Jazzy's and ours."""
    kilted = json.loads((TABLE_PATH.parent / 'rihs01_kilted_core.json').read_text())
    assert len(kilted) == 96
    jazzy = load_table()
    assert {name: jazzy[name] for name in kilted} == kilted
    assert {name: type_hash(name) for name in kilted} == kilted
