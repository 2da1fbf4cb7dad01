#include "thermal_lidar_calibration/tools/calibration_summary.hpp"
#include "thermal_lidar_calibration/app/report/quality_output.hpp"
#include "thermal_lidar_calibration/app/report/static_transform_command.hpp"
#include "thermal_lidar_calibration/app/report/timing_text.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace thermal_lidar_calibration {
namespace {

std::string fmt(const char* format, double a, double b, double c) {
  char buf[128];
  std::snprintf(buf, sizeof(buf), format, a, b, c);
  return buf;
}

}  // namespace

std::string formatCalibrationSummary(const SummaryInput& in) {
  const CalibrationResult& r = in.result;
  const Extrinsic& e = r.extrinsic;
  const Eigen::Matrix3d R = e.rotationMatrix();
  const Eigen::Quaterniond q = e.quaternion();
  constexpr double kDeg = 180.0 / M_PI;
  std::ostringstream s;
  s << "calibrate_bag: " << (r.stopped ? "STOPPED EARLY (best so far)" : "done") << "\n";
  s << "  bag              " << in.bag_path << " (" << in.messages_read << " messages, "
    << in.frames << " synchronized frames)\n";
  s << "  frames           " << in.counts.summary() << "\n";
  s << "  pairs            " << r.pairs_collected << " kept, " << r.pairs_used << " used ("
    << in.algorithm_text
    << (r.evolution_full_length ? "; evolution run to max_iterations: the shortened run's fit failed Algorithm 2's test"
                                : "")
    << ")\n";
  if (in.pairing) {
    const PairingSummary& p = *in.pairing;
    s << "  pairs by rule    counts " << p.counts << ", association " << p.association;
    if (p.mode == PairingMode::kAssociation) {
      s << " (of " << p.candidates << " frames the count rule did not keep; " << p.rounds << " round"
        << (p.rounds == 1 ? "" : "s") << (p.converged ? "" : ", still changing");
      if (p.final_round) {
        s << "; final round over them and " << p.skipped_frames << " skipped frames: +" << p.final_round_pairs;
      }
      s << ")";
    } else {
      s << " (pairing counts)";
    }
    s << "\n";
    if (!p.note.empty()) s << "  association      " << p.note << "\n";
  }
  s << "  rotation_vector  " << fmt("[%.6f, %.6f, %.6f] rad", e.rotation_vector.x(),
                                    e.rotation_vector.y(), e.rotation_vector.z())
    << "  (rotation angle " << fmt("%.3f", Eigen::AngleAxisd(R).angle() * kDeg, 0, 0)
    << " deg)\n";
  for (int row = 0; row < 3; ++row) {
    s << (row == 0 ? "  rotation_matrix  " : "                   ")
      << fmt("[%9.6f %9.6f %9.6f]", R(row, 0), R(row, 1), R(row, 2)) << "\n";
  }
  s << "  translation      "
    << fmt("[%.4f, %.4f, %.4f] m", e.translation.x(), e.translation.y(), e.translation.z())
    << "\n";
  s << "  quaternion_xyzw  " << fmt("[%.6f, %.6f, %.6f, ", q.x(), q.y(), q.z())
    << fmt("%.6f]", q.w(), 0, 0) << "\n";
  s << "  loss             " << fmt("%.4f px (bilinear %.4f; before refinement %.4f)", r.loss,
                                    r.loss_bilinear, r.evolution_loss)
    << "\n";
  if (r.ring_alias_turn != 0) {
    // A turned start refined to a clearly lower loss than the refinement's own end (ring_alias.hpp):
    // say so. Where it ends says how far the refinement had been (often a ring off, sometimes near).
    s << "  ring alias       "
      << fmt("refined again from the pose turned %.0f ring spacing(s) of %.2f deg about x: "
             "a clearly lower loss, kept",
             std::abs(static_cast<double>(r.ring_alias_turn)), r.ring_spacing_rad * kDeg, 0)
      << "\n";
  }
  s << "  time offset      " << timeOffsetText(r, in.quality ? in.quality->uncertainty : std::nullopt);
  if (r.time_offset_mode != TimeOffsetMode::kNone) {
    s << fmt("; loss %.4f px with it, %.4f px without", r.loss, r.loss_without_timing, 0);
  }
  s << "\n";
  if (in.truth) {
    s << "  truth            "
      << fmt("rotation error %.4f deg, translation error %.3f cm, ",
             in.truth->rotation_error_rad * kDeg, in.truth->translation_error_m * 100.0, 0)
      << fmt("loss of truth %.4f px vs result %.4f px (same %.0f pairs)", in.truth->truth_loss,
             r.loss, static_cast<double>(r.pairs_used))
      << "\n";
  }
  if (in.quality) s << formatQualitySummary(*in.quality);
  s << "  run time         " << fmt("%.2f s (optimizer %.2f s, %.0f loss evaluations)",
                                    in.total_seconds, r.seconds,
                                    static_cast<double>(r.evaluations))
    << "\n";
  s << "  result file      " << in.output_path << "\n";
  s << "  tf               " << staticTransformPublisherCommand(e, in.lidar_frame, in.camera_frame)
    << "\n";
  return s.str();
}

}  // namespace thermal_lidar_calibration
