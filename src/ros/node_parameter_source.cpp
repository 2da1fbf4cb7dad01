// ParameterSource over a ros::NodeHandle's private parameters.

#include "thermal_lidar_calibration/ros/node_parameter_source.hpp"

#include <ros/param.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <algorithm>

namespace thermal_lidar_calibration {
namespace ros_io {
namespace {

class NodeHandleParameterSource : public ParameterSource {
 public:
  explicit NodeHandleParameterSource(const ros::NodeHandle& nh) : nh_(nh) {}

  bool has(const std::string& key) const override { return nh_.hasParam(key); }
  std::optional<double> getDouble(const std::string& key) const override {
    XmlRpc::XmlRpcValue v;
    if (!get(key, v)) return std::nullopt;
    if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
    if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
    return std::nullopt;
  }
  std::optional<long long> getInt(const std::string& key) const override {
    XmlRpc::XmlRpcValue v;
    if (!get(key, v) || v.getType() != XmlRpc::XmlRpcValue::TypeInt) return std::nullopt;
    return static_cast<int>(v);
  }
  std::optional<std::string> getString(const std::string& key) const override {
    XmlRpc::XmlRpcValue v;
    if (!get(key, v) || v.getType() != XmlRpc::XmlRpcValue::TypeString) return std::nullopt;
    return static_cast<std::string>(v);
  }
  std::optional<bool> getBool(const std::string& key) const override {
    XmlRpc::XmlRpcValue v;
    if (!get(key, v) || v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) return std::nullopt;
    return static_cast<bool>(v);
  }

 private:
  bool get(const std::string& key, XmlRpc::XmlRpcValue& v) const {
    return nh_.getParam(key, v);
  }
  ros::NodeHandle nh_;
};

}  // namespace

std::unique_ptr<ParameterSource> makeNodeHandleParameterSource(const ros::NodeHandle& private_nh) {
  return std::make_unique<NodeHandleParameterSource>(private_nh);
}

std::vector<std::string> nodeParameterKeys(const ros::NodeHandle& private_nh) {
  std::vector<std::string> names;
  std::vector<std::string> keys;
  if (!ros::param::getParamNames(names)) return keys;
  std::string prefix = private_nh.getNamespace();
  if (prefix.empty() || prefix.back() != '/') prefix += '/';
  for (const auto& name : names) {
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string rest = name.substr(prefix.size());
    const std::string key = rest.substr(0, rest.find('/'));
    if (!key.empty() && std::find(keys.begin(), keys.end(), key) == keys.end()) {
      keys.push_back(key);
    }
  }
  return keys;
}

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
