"""The component containers (`component_container`, `component_container_mt`), named as
rclcpp_components' so launch files and tutorials find them."""
