"""sros2 policies: loading (XInclude, checks), writing in sros2's order, and the DDS
permissions made from them."""

from __future__ import annotations

import datetime
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from ros2lite.security.errors import PolicyError
from ros2lite.security.permissions import parse_permissions, permissions_xml
from ros2lite.security.policy import (
    NodeAccess,
    add_node_access,
    dump_policy,
    load_policy,
    new_policy,
    policy_for_enclave,
)

COMMON = """<?xml version="1.0" encoding="UTF-8"?>
<profile>
  <services reply="ALLOW">
    <service>~/get_parameters</service>
  </services>
</profile>
"""

POLICY = """<?xml version="1.0" encoding="UTF-8"?>
<policy version="0.2.0" xmlns:xi="http://www.w3.org/2001/XInclude">
  <enclaves>
    <enclave path="/demo/talker">
      <profiles>
        <profile ns="/robot" node="talker">
          <xi:include href="common/node.xml" xpointer="xpointer(/profile/*)"/>
          <topics publish="ALLOW"><topic>chatter</topic><topic>/abs</topic></topics>
          <topics publish="DENY"><topic>secret</topic></topics>
          <actions call="ALLOW"><action>fib</action></actions>
        </profile>
      </profiles>
    </enclave>
  </enclaves>
</policy>
"""


@pytest.fixture
def policy_file(tmp_path: Path) -> Path:
    (tmp_path / 'common').mkdir()
    (tmp_path / 'common' / 'node.xml').write_text(COMMON)
    path = tmp_path / 'policy.xml'
    path.write_text(POLICY)
    return path


def test_include_and_permissions(policy_file: Path) -> None:
    policy = policy_for_enclave(load_policy(policy_file), '/demo/talker')
    when = datetime.datetime(2030, 1, 1, tzinfo=datetime.timezone.utc)
    document = permissions_xml(policy, 7, when, when.replace(year=2040))
    root = ET.fromstring(document)
    grant = root.find('permissions/grant')
    assert grant is not None and grant.get('name') == '/demo/talker'
    assert grant.findtext('subject_name') == 'CN=/demo/talker'
    assert grant.findtext('validity/not_before') == '2030-01-01T00:00:00+00:00'
    assert [e.tag for e in grant] == [
        'subject_name',
        'validity',
        'deny_rule',
        'allow_rule',
        'default',
    ]
    deny = [t.text for t in grant.findall('deny_rule/publish/topics/topic')]
    assert deny == ['rt/robot/secret']
    allow_pub = [t.text for t in grant.findall('allow_rule/publish/topics/topic')]
    # blocks ordered by their first name, each in its own order, as the XSL sorts them
    assert allow_pub == [
        'rq/robot/fib/_action/cancel_goalRequest',
        'rq/robot/fib/_action/get_resultRequest',
        'rq/robot/fib/_action/send_goalRequest',
        'rr/robot/talker/get_parametersReply',
        'rt/robot/chatter',
        'rt/abs',
    ]
    allow_sub = [t.text for t in grant.findall('allow_rule/subscribe/topics/topic')]
    assert 'rq/robot/talker/get_parametersRequest' in allow_sub
    assert 'rt/robot/fib/_action/status' in allow_sub
    assert grant.findtext('allow_rule/domains/id') == '7'
    assert grant.findtext('default') == 'DENY'
    # and read back as the router does
    (parsed,) = parse_permissions(document, 'test')
    assert parsed.common_name == '/demo/talker'
    assert [r.allow for r in parsed.rules] == [False, True]
    assert parsed.valid_at(when) and not parsed.valid_at(when.replace(year=2041))


def test_dump_orders_as_sros2() -> None:
    policy = new_policy()
    add_node_access(
        policy,
        [
            NodeAccess('talker', '/', '/b', publishes=['/rosout', '/chatter', '/chatter']),
            NodeAccess(
                'listener',
                '/ns',
                '/a',
                subscribes=['/ns/chatter', '/x/y'],
                serves=['/ns/listener/get_parameters'],
            ),
        ],
    )
    assert dump_policy(policy) == (
        '<policy version="0.2.0">\n'
        '  <enclaves>\n'
        '    <enclave path="/a">\n'
        '      <profiles>\n'
        '        <profile node="listener" ns="/ns">\n'
        '          <services reply="ALLOW">\n'
        '            <service>~/get_parameters</service>\n'
        '          </services>\n'
        '          <topics subscribe="ALLOW">\n'
        '            <topic>/x/y</topic>\n'
        '            <topic>chatter</topic>\n'
        '          </topics>\n'
        '        </profile>\n'
        '      </profiles>\n'
        '    </enclave>\n'
        '    <enclave path="/b">\n'
        '      <profiles>\n'
        '        <profile node="talker" ns="/">\n'
        '          <topics publish="ALLOW">\n'
        '            <topic>chatter</topic>\n'
        '            <topic>rosout</topic>\n'
        '          </topics>\n'
        '        </profile>\n'
        '      </profiles>\n'
        '    </enclave>\n'
        '  </enclaves>\n'
        '</policy>\n'
    )


@pytest.mark.parametrize(
    ('text', 'why'),
    [
        ('<nope/>', 'the root element is <nope>'),
        (
            '<policy version="0.2.0"><enclaves><enclave path="x"/></enclaves></policy>',
            'not a valid enclave name',
        ),
        (
            '<policy version="0.2.0"><enclaves><enclave path="/x"><profiles><profile ns="/" '
            'node="n"><topics publish="MAYBE"><topic>t</topic></topics></profile></profiles>'
            '</enclave></enclaves></policy>',
            'must be ALLOW or DENY',
        ),
        (
            '<policy version="0.2.0"><enclaves><enclave path="/x"><profiles><profile ns="/" '
            'node="n"><topics publish="ALLOW"><topic>a b</topic></topics></profile></profiles>'
            '</enclave></enclaves></policy>',
            "bad <topic> 'a b'",
        ),
        ('<!DOCTYPE p [<!ENTITY a "b">]><policy/>', 'DTDs and entities are not accepted'),
        ('<policy', 'not well-formed XML'),
        (
            '<policy version="1" xmlns:xi="http://www.w3.org/2001/XInclude"><enclaves>'
            '<xi:include href="http://example.com/x.xml"/></enclaves></policy>',
            'relative file href',
        ),
    ],
)
def test_bad_policies_are_one_line(tmp_path: Path, text: str, why: str) -> None:
    path = tmp_path / 'bad.xml'
    path.write_text(text)
    with pytest.raises(PolicyError) as info:
        load_policy(path)
    message = str(info.value)
    assert why in message and str(path) in message and '\n' not in message


def test_generate_artifacts_from_policy(policy_file: Path, tmp_path: Path, run: object) -> None:
    keystore = tmp_path / 'ks'
    result = run(
        'security',
        'generate_artifacts',
        '-k',
        str(keystore),
        '-e',
        '/extra',  # type: ignore[operator]
        '-p',
        str(policy_file),
    )
    assert result.code == 0, result.err
    assert result.out == f'{keystore} is not a valid keystore, creating new keystore\n'
    assert run('security', 'list_enclaves', str(keystore)).out == '/demo/talker\n/extra\n'  # type: ignore[operator]
    permissions = (keystore / 'enclaves/demo/talker/permissions.xml').read_text()
    assert '<topic>rt/robot/chatter</topic>' in permissions
    assert '<topic>rt/*</topic>' in (keystore / 'enclaves/extra/permissions.xml').read_text()
