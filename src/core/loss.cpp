#include "thermal_lidar_calibration/core/loss.hpp"

#include "thermal_lidar_calibration/core/person_timing.hpp"

#include "loss_kernels.hpp"
#include "threads.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <atomic>
#include <numeric>
#include <stdexcept>
#include <string>

namespace thermal_lidar_calibration {
namespace {

using Params = std::array<float, 12>;

// At most this many candidates are swept together over one pair's points before the next
// pair, so the pair's points and distance map stay in cache.
constexpr std::size_t kCandidateBlock = 16;

kernels::MapView viewOf(const std::shared_ptr<const DistanceMap>& map) {
  const DistanceMap& d = *map;
  return {d.data(), d.width(), static_cast<float>(d.x0()), static_cast<float>(d.y0()),
          static_cast<float>(d.x0() + d.width() - 1), static_cast<float>(d.y0() + d.height() - 1)};
}

// What the kernels subtract from each point's reading: the margin, and for the sub-pixel rule at
// least the distance from a person pixel's centre to its outline (LossConfig::outline_px).
float marginOf(const LossConfig& config, PixelRule rule) {
  const double margin =
      rule == PixelRule::kBilinear ? std::max(config.margin_px, config.outline_px) : config.margin_px;
  return static_cast<float>(margin);
}

kernels::Points pointsOf(const PreparedPair& p) {
  return {p.x.data(), p.y.data(), p.z.data(), static_cast<int>(p.count)};
}

// A pair's assigned ring ends laid out for kernels::sumRingEnds: one array per field, padded to
// a multiple of kPointBlock, and the outlines' columns in one array (left then right side of
// each outline), so the vector kernel gathers both. The ends' points are copied per evaluator
// (RingEndPoints): a time offset moves them.
struct PackedRingEnds {
  std::vector<std::int32_t> point, rows, offset;
  std::vector<float> side, first_row, half_step, edges;
  std::vector<std::uint8_t> pairs_previous;
  int count = 0;

