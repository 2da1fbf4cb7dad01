#pragma once
// Message rates of a node's inputs over a sliding window, and the one-line finding when a topic
// stops or never starts (for /diagnostics and a throttled warning: a node that sits silently at
// "collecting 0/60" because one of three topics never arrives leaves the user guessing).

#include <chrono>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace thermal_lidar_calibration {

class InputRates {
 public:
  using Clock = std::chrono::steady_clock;

  // `topics`: the inputs, by name; `window_s`: the rate window; a topic silent for `stale_s`
  // while another arrives (or, before any, that long after start) is a problem.
  InputRates(std::vector<std::string> topics, Clock::time_point start, double window_s = 5.0,
             double stale_s = 5.0);

  void message(std::size_t topic, Clock::time_point now);  // a message arrived on topics[topic]
  void frame(Clock::time_point now);                        // a synchronized frame was offered

  double rateHz(std::size_t topic, Clock::time_point now);
  double frameRateHz(Clock::time_point now);
  const std::vector<std::string>& topics() const { return topics_; }
  std::uint64_t total(std::size_t topic) const { return totals_[topic]; }

  // "" when every topic flows; else e.g. "no messages on /thermal/human_mask for 12 s while
  // /thermal/image_raw, /lidar/human_clusters arrive: is its publisher running and remapped?"
  std::string problem(Clock::time_point now) const;

 private:
  static void prune(std::deque<Clock::time_point>& q, Clock::time_point now, double window_s);
  std::vector<std::string> topics_;
  Clock::time_point start_;
  double window_s_, stale_s_;
  std::vector<std::deque<Clock::time_point>> recent_;
  std::vector<Clock::time_point> last_;
  std::vector<std::uint64_t> totals_;
  std::deque<Clock::time_point> frames_;
};

}  // namespace thermal_lidar_calibration
