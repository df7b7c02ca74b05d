"""The machinery under rclpy's face: scheduling, delivery, the node as its parts see it.
Not API: names here may change between releases."""