  PackedRingEnds() = default;
  explicit PackedRingEnds(const RingEndSet& set) {
    std::vector<std::int32_t> starts;  // per outline, where its left side starts; the right follows
    for (const PersonOutline& o : set.outlines) {
      starts.push_back(static_cast<std::int32_t>(edges.size()));
      edges.insert(edges.end(), o.left.begin(), o.left.end());
      edges.insert(edges.end(), o.right.begin(), o.right.end());
    }
    for (const AssignedRingEnd& e : set.ends) {
      const PersonOutline& o = set.outlines[e.outline];
      const auto left = static_cast<std::int32_t>(o.left.size());
      point.push_back(static_cast<std::int32_t>(e.point));
      side.push_back(static_cast<float>(e.side));
      first_row.push_back(static_cast<float>(o.first_row));
      rows.push_back(e.side > 0 ? static_cast<std::int32_t>(o.right.size()) : left);
      offset.push_back(starts[e.outline] + (e.side > 0 ? left : 0));
      half_step.push_back(e.half_step);
      pairs_previous.push_back(e.pairs_previous ? 1 : 0);
    }
    count = static_cast<int>(point.size());
    // Padding lanes: point 0, no rows (so no gather), masked out of the sum.
    const std::size_t padded = (point.size() + kernels::kPointBlock - 1) / kernels::kPointBlock * kernels::kPointBlock;
    point.resize(padded, 0);
    rows.resize(padded, 0);
    offset.resize(padded, 0);
    side.resize(padded, 1.0f);
    first_row.resize(padded, 0.0f);
    half_step.resize(padded, 0.0f);
    pairs_previous.resize(padded, 0);
  }
};

// The ends' points of one pair, as PackedRingEnds::point indexes them, where the pair has them.
struct RingEndPoints {
  std::vector<float> x, y, z;
  RingEndPoints() = default;
  RingEndPoints(const PackedRingEnds& ends, const PreparedPair& pair) {
    x.reserve(ends.point.size());
    y.reserve(ends.point.size());
    z.reserve(ends.point.size());
    for (const std::int32_t k : ends.point) {
      x.push_back(pair.x[static_cast<std::size_t>(k)]);
      y.push_back(pair.y[static_cast<std::size_t>(k)]);
      z.push_back(pair.z[static_cast<std::size_t>(k)]);
    }
  }
};

kernels::RingEnds viewOf(const PackedRingEnds& e, const RingEndPoints& p) {
  return {p.x.data(),        p.y.data(),      p.z.data(),         e.side.data(), e.first_row.data(),
          e.rows.data(),     e.offset.data(), e.half_step.data(), e.edges.data(), e.pairs_previous.data(), e.count};
}

}  // namespace

PreparedPair::PreparedPair(const CalibrationPair& pair, std::optional<double> time_offset_s)
    : distance(pair.distance_map ? pair.distance_map : std::make_shared<const DistanceMap>(pair.mask)) {
  count = pair.points.size();
  const std::size_t padded = (count + kernels::kPointBlock - 1) / kernels::kPointBlock * kernels::kPointBlock;
  x.assign(padded, 0.0f);
  y.assign(padded, 0.0f);
  z.assign(padded, 0.0f);
  const bool moving = time_offset_s && hasMeasuredMotion(pair);
  if (!moving) {
    for (std::size_t i = 0; i < count; ++i) {
      x[i] = pair.points[i].x();
      y[i] = pair.points[i].y();
      z[i] = pair.points[i].z();
    }
    bound();
    return;
  }
  const std::vector<Eigen::Vector3f> base = pointsAtImageTime(pair, 0.0);
  auto m = std::make_shared<Motion>();
  m->base_x.resize(count);
  m->base_y.resize(count);
  m->base_z.resize(count);
  m->vx.resize(count);
  m->vy.resize(count);
  m->vz.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    m->base_x[i] = base[i].x();
    m->base_y[i] = base[i].y();
    m->base_z[i] = base[i].z();
    m->vx[i] = pair.point_velocity[i].x();
    m->vy[i] = pair.point_velocity[i].y();
    m->vz[i] = pair.point_velocity[i].z();
  }
  if (pair.turn_rate_rps != 0.0) {
    m->ax.resize(count);
    m->ay.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const Eigen::Vector3f a = turnAcceleration(pair.point_velocity[i], pair.turn_rate_rps);
      const float lead = static_cast<float>(leadTimeS(pair, i));
      m->ax[i] = a.x();
      m->ay[i] = a.y();
      m->vx[i] += a.x() * lead;
      m->vy[i] += a.y() * lead;
    }
  }
  motion = std::move(m);
  moveTo(*time_offset_s);
}

void PreparedPair::moveTo(double time_offset_s) {
  if (!motion) return;  // no motion: the points stay where they were captured
  const Motion& m = *motion;
  const float d = static_cast<float>(time_offset_s);
  for (std::size_t i = 0; i < count; ++i) {
    x[i] = m.base_x[i] + d * m.vx[i];
    y[i] = m.base_y[i] + d * m.vy[i];
    z[i] = m.base_z[i] + d * m.vz[i];
  }
  if (!m.ax.empty()) {
    const float half_d2 = 0.5f * d * d;
    for (std::size_t i = 0; i < count; ++i) {
      x[i] += half_d2 * m.ax[i];
      y[i] += half_d2 * m.ay[i];
    }
  }
  bound();
}

void PreparedPair::bound() {
  centre.setZero();
  radius = 0.0;
  if (count == 0) return;
  for (std::size_t i = 0; i < count; ++i) centre += Eigen::Vector3d(x[i], y[i], z[i]);
  centre /= static_cast<double>(count);
  for (std::size_t i = 0; i < count; ++i) {
    radius = std::max(radius, (Eigen::Vector3d(x[i], y[i], z[i]) - centre).norm());
  }
}

struct LossEvaluator::Impl {
  std::vector<PreparedPair> pairs;
  kernels::Lens lens{};
  bool distorted = false;
  float penalty = 0.0f;
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  // Per pair, the ring ends (withRingEnds; null without), shared by the copies, and their points.
  std::shared_ptr<const std::vector<PackedRingEnds>> ring_ends;
  std::vector<RingEndPoints> ring_points;
  mutable std::atomic<std::uint64_t> points{0};

