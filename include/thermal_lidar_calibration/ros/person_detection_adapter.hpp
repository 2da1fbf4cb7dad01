#pragma once
// The person detectors on ROS messages: a raw thermal image becomes its person mask (mono8, same
// header and size), a raw point cloud becomes the points on people (float32 x, y, z + uint32
// `label`, same header). One adapter for the detection nodelets and for calibrate_bag --detect,
// so that live and offline detection are the same code; what comes out feeds the ingest path
// unchanged, exactly like masks and clusters from a detector of the user's own.

#include "thermal_lidar_calibration/app/parameters/detection_parameters.hpp"
#include "thermal_lidar_calibration/detection/lidar_person_detector.hpp"
#include "thermal_lidar_calibration/detection/person_size_model.hpp"
#include "thermal_lidar_calibration/detection/thermal_person_segmenter.hpp"

#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <string>

namespace thermal_lidar_calibration {
namespace ros_io {

struct SegmentedImage {
  // The image as calibrated: the input itself, or flipped by thermal_input_flip (same encoding
  // and header).
  sensor_msgs::Image::ConstPtr image;
  sensor_msgs::Image::Ptr mask;  // mono8, 0 = background, ids 1..n
  detection::ThermalSegmentation segmentation;
};

struct DetectedCloud {
  // The points on people: float32 x, y, z, uint32 label 1..n, then every other field of the raw
  // scan as it was (intensity, ring, the per-point time of issue 21, ...), same header.
  sensor_msgs::PointCloud2::Ptr clusters;
  detection::LidarDetection detection;
};

class PersonDetectionAdapter {
 public:
  // Throws std::invalid_argument on a bad configuration (the detectors' validate()).
  explicit PersonDetectionAdapter(const DetectionParameters& params);

  // Throw std::invalid_argument naming `topic` on a message they cannot read (encoding, sizes,
  // fields): the caller reports it and goes on. segment() learns from the frames it sees (the
  // ground-plane size check): give it one camera's frames in time order.
  SegmentedImage segment(const sensor_msgs::Image::ConstPtr& image, const std::string& topic);
  DetectedCloud detect(const sensor_msgs::PointCloud2& cloud, const std::string& topic);

  const DetectionParameters& parameters() const { return params_; }

 private:
  DetectionParameters params_;
  detection::ThermalPersonSegmenter segmenter_;
  detection::PersonSizeModel person_size_;
  detection::LidarPersonDetector lidar_;
};

// float32 x, y, z + uint32 label, dense, with `header`.
sensor_msgs::PointCloud2::Ptr encodeLabelledPoints(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<std::uint32_t>& labels,
                                                   const std_msgs::Header& header);
// The same, followed by every field of `source` other than x, y, z and label (each with its
// datatype and count; a field that does not fit source's point_step is left out), copied from
// point source_index[i] of `source` for output point i. The source layout must have been checked
// (decodeCloud): x, y, z inside point_step and data for every point.
sensor_msgs::PointCloud2::Ptr encodeLabelledPoints(const std::vector<Eigen::Vector3f>& points,
                                                   const std::vector<std::uint32_t>& labels,
                                                   const sensor_msgs::PointCloud2& source,
                                                   const std::vector<std::uint32_t>& source_index);

}  // namespace ros_io
}  // namespace thermal_lidar_calibration
