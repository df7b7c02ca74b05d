"""What the keyboard teleop demos share: reading keys from a terminal, and spinning a node on
a thread of its own while the main thread reads them."""