  // The same pairs (points copied, distance maps and motion shared), lens and ring ends; its own
  // count. Not the ends' points: every copy moves the points or changes the ends, then takes
  // them again (placeRingEnds).
  std::shared_ptr<Impl> copy() const {
    auto out = sameCamera();
    out->pairs = pairs;
    out->ring_ends = ring_ends;
    return out;
  }

  // Pairs `keep` only, in that order, with their ring ends and the ends' points.
  std::shared_ptr<Impl> ofPairs(const std::vector<std::size_t>& keep) const {
    auto out = sameCamera();
    out->pairs.reserve(keep.size());
    for (std::size_t i : keep) out->pairs.push_back(pairs[i]);
    if (ring_ends) {
      auto ends = std::make_shared<std::vector<PackedRingEnds>>();
      ends->reserve(keep.size());
      for (std::size_t i : keep) ends->push_back((*ring_ends)[i]);
      out->ring_ends = std::move(ends);
      out->ring_points.reserve(keep.size());
      for (std::size_t i : keep) out->ring_points.push_back(ring_points[i]);
    }
    return out;
  }

  // No pairs yet; the same lens, projection and penalty.
  std::shared_ptr<Impl> sameCamera() const {
    auto out = std::make_shared<Impl>();
    out->lens = lens;
    out->distorted = distorted;
    out->penalty = penalty;
    out->K = K;
    return out;
  }

  // Fold K into [R | t] when there is no distortion: one mat-vec and one reciprocal per point.
  Params paramsOf(const Extrinsic& e) const { return paramsOf(e.rotationMatrix(), e.translation); }
  Params paramsOf(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) const {
    Eigen::Matrix<double, 3, 4> m;
    m.leftCols<3>() = R;
    m.col(3) = t;
    if (!distorted) m = K * m;
    Params out;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) out[r * 4 + c] = static_cast<float>(m(r, c));
    }
    return out;
  }

  // Eq. (1): the mean psi over the pair's points; with the sub-pixel rule and a ring-end weight,
  // plus the weighted mean ring-end cost of the pair (index i).
  double pairLoss(const Params& m, std::size_t i, const PreparedPair& pair, const kernels::MapView& map,
                  const kernels::Points& pts, PixelRule rule, float margin, double ring_weight) const {
    const float sum = kernels::sumPsi(m.data(), distorted, rule == PixelRule::kBilinear, lens, pts,
                                      map, penalty, margin);
    const double mean = static_cast<double>(sum) / static_cast<double>(pair.count);
    if (rule != PixelRule::kBilinear || !(ring_weight > 0.0) || !ring_ends || (*ring_ends)[i].count == 0) {
      return mean;
    }
    return mean + ring_weight * ringEndCost(m, (*ring_ends)[i], ring_points[i]);
  }
  double pairLoss(const Params& m, std::size_t i, PixelRule rule, float margin, double ring_weight) const {
    const PreparedPair& pair = pairs[i];
    return pairLoss(m, i, pair, viewOf(pair.distance), pointsOf(pair), rule, margin, ring_weight);
  }

  // The pair's ring-end charge (kernels::sumRingEnds: ringPairCost per ring with both ends measured,
  // ringEndCost per other end; behind the camera the cap) over its assigned ends.
  double ringEndCost(const Params& m, const PackedRingEnds& ends, const RingEndPoints& points) const {
    return static_cast<double>(
               kernels::sumRingEnds(m.data(), distorted, lens, viewOf(ends, points), LossConfig::kRingEndCapPx,
                                    LossConfig::kRingWidthWeight)) /
           static_cast<double>(ends.count);
  }

  // The ends' points taken again from the pairs (after they moved to another time offset).
  void placeRingEnds() {
    ring_points.assign(pairs.size(), {});
    if (!ring_ends) return;
    for (std::size_t i = 0; i < pairs.size(); ++i) ring_points[i] = RingEndPoints((*ring_ends)[i], pairs[i]);
  }
};

