"""Watching topics from outside, for the CLI and scripts: one topic's type, QoS and arrivals
(topic), subscriptions that hand over raw arrivals (subscription), and the statistics behind
`topic hz/bw/delay` (stats)."""
