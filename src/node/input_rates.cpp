#include "thermal_lidar_calibration/node/input_rates.hpp"

#include <cmath>

namespace thermal_lidar_calibration {

InputRates::InputRates(std::vector<std::string> topics, Clock::time_point start, double window_s,
                       double stale_s)
    : topics_(std::move(topics)),
      start_(start),
      window_s_(window_s),
      stale_s_(stale_s),
      recent_(topics_.size()),
      last_(topics_.size()),
      totals_(topics_.size(), 0) {}

void InputRates::prune(std::deque<Clock::time_point>& q, Clock::time_point now, double window_s) {
  while (!q.empty() && std::chrono::duration<double>(now - q.front()).count() > window_s) q.pop_front();
}

void InputRates::message(std::size_t topic, Clock::time_point now) {
  recent_[topic].push_back(now);
  prune(recent_[topic], now, window_s_);
  last_[topic] = now;
  ++totals_[topic];
}

void InputRates::frame(Clock::time_point now) {
  frames_.push_back(now);
  prune(frames_, now, window_s_);
}

double InputRates::rateHz(std::size_t topic, Clock::time_point now) {
  prune(recent_[topic], now, window_s_);
  return static_cast<double>(recent_[topic].size()) / window_s_;
}

double InputRates::frameRateHz(Clock::time_point now) {
  prune(frames_, now, window_s_);
  return static_cast<double>(frames_.size()) / window_s_;
}

std::string InputRates::problem(Clock::time_point now) const {
  const auto seconds = [&](Clock::time_point t) { return std::chrono::duration<double>(now - t).count(); };
  if (seconds(start_) < stale_s_) return "";
  std::vector<std::size_t> silent;
  std::string arriving;
  for (std::size_t i = 0; i < topics_.size(); ++i) {
    const double since = totals_[i] == 0 ? seconds(start_) : seconds(last_[i]);
    if (since >= stale_s_) {
      silent.push_back(i);
    } else {
      arriving += (arriving.empty() ? "" : ", ") + topics_[i];
    }
  }
  if (silent.empty()) return "";
  std::string names;
  double longest = 0;
  bool never = true;
  for (std::size_t i : silent) {
    names += (names.empty() ? "" : ", ") + topics_[i];
    longest = std::max(longest, totals_[i] == 0 ? seconds(start_) : seconds(last_[i]));
    never = never && totals_[i] == 0;
  }
  const std::string how_long = std::to_string(static_cast<long long>(std::floor(longest))) + " s";
  const std::string what = never ? "no message ever on " + names + " (" + how_long + " since start)"
                                 : "no messages on " + names + " for " + how_long;
  if (arriving.empty()) {
    return what + ": is the bag or the sensors running, with the topics remapped to the node's inputs?";
  }
  return what + " while " + arriving + " arrive: is its publisher running and remapped to the node's input?";
}

}  // namespace thermal_lidar_calibration
