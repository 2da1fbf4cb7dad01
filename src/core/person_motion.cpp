#include "thermal_lidar_calibration/core/person_motion.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace thermal_lidar_calibration {
namespace {

// Once a person's own velocity is known, the next centroid is searched within this of where it
// should be: a walker turning round or a vehicle braking moves less than this off the straight
// line within the window, while people stand further apart than this (about 0.9 m at least).
constexpr double kTrackedGateM = 0.6;
// Summed misfits closer than this are the same (rounding: a candidate with one supporter fits it
// exactly).
constexpr double kSameMisfitM = 1e-6;

// A track's bend is read over this many scans on each side (when found), its velocity over
// MotionConfig::window_scans: a parabola's curvature from five scans is about 50 times the
// centroid noise in m/s^2, from nine about 11 times (a 2 m/s tractor's 0.1 rad/s turn bends
// its tracks by 0.2 m/s^2).
constexpr int kBendScans = 4;

struct Track {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> c;
  std::vector<int> order;  // 0: the pair's own scan; k: the k-th found on its side
  int misses = 0;  // consecutive scans without it, in the current direction
  bool active = true;
  int found = 0;   // scans found in the current direction
};

// Least-squares straight line through the centroids: velocity and its standard error.
void fitLine(const Track& track, double centroid_noise_m, Eigen::Vector3d& velocity,
             Eigen::Vector3d& std_error) {
  const std::size_t n = track.t.size();
  double tm = 0.0;
  Eigen::Vector3d cm = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    tm += track.t[i];
    cm += track.c[i];
  }
  tm /= static_cast<double>(n);
  cm /= static_cast<double>(n);
  double stt = 0.0;
  Eigen::Vector3d stc = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    stt += (track.t[i] - tm) * (track.t[i] - tm);
    stc += (track.t[i] - tm) * (track.c[i] - cm);
  }
  if (stt <= 0.0) {  // every centroid at one instant: no motion can be read
    velocity.setZero();
    std_error.setConstant(std::numeric_limits<double>::infinity());
    return;
  }
  velocity = stc / stt;
  // The residual spread with three or more scans, but never below half the centroid noise
  // (three points on a line by chance would claim a perfect measurement); the noise alone with two.
  Eigen::Vector3d sigma = Eigen::Vector3d::Constant(centroid_noise_m);
  if (n >= 3) {
    Eigen::Vector3d ss = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d r = track.c[i] - (cm + velocity * (track.t[i] - tm));
      ss += r.cwiseProduct(r);
    }
    sigma = (ss / static_cast<double>(n - 2)).cwiseSqrt().cwiseMax(0.5 * centroid_noise_m);
  }
  std_error = sigma / std::sqrt(stt);
}

// The horizontal acceleration of a parabola through the track's centroids (least squares), when
// the track has scans on both sides of its first (the pair's own) and at least four: with scans
// on one side only the bend is an extrapolation. `weight`: how well the scans' times pin the
// curvature (the inverse of its variance for a unit centroid noise). False otherwise.
bool fitBend(const Track& track, Eigen::Vector2d& acceleration, double& weight) {
  if (track.t.size() < 4) return false;
  const double t0 = track.t[0];
  bool before = false, after = false;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> B = Eigen::Matrix<double, 3, 2>::Zero();
  for (std::size_t k = 0; k < track.t.size(); ++k) {
    const double s = track.t[k] - t0;
    before |= s < 0.0;
    after |= s > 0.0;
    const Eigen::Vector3d f(1.0, s, 0.5 * s * s);
    A += f * f.transpose();
    B += f * track.c[k].head<2>().transpose();
  }
  if (!before || !after) return false;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
  if (ldlt.info() != Eigen::Success) return false;
  acceleration = ldlt.solve(B).row(2).transpose();
  weight = 1.0 / ldlt.solve(Eigen::Vector3d::UnitZ()).z();
  return acceleration.allFinite() && std::isfinite(weight) && weight > 0.0;
}