LossEvaluator::LossEvaluator(const CameraModel& camera, const std::vector<CalibrationPair>& pairs,
                             LossConfig config)
    : camera_(camera), config_(config), impl_(std::make_shared<Impl>()) {
  camera_.validate();
  config_.validate();
  // The kernels compute pixel indices in float, exact only below 2^24 (16.7 megapixels).
  if (static_cast<long long>(camera_.width) * camera_.height >= (1LL << 24)) {
    throw std::invalid_argument("loss: images of 16.7 megapixels or more are not supported (" +
                                std::to_string(camera_.width) + "x" +
                                std::to_string(camera_.height) + ")");
  }
  impl_->pairs.reserve(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const CalibrationPair& p = pairs[i];
    const std::string where = "pair " + std::to_string(i) + ": ";
    if (p.points.empty()) throw std::invalid_argument(where + "has no LiDAR points");
    if (p.mask.cols != camera_.width || p.mask.rows != camera_.height) {
      throw std::invalid_argument(where + "mask is " + std::to_string(p.mask.cols) + "x" +
                                  std::to_string(p.mask.rows) + " but the camera is " +
                                  std::to_string(camera_.width) + "x" +
                                  std::to_string(camera_.height));
    }
    try {
      impl_->pairs.emplace_back(p, config_.time_offset_s);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + e.what());
    }
  }
  impl_->distorted = camera_.hasDistortion();
  impl_->K = camera_.K();
  const auto f = [](double v) { return static_cast<float>(v); };
  impl_->lens = {f(camera_.fx), f(camera_.fy), f(camera_.cx), f(camera_.cy), f(camera_.skew),
                 f(camera_.distortion[0]), f(camera_.distortion[1]), f(camera_.distortion[2]),
                 f(camera_.distortion[3]), f(camera_.distortion[4]),
                 camera_.distortion[2] == 0.0 && camera_.distortion[3] == 0.0 && camera_.skew == 0.0};
  impl_->penalty = static_cast<float>(config_.behind_camera_penalty_c1 *
                                      std::max(camera_.width, camera_.height));
}

LossEvaluator::LossEvaluator(CameraModel camera, LossConfig config, std::shared_ptr<Impl> impl)
    : camera_(std::move(camera)), config_(config), impl_(std::move(impl)) {}

LossEvaluator::~LossEvaluator() = default;
LossEvaluator::LossEvaluator(LossEvaluator&&) noexcept = default;

LossEvaluator LossEvaluator::withPixelRule(PixelRule rule) const {
  LossConfig config = config_;
  config.pixel_rule = rule;
  return LossEvaluator(camera_, config, impl_);
}

LossEvaluator LossEvaluator::withTimeOffset(double time_offset_s) const {
  if (!config_.time_offset_s) throw std::logic_error("loss: withTimeOffset on an evaluator without a time offset");
  LossConfig config = config_;
  config.time_offset_s = time_offset_s;
  auto impl = impl_->copy();
  for (PreparedPair& pair : impl->pairs) pair.moveTo(time_offset_s);
  impl->placeRingEnds();
  return LossEvaluator(camera_, config, impl);
}

LossEvaluator LossEvaluator::ofPairs(const std::vector<std::size_t>& pairs) const {
  for (std::size_t i : pairs) {
    if (i >= impl_->pairs.size()) {
      throw std::invalid_argument("loss: ofPairs: pair " + std::to_string(i) + " of " +
                                  std::to_string(impl_->pairs.size()));
    }
  }
  return LossEvaluator(camera_, config_, impl_->ofPairs(pairs));
}

bool LossEvaluator::hasMotion() const {
  for (const PreparedPair& p : impl_->pairs) {
    if (p.motion) return true;
  }
  return false;
}

LossEvaluator LossEvaluator::withMargin(double margin_px) const {
  LossConfig config = config_;
  config.margin_px = margin_px;
  config.validate();
  return LossEvaluator(camera_, config, impl_);
}

LossEvaluator LossEvaluator::withOutline(double outline_px) const {
  LossConfig config = config_;
  config.outline_px = outline_px;
  config.validate();
  return LossEvaluator(camera_, config, impl_);
}

