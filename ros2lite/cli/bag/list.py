"""`bag list`: the storage plugins and compressors this ros2lite has, as ros2cli lists them."""

from __future__ import annotations

import click

from ..options import json_option
from ..parsing import command
from ..render import print_json

# plugin kind → [(name, description, type, base class)], pluginlib's fields
PLUGINS: dict[str, list[tuple[str, str, str, str]]] = {
    "storage": [
        (
            "mcap",
            "Plugin to write to and read from MCAP files",
            "rosbag2_storage_plugins::MCAPStorage",
            "rosbag2_storage::storage_interfaces::ReadWriteInterface",
        ),
        (
            "sqlite3",
            "Plugin to read sqlite3 (.db3) bags",
            "rosbag2_storage_plugins::SqliteStorage",
            "rosbag2_storage::storage_interfaces::ReadWriteInterface",
        ),
        (
            "rosbag1",
            "Plugin to read ROS 1 (.bag) bags, as ROS 2 messages (needs rosbags)",
            "ros2lite::Rosbag1Storage",
            "rosbag2_storage::storage_interfaces::ReadOnlyInterface",
        ),
    ],
    "converter": [],
    "compressor": [
        (
            "zstd",
            "zstd compression of MCAP chunks",
            "rosbag2_compression_zstd::ZstdCompressor",
            "rosbag2_compression::BaseCompressorInterface",
        ),
    ],
    "decompressor": [
        (
            "zstd",
            "zstd decompression of MCAP chunks",
            "rosbag2_compression_zstd::ZstdDecompressor",
            "rosbag2_compression::BaseDecompressorInterface",
        ),
    ],
}


@command("list")
@click.argument("plugin_type", type=click.Choice(list(PLUGINS)))
@click.option("-v", "--verbose", is_flag=True, help="List out verbose information.")
@json_option('[{"name", "description", "type", "base_class"}…]')
def cli(plugin_type: str, verbose: bool, as_json: bool) -> None:
    """Print information about available plugins to the screen."""
    if as_json:
        print_json(
            [
                {"name": n, "description": d, "type": t, "base_class": b}
                for n, d, t, b in PLUGINS[plugin_type]
            ]
        )
        return
    for name, description, type_name, base in PLUGINS[plugin_type]:
        if verbose:
            click.echo(
                f"name: {name}\n\tdescription: {description}\n\ttype: {type_name}"
                f"\n\tbase_class: {base}"
            )
        else:
            click.echo(name)