// The yaw rate w that best explains the bends a_i = w (v_y, -v_x) (the turn of each horizontal
// velocity, -w z x v) over the people with one: the weighted least-squares slope through the
// origin, each bend weighed by how well its track pins it (fitBend); 0 without any. Pooled
// because one person's bend is noisy; a walker's own turning adds a little noise.
double turnRate(const std::vector<Eigen::Vector2d>& bends, const std::vector<Eigen::Vector2d>& velocities,
                const std::vector<double>& weights) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < bends.size(); ++i) {
    const Eigen::Vector2d jv(velocities[i].y(), -velocities[i].x());
    num += weights[i] * bends[i].dot(jv);
    den += weights[i] * jv.squaredNorm();
  }
  return den > 0.0 ? num / den : 0.0;
}

Eigen::Vector3d predict(const Track& track, double t, const Eigen::Vector3d& common_shift,
                        double common_dt, double centroid_noise_m) {
  if (track.t.size() >= 2) {
    Eigen::Vector3d v, se;
    fitLine(track, centroid_noise_m, v, se);
    // From the track's centroid nearest in time (the tracks grow in both directions).
    std::size_t anchor = 0;
    for (std::size_t i = 1; i < track.t.size(); ++i) {
      if (std::abs(track.t[i] - t) < std::abs(track.t[anchor] - t)) anchor = i;
    }
    return track.c[anchor] + v * (t - track.t[anchor]);
  }
  const double scale = common_dt != 0.0 ? (t - track.t[0]) / common_dt : 0.0;
  return track.c[0] + common_shift * scale;
}

// The shift most people of `from` show in `to`, `dt` after it: standing people all move by the
// vehicle's own motion, walkers deviate by a few centimetres per scan. Every displacement from a
// person of `from` to one of `to` within `gate_m` is a candidate. It scores one for each person
// of `from` it takes onto someone in `to` (within kTrackedGateM), and one for each it takes,
// scaled to `mirror` (the nearest scan on the other side, `mirror_dt` after `from`), onto someone
// there: when a person is missing from `to`, the displacement onto a neighbour explains as many
// people of `to` as the true shift does, but not those of the other side. The best candidate's
// supporters' mean displacement is the shift (fewer summed misfits break a tie, then the shorter
// shift); zero when nobody has a candidate. The last tie: two people, each missed in one of the
// two neighbouring scans, leave the step from one onto the other as well supported on both sides
// as the true step, both with no misfit; the shorter is the slower vehicle (people stand at least
// 0.9 m apart, so the other reading is 9 m/s or more faster at 10 Hz).
Eigen::Vector3d commonShift(const ScanPeople& from, const ScanPeople& to, double dt, const ScanPeople* mirror,
                            double mirror_dt, double gate_m) {
  const auto nearest = [](const ScanPeople& scan, const Eigen::Vector3d& at, const ScanPeople::Person** found) {
    double best = kTrackedGateM;
    *found = nullptr;
    for (const auto& q : scan.people) {
      const double d = (q.centroid - at).norm();
      if (d <= best) {
        best = d;
        *found = &q;
      }
    }
    return best;
  };
  int best_score = 0;
  double best_misfit = 0.0;
  Eigen::Vector3d best_shift = Eigen::Vector3d::Zero();
  for (const auto& p : from.people) {
    for (const auto& q : to.people) {
      const Eigen::Vector3d candidate = q.centroid - p.centroid;
      if (candidate.norm() > gate_m) continue;
      int in_to = 0;
      double misfit = 0.0;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (const auto& r : from.people) {
        const ScanPeople::Person* hit = nullptr;
        const double d = nearest(to, r.centroid + candidate, &hit);
        if (!hit) continue;
        ++in_to;
        misfit += d;
        sum += hit->centroid - r.centroid;
      }
      int score = in_to;
      if (mirror && dt != 0.0) {
        const Eigen::Vector3d scaled = candidate * (mirror_dt / dt);
        for (const auto& r : from.people) {
          const ScanPeople::Person* hit = nullptr;
          nearest(*mirror, r.centroid + scaled, &hit);
          if (hit) ++score;
        }
      }
      if (in_to == 0) continue;
      const Eigen::Vector3d shift = sum / static_cast<double>(in_to);
      const bool same_misfit = std::abs(misfit - best_misfit) <= kSameMisfitM;
      if (score > best_score || (score == best_score && !same_misfit && misfit < best_misfit) ||
          (score == best_score && same_misfit && shift.norm() < best_shift.norm())) {
        best_score = score;
        best_misfit = misfit;
        best_shift = shift;
      }
    }
  }
  return best_shift;
}

}  // namespace