LossEvaluator LossEvaluator::withRingEnds(const std::vector<CalibrationPair>& pairs, const Extrinsic& at,
                                          double weight, const RingEndRules& rules) const {
  if (pairs.size() != impl_->pairs.size()) {
    throw std::invalid_argument("loss: withRingEnds needs the evaluator's own pairs");
  }
  LossConfig config = config_;
  config.ring_end_weight = weight;
  config.validate();
  auto impl = impl_->copy();
  auto packed = std::make_shared<std::vector<PackedRingEnds>>(pairs.size());
  const Params m = impl->paramsOf(at);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const PreparedPair& p = impl->pairs[i];
    if (pairs[i].points.size() != p.count) {
      throw std::invalid_argument("loss: withRingEnds needs the evaluator's own pairs");
    }
    const std::vector<RingEnd> ends = findRingEnds(pairs[i].points, pairs[i].labels);
    if (ends.empty()) continue;
    std::vector<Eigen::Vector2f> pixels(p.count, Eigen::Vector2f::Constant(std::nanf("")));
    for (std::size_t k = 0; k < p.count; ++k) {
      float u, v;
      if (kernels::projectPoint(m.data(), impl->distorted, impl->lens, p.x[k], p.y[k], p.z[k], u, v)) {
        pixels[k] = Eigen::Vector2f(u, v);
      }
    }
    (*packed)[i] = PackedRingEnds(assignRingEnds(pairs[i].mask, pairs[i].labels, ends, pixels, rules));
  }
  impl->ring_ends = packed;
  impl->placeRingEnds();
  return LossEvaluator(camera_, config, impl);
}

LossEvaluator LossEvaluator::withoutRingEnds() const {
  LossConfig config = config_;
  config.ring_end_weight = 0.0;
  return LossEvaluator(camera_, config, impl_);
}

std::size_t LossEvaluator::ringEndCount() const {
  std::size_t n = 0;
  if (impl_->ring_ends) {
    for (const PackedRingEnds& ends : *impl_->ring_ends) n += static_cast<std::size_t>(ends.count);
  }
  return n;
}

std::size_t LossEvaluator::pairCount() const { return impl_->pairs.size(); }

bool LossEvaluator::maskTouchesImageBorder(std::size_t pair) const {
  const DistanceMap& d = *impl_->pairs.at(pair).distance;
  return d.x0() <= 0 || d.y0() <= 0 || d.x0() + d.width() >= camera_.width ||
         d.y0() + d.height() >= camera_.height;
}

Eigen::Vector3d LossEvaluator::centroid(const std::vector<std::size_t>& pairs) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double count = 0.0;
  const auto add = [&](const PreparedPair& p) {
    sum += p.centre * static_cast<double>(p.count);
    count += static_cast<double>(p.count);
  };
  if (pairs.empty()) {
    for (const PreparedPair& p : impl_->pairs) add(p);
  } else {
    for (std::size_t i : pairs) add(impl_->pairs.at(i));
  }
  return count > 0.0 ? Eigen::Vector3d(sum / count) : Eigen::Vector3d::Zero();
}

double LossEvaluator::pairLoss(std::size_t pair, const Extrinsic& extrinsic) const {
  impl_->points += impl_->pairs.at(pair).count;
  return impl_->pairLoss(impl_->paramsOf(extrinsic), pair, config_.pixel_rule,
                         marginOf(config_, config_.pixel_rule), config_.ring_end_weight);
}

double LossEvaluator::loss(const Extrinsic& extrinsic, const std::vector<std::size_t>& subset) const {
  std::vector<double> out;
  lossBatch({extrinsic}, subset, out, 1);
  return out.front();
}

void LossEvaluator::lossBatch(const std::vector<Extrinsic>& candidates,
                              const std::vector<std::size_t>& subset, std::vector<double>& out,
                              int threads) const {
  const std::size_t pair_count = sumOverPairs(candidates, subset, out, threads, [](double loss) { return loss; });
  for (double& v : out) v /= static_cast<double>(pair_count);
}

void LossEvaluator::pairsAboveBatch(const std::vector<Extrinsic>& candidates,
                                    const std::vector<std::size_t>& subset, double level,
                                    std::vector<double>& out, int threads) const {
  sumOverPairs(candidates, subset, out, threads, [level](double loss) { return loss > level ? 1.0 : 0.0; });
}

