// The pairing keys (issue 23): which rule pairs the frames, the matcher's margins, the initial
// extrinsic and the check it must pass.

#include "thermal_lidar_calibration/app/parameters/association_parameters.hpp"

namespace thermal_lidar_calibration {

void addAssociationRows(ParameterTable<CoreParameters>& t) {
  auto pairing = t.group<PairingConfig>([](CoreParameters& p) -> PairingConfig& { return p.pairing; });
  auto association = t.group<AssociationConfig>(
      [](CoreParameters& p) -> AssociationConfig& { return p.pairing.association; });
  auto top = t.fields();
  t.section("Pairing by association (beyond the paper; issue #23)");
  pairing.choice("pairing", &PairingConfig::mode,
                 {{"counts", PairingMode::kCounts}, {"association", PairingMode::kAssociation}},
                 "must be 'counts' or 'association'",
                 "counts: the paper's rule alone (equal people counts); association: after the first fit on the "
                 "count rule's pairs, every frame with people in both modalities is paired person by person at "
                 "the extrinsic, refitted until the pairs stop changing (a drift watch pairs them at its reference)",
                 "refine none (the paper's method) always pairs by counts");
  association.real("association_min_overlap", &AssociationConfig::min_overlap, kConfigRange, "",
                   "a LiDAR person's share of in-view points that must land on one mask region to pair with it");
  association.real("association_margin", &AssociationConfig::margin, kConfigRange, "",
                   "that share must beat the person's second region, and every other person's share of that "
                   "region, by this much (else both are left out)");
  association.real("association_tolerance_px", &AssociationConfig::tolerance_px, kConfigRange, "px",
                   "a projected point this close to a region counts as on it");
  association.integer("association_max_rounds", &AssociationConfig::max_rounds, kConfigRange, "",
                      "associate-and-refit rounds at most (they stop when the pairs no longer change)");
  pairing.boolean("association_final_round", &PairingConfig::final_round,
                  "after the rounds, the frames skip_frames passed over are paired as well (every frame with people "
                  "in both modalities, the skip rule off) and the fit refined once more on them; the bootstrap "
                  "still resamples only the pairs the skip rule made");
  top.text("initial_extrinsic_file", &CoreParameters::initial_extrinsic_file,
           TextRule::optional("start from the paper's first fit"),
           "a result YAML (rotation_vector or rotation_matrix, translation; its time_offset_s) to start "
           "association from instead of the first fit, if the count rule's pairs agree with it");
  pairing.real("initial_extrinsic_min_agreement", &PairingConfig::min_initial_agreement, kConfigRange, "",
               "the share of the count rule's pairs within threshold_sample_px of the initial extrinsic it "
               "needs; else it is refused (the result's association note says so) and the paper's fit runs");
}

AssociationPairing associationPairing(const CoreParameters& p) {
  AssociationPairing a{p.pairing.association, PairingLimits{p.gate.max_people, p.gate.skip_frames}};
  a.config.min_points_in_view = p.gate.min_points_per_cluster;
  return a;
}

std::optional<AssociationPairing> associationIfAsked(const CoreParameters& p) {
  if (!pairsByAssociation(p.pairing, p.calibration)) return std::nullopt;
  return associationPairing(p);
}

}  // namespace thermal_lidar_calibration