void MotionConfig::validate() const {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("motion: " + what);
  };
  require(window_scans >= 1 && window_scans <= 10, "motion_window_scans must be in [1, 10]");
  require(max_speed_mps > 0.0 && max_speed_mps <= 100.0, "motion_max_speed_mps must be in (0, 100]");
  require(max_gap_s > 0.0 && max_gap_s <= 5.0, "motion_max_gap_s must be in (0, 5]");
  require(centroid_noise_m > 0.0 && centroid_noise_m <= 1.0, "centroid noise must be in (0, 1] m");
}

ScanPeople summariseScan(double stamp_s, const std::vector<Eigen::Vector3f>& points,
                         const std::vector<std::int32_t>& labels,
                         const std::vector<float>& point_time_s) {
  if (labels.size() != points.size()) {
    throw std::invalid_argument("scan: " + std::to_string(points.size()) + " points but " +
                                std::to_string(labels.size()) + " labels");
  }
  const bool timed = !point_time_s.empty();
  if (timed && point_time_s.size() != points.size()) {
    throw std::invalid_argument("scan: " + std::to_string(points.size()) + " points but " +
                                std::to_string(point_time_s.size()) + " point times");
  }
  struct Sum {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    double t = 0.0;
    int n = 0;
  };
  std::map<std::int32_t, Sum> sums;
  for (std::size_t i = 0; i < points.size(); ++i) {
    Sum& s = sums[labels[i]];
    s.p += points[i].cast<double>();
    s.t += timed ? static_cast<double>(point_time_s[i]) : 0.0;
    ++s.n;
  }
  ScanPeople scan;
  scan.stamp_s = stamp_s;
  for (const auto& [label, s] : sums) {
    ScanPeople::Person person;
    person.label = label;
    person.centroid = s.p / s.n;
    person.time_s = stamp_s + s.t / s.n;
    person.points = s.n;
    scan.people.push_back(person);
  }
  return scan;
}

