#pragma once
// ROS 2 names on the DDS wire (rmw_cyclonedds): topic "/a/b" is DDS topic
// "rt/a/b"; names follow rcl's rules (tokens of letters, digits and '_', not
// starting with a digit, separated by single '/').
#include <string>
#include <string_view>

namespace dsswarm::net {

// "" and "/" → "/"; "robot1", "/robot1/" → "/robot1". Throws ConfigError for
// a namespace ROS would reject ("/a//b", "/1robot", "/a b").
std::string normalize_namespace(std::string_view ns);

// The fully qualified name: an absolute `name` ("/scan") is kept, a relative
// one ("scan", "laser/scan") goes under the namespace. Private names ("~/x")
// need a node name and are rejected, like invalid ones (ConfigError).
std::string ros_fully_qualified_name(std::string_view ns, std::string_view name);

// The DDS topic for a ROS topic: ros_topic_name("/robot1", "scan") == "rt/robot1/scan".
std::string ros_topic_name(std::string_view ns, std::string_view name);

// A tf frame id as tf2 compares them: without a leading '/'.
std::string_view strip_frame_slash(std::string_view frame);

}  // namespace dsswarm::net