template <typename Term>
std::size_t LossEvaluator::sumOverPairs(const std::vector<Extrinsic>& candidates,
                                        const std::vector<std::size_t>& subset, std::vector<double>& out,
                                        int threads, Term term) const {
  std::vector<std::size_t> all;
  const std::vector<std::size_t>* pairs = &subset;
  if (subset.empty()) {
    all.resize(impl_->pairs.size());
    std::iota(all.begin(), all.end(), std::size_t{0});
    pairs = &all;
  }
  if (pairs->empty()) throw std::invalid_argument("loss: no pairs to evaluate");
  for (std::size_t i : *pairs) {
    if (i >= impl_->pairs.size()) throw std::invalid_argument("loss: pair index out of range");
  }
  const std::size_t n = candidates.size();
  out.assign(n, 0.0);
  std::vector<Params> params(n);
  for (std::size_t c = 0; c < n; ++c) params[c] = impl_->paramsOf(candidates[c]);

  // Small batches (the refinement's 12 probes) are split into smaller blocks so that every
  // thread gets some; large ones use whole blocks.
  int team = resolveThreads(threads);
  const std::size_t per_thread = (n + static_cast<std::size_t>(team) - 1) / static_cast<std::size_t>(team);
  const std::size_t block = std::clamp<std::size_t>(per_thread, 1, kCandidateBlock);
  const int blocks = static_cast<int>((n + block - 1) / block);
  team = std::max(1, std::min(team, blocks));
  const PixelRule rule = config_.pixel_rule;
  const float margin = marginOf(config_, rule);
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
  for (int b = 0; b < blocks; ++b) {
    const std::size_t begin = static_cast<std::size_t>(b) * block;
    const std::size_t end = std::min(n, begin + block);
    std::array<double, kCandidateBlock> sums{};
    // Each candidate's sum runs over the pairs in the same order in any block or thread.
    for (std::size_t pi : *pairs) {
      const PreparedPair& pair = impl_->pairs[pi];
      const kernels::MapView map = viewOf(pair.distance);
      const kernels::Points pts = pointsOf(pair);
      for (std::size_t c = begin; c < end; ++c) {
        sums[c - begin] +=
            term(impl_->pairLoss(params[c], pi, pair, map, pts, rule, margin, config_.ring_end_weight));
      }
    }
    for (std::size_t c = begin; c < end; ++c) out[c] = sums[c - begin];
  }
  std::uint64_t per_candidate = 0;
  for (std::size_t pi : *pairs) per_candidate += impl_->pairs[pi].count;
  impl_->points += per_candidate * n;
  return pairs->size();
}

double LossEvaluator::insideFraction(std::size_t pair, const Extrinsic& extrinsic) const {
  const PreparedPair& p = impl_->pairs.at(pair);
  const Params m = impl_->paramsOf(extrinsic);
  const int inside = kernels::countInside(m.data(), impl_->distorted, impl_->lens, pointsOf(p),
                                          camera_.width, camera_.height);
  return static_cast<double>(inside) / static_cast<double>(p.count);
}

bool LossEvaluator::somePairInside(const std::vector<std::size_t>& pairs,
                                   const Extrinsic& extrinsic, double fraction) const {
  const Eigen::Matrix3d R = extrinsic.rotationMatrix();
  const Params m = impl_->paramsOf(R, extrinsic.translation);
  for (std::size_t i : pairs) {
    const PreparedPair& p = impl_->pairs.at(i);
    // Camera-frame depth of the sphere's centre; if even its nearest point is not in front, no
    // point of this pair can be (R preserves distances).
    const double z = R.row(2).dot(p.centre) + extrinsic.translation.z();
    if (z + p.radius <= 0.0) continue;
    const int needed = static_cast<int>(std::ceil(fraction * static_cast<double>(p.count) - 1e-9));
    if (kernels::atLeastInside(m.data(), impl_->distorted, impl_->lens, pointsOf(p),
                               camera_.width, camera_.height, needed)) {
      return true;
    }
  }
  return false;
}

std::uint64_t LossEvaluator::pointsEvaluated() const { return impl_->points.load(); }

}  // namespace thermal_lidar_calibration