std::vector<PersonMotion> estimateMotion(const std::vector<ScanPeople>& scans, std::size_t centre,
                                         const MotionConfig& config) {
  config.validate();
  if (centre >= scans.size()) throw std::invalid_argument("motion: scan index out of range");
  const ScanPeople& own = scans[centre];
  std::vector<Track> tracks(own.people.size());
  for (std::size_t i = 0; i < own.people.size(); ++i) {
    tracks[i].t.push_back(own.people[i].time_s);
    tracks[i].c.push_back(own.people[i].centroid);
    tracks[i].order.push_back(0);
  }

  for (const int dir : {-1, 1}) {
    for (Track& track : tracks) {
      track.active = true;
      track.misses = 0;
      track.found = 0;
    }
    // The nearest scan on the other side checks the common shift on this one (commonShift).
    const long other = static_cast<long>(centre) - dir;
    const ScanPeople* mirror = nullptr;
    if (other >= 0 && other < static_cast<long>(scans.size()) &&
        std::abs(scans[static_cast<std::size_t>(other)].stamp_s - own.stamp_s) <= config.max_gap_s) {
      mirror = &scans[static_cast<std::size_t>(other)];
    }
    double last_stamp = own.stamp_s;
    for (int step = 1;; ++step) {
      const long j = static_cast<long>(centre) + dir * step;
      if (j < 0 || j >= static_cast<long>(scans.size())) break;
      const ScanPeople& scan = scans[static_cast<std::size_t>(j)];
      if (std::abs(scan.stamp_s - last_stamp) > config.max_gap_s) break;  // a hole in the scans
      last_stamp = scan.stamp_s;
      const double dt = scan.stamp_s - own.stamp_s;
      const Eigen::Vector3d shift =
          commonShift(own, scan, dt, mirror, mirror ? mirror->stamp_s - own.stamp_s : 0.0,
                      config.max_speed_mps * std::abs(dt) + kTrackedGateM);

      // Every (active person, candidate) within its gate, nearest first, assigned one to one.
      struct Option {
        double distance;
        std::size_t track, candidate;
      };
      std::vector<Option> options;
      bool any_active = false;
      for (std::size_t i = 0; i < tracks.size(); ++i) {
        if (!tracks[i].active) continue;
        any_active = true;
        for (std::size_t k = 0; k < scan.people.size(); ++k) {
          const ScanPeople::Person& q = scan.people[k];
          const Eigen::Vector3d at = predict(tracks[i], q.time_s, shift, dt, config.centroid_noise_m);
          const double d = (q.centroid - at).norm();
          if (d <= kTrackedGateM) options.push_back({d, i, k});
        }
      }
      if (!any_active) break;
      std::sort(options.begin(), options.end(), [](const Option& a, const Option& b) {
        return a.distance != b.distance ? a.distance < b.distance
                                        : (a.track != b.track ? a.track < b.track : a.candidate < b.candidate);
      });
      std::vector<char> track_taken(tracks.size(), 0), candidate_taken(scan.people.size(), 0);
      for (const Option& o : options) {
        if (track_taken[o.track] || candidate_taken[o.candidate]) continue;
        track_taken[o.track] = candidate_taken[o.candidate] = 1;
        Track& track = tracks[o.track];
        track.t.push_back(scan.people[o.candidate].time_s);
        track.c.push_back(scan.people[o.candidate].centroid);
        track.misses = 0;
        track.order.push_back(++track.found);
        if (track.found >= std::max(config.window_scans, kBendScans)) track.active = false;
      }
      for (std::size_t i = 0; i < tracks.size(); ++i) {
        // One scan without the person (hidden behind another, missed by the detector) is
        // bridged; two in a row end the track on this side.
        if (tracks[i].active && !track_taken[i] && ++tracks[i].misses > 1) tracks[i].active = false;
      }
    }
  }

  std::vector<PersonMotion> out(own.people.size());
  for (std::size_t i = 0; i < own.people.size(); ++i) {
    // The velocity from the window's scans only, as found on each side.
    Track inner;
    for (std::size_t k = 0; k < tracks[i].t.size(); ++k) {
      if (tracks[i].order[k] > config.window_scans) continue;
      inner.t.push_back(tracks[i].t[k]);
      inner.c.push_back(tracks[i].c[k]);
    }
    out[i].label = own.people[i].label;
    out[i].scans = static_cast<int>(inner.t.size());
    if (out[i].scans < 2) continue;
    fitLine(inner, config.centroid_noise_m, out[i].velocity_mps, out[i].std_error_mps);
  }
  std::vector<Eigen::Vector2d> bends, velocities;
  std::vector<double> weights;
  for (std::size_t i = 0; i < own.people.size(); ++i) {
    Eigen::Vector2d a;
    double weight = 0.0;
    if (out[i].measured() && fitBend(tracks[i], a, weight)) {
      bends.push_back(a);
      velocities.push_back(out[i].velocity_mps.head<2>());
      weights.push_back(weight);
    }
  }
  const double w = turnRate(bends, velocities, weights);
  for (PersonMotion& m : out) {
    if (m.measured()) m.turn_rate_rps = w;
  }
  return out;
}

}  // namespace thermal_lidar_calibration
