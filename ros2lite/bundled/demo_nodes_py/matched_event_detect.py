"""`matched_event_detect`: matched events shown step by step. Node
`matched_event_detection_node` publishes `pub_topic_matched_event_detect` and subscribes to
`sub_topic_matched_event_detect`, logging each change in what it is matched with, while
`multi_sub_node` adds and removes two subscriptions of the first topic, then
`multi_pub_node` two publishers of the second. Each step waits at most 10 s for its event."""

from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import ros2lite
from ros2lite.bundled.runner import run_main
from ros2lite.event_handler import (
    PublisherEventCallbacks,
    QoSPublisherMatchedInfo,
    QoSSubscriptionMatchedInfo,
    SubscriptionEventCallbacks,
)
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node
from ros2lite.publisher import Publisher
from ros2lite.subscription import Subscription
from ros2lite.task import Future

PUB_TOPIC = 'pub_topic_matched_event_detect'
_Made = TypeVar('_Made')
SUB_TOPIC = 'sub_topic_matched_event_detect'
STEP_TIMEOUT = 10.0


class MatchedEventDetectNode(Node):
    """Logs how its publisher's subscriptions and its subscription's publishers come and go."""

    def __init__(self, pub_topic: str, sub_topic: str) -> None:
        super().__init__('matched_event_detection_node')
        self.any_subscription = False
        self.any_publisher = False
        self.future: Future[bool] = Future()
        self.pub = self.create_publisher(
            String, pub_topic, 10, event_callbacks=PublisherEventCallbacks(matched=self.on_pub)
        )
        self.sub = self.create_subscription(
            String,
            sub_topic,
            lambda msg: None,
            10,
            event_callbacks=SubscriptionEventCallbacks(matched=self.on_sub),
        )

    def _report(self, connected: bool, kind: str, change: int, current: int) -> bool:
        """Log one change in the `kind` ('subscription'/'publisher') connections; returns
        whether any is connected now."""
        if connected and current == 0:
            self.get_logger().info(f'Last {kind} is disconnected.')
            connected = False
        elif connected:
            self.get_logger().info(
                f'The changed number of connected {kind} is {change} and current number of '
                f'connected {kind} is {current}'
            )
        elif current != 0:
            self.get_logger().info(f'First {kind} is connected.')
            connected = True
        self.future.set_result(True)
        return connected

    def on_pub(self, info: QoSPublisherMatchedInfo) -> None:
        """The publisher's matched event."""
        self.any_subscription = self._report(
            self.any_subscription, 'subscription', info.current_count_change, info.current_count
        )

    def on_sub(self, info: QoSSubscriptionMatchedInfo) -> None:
        """The subscription's matched event."""
        self.any_publisher = self._report(
            self.any_publisher, 'publisher', info.current_count_change, info.current_count
        )

    def get_future(self) -> Future[bool]:
        """A fresh future the next event completes."""
        self.future = Future()
        return self.future


class MultiSubNode(Node):
    """Makes and drops subscriptions of one topic on request."""

    def __init__(self, topic: str) -> None:
        super().__init__('multi_sub_node')
        self.topic = topic

    def create_one_sub(self) -> Subscription[String]:
        """One more subscription."""
        self.get_logger().info('Create a new subscription.')
        return self.create_subscription(String, self.topic, lambda msg: None, 10)

    def destroy_one_sub(self, sub: Subscription[String]) -> None:
        """Drop one made here."""
        self.get_logger().info('Destroy a subscription.')
        self.destroy_subscription(sub)


class MultiPubNode(Node):
    """Makes and drops publishers of one topic on request."""

    def __init__(self, topic: str) -> None:
        super().__init__('multi_pub_node')
        self.topic = topic

    def create_one_pub(self) -> Publisher[String]:
        """One more publisher."""
        self.get_logger().info('Create a new publisher.')
        return self.create_publisher(String, self.topic, 10)

    def destroy_one_pub(self, pub: Publisher[String]) -> None:
        """Drop one made here."""
        self.get_logger().info('Destroy a publisher.')
        self.destroy_publisher(pub)


def walk_through() -> None:
    """Connect and disconnect two subscriptions, then two publishers, one event at a time."""
    detector = MatchedEventDetectNode(PUB_TOPIC, SUB_TOPIC)
    subs = MultiSubNode(PUB_TOPIC)
    pubs = MultiPubNode(SUB_TOPIC)
    executor = SingleThreadedExecutor()
    for node in (detector, subs, pubs):
        executor.add_node(node)

    def step(action: Callable[..., _Made], *args: object) -> _Made:
        future = detector.get_future()
        made = action(*args)
        executor.spin_until_future_complete(future, STEP_TIMEOUT)
        return made

    sub1 = step(subs.create_one_sub)
    sub2 = step(subs.create_one_sub)
    step(subs.destroy_one_sub, sub1)
    step(subs.destroy_one_sub, sub2)
    pub1 = step(pubs.create_one_pub)
    pub2 = step(pubs.create_one_pub)
    step(pubs.destroy_one_pub, pub1)
    step(pubs.destroy_one_pub, pub2)
    for node in (pubs, subs, detector):
        node.destroy_node()
    ros2lite.try_shutdown()


def main(args: list[str] | None = None) -> int:
    """`matched_event_detect`'s entry point."""
    return run_main(walk_through, args)


if __name__ == '__main__':
    raise SystemExit(main())
