"""The JSON form (`--json`): a message to JSON text and JSON text to a message, against the
YAML text `topic echo` prints and `topic pub` reads for the same message (the baseline)."""

from __future__ import annotations

import json

from bench_interfaces import sample_messages
from common import rate, report


def bench_json() -> None:
    from ros2lite.interfaces import message_to_yaml, set_message_fields
    from ros2lite.interfaces.json_form import dumps, json_to_message, message_to_json

    for name, msg in sample_messages().items():
        short = name.rsplit('/', 1)[1]
        out = rate(lambda m=msg: dumps(message_to_json(m)))
        base = rate(lambda m=msg: message_to_yaml(m))
        report(f'json_out_{short}', out, 'msg/s', out / base)
        text = dumps(message_to_json(msg))
        cls = type(msg)
        yaml_text = message_to_yaml(msg)
        back = rate(lambda t=text, c=cls: json_to_message(c, json.loads(t)))
        if short == 'Image':  # PyYAML reads its 921,600 numbers in tens of seconds
            report(f'json_in_{short}', back, 'msg/s', 0.0)
            continue
        base_in = rate(lambda y=yaml_text, c=cls: set_message_fields(c(), y), repeats=2)
        report(f'json_in_{short}', back, 'msg/s', back / base_in)


BENCHES = {'json': bench_json}
