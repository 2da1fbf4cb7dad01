# Precompiled headers: build time only (issue 22: CI, apt + build + every test, within 12 minutes
# on a fresh 2-core machine). Most of a cold build went to parsing the same system headers again
# in every file: Eigen, OpenCV and the standard library take ~1.5 s of CPU a file, roscpp, rosbag
# and the messages ~2.5 s more, gtest ~1 s. Each group of targets below parses them once.
# Included at the end of CMakeLists.txt, once every target exists; a target that is not there
# (testing off) is skipped. TLC_PRECOMPILED_HEADERS=OFF builds without them: a file must still
# include what it uses, which that build checks.
option(TLC_PRECOMPILED_HEADERS "Precompile the system headers most files include (build time only)" ON)
if(NOT TLC_PRECOMPILED_HEADERS)
  return()
endif()

set(TLC_PCH_ROS_FREE
  <algorithm> <cmath> <cstdint> <functional> <map> <memory> <optional> <sstream> <stdexcept>
  <string> <vector> <Eigen/Core> <Eigen/Geometry> <opencv2/core.hpp> <opencv2/imgproc.hpp>)
set(TLC_PCH_ROS
  <ros/ros.h> <rosbag/bag.h> <rosbag/view.h> <sensor_msgs/CameraInfo.h> <sensor_msgs/Image.h>
  <sensor_msgs/PointCloud2.h> <sensor_msgs/point_cloud2_iterator.h>)

# tlc_precompile(HEADERS <header>... TARGETS <target>...): the first target there precompiles the
# headers, the others reuse its precompiled header (they must compile with the same flags; GCC
# says so with -Winvalid-pch when one does not, and then parses the headers itself).
function(tlc_precompile)
  cmake_parse_arguments(ARG "" "" "HEADERS;TARGETS" ${ARGN})
  set(first "")
  foreach(target ${ARG_TARGETS})
    if(NOT TARGET ${target})
      continue()
    elseif(first STREQUAL "")
      target_precompile_headers(${target} PRIVATE ${ARG_HEADERS})
      set(first ${target})
    else()
      target_precompile_headers(${target} REUSE_FROM ${first})
    endif()
  endforeach()
endfunction()

# The ROS-free libraries: one each, their flags differ (-O2 / -O3, OpenMP, PCL's definitions).
foreach(lib core synthetic detection app detection_tool)
  tlc_precompile(HEADERS ${TLC_PCH_ROS_FREE} TARGETS thermal_lidar_calibration_${lib})
endforeach()
# The loss kernels compile with their own floating-point flags (-fno-math-errno changes a
# predefined macro the headers read): they parse their headers themselves.
set_source_files_properties(${PROJECT_SOURCE_DIR}/src/core/loss_kernels.cpp PROPERTIES
  SKIP_PRECOMPILE_HEADERS ON)
# The ROS side: the adapters' library and the libraries over it (node/, tools/, the nodelets, the
# generator) share one precompiled header (they compile with the same flags). A shared library
# defines <target>_EXPORTS, which would make each one's differ (GCC: "not used because
# thermal_lidar_calibration_ros_EXPORTS not defined"); nothing here reads those macros (symbol
# visibility is the default), so they are not defined.
set(ros_libs "")
foreach(lib ros node tools nodelets synthetic_bag)
  set_target_properties(thermal_lidar_calibration_${lib} PROPERTIES DEFINE_SYMBOL "")
  list(APPEND ros_libs thermal_lidar_calibration_${lib})
endforeach()
tlc_precompile(HEADERS ${TLC_PCH_ROS_FREE} ${TLC_PCH_ROS} TARGETS ${ros_libs})

# The tests (gtest): those that link the ROS adapters (directly or through node/, tools/), those
# that link the detectors (directly or through app/: PCL's targets add -fPIC, which a precompiled
# header must share; GCC warned -Winvalid-pch for each and parsed the headers itself), and those
# that link only other ROS-free parts.
set(ros_tests "")
set(detection_tests "")
set(ros_free_tests "")
foreach(dir ${PROJECT_SOURCE_DIR} ${PROJECT_SOURCE_DIR}/test)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target ${targets})
    if(NOT target MATCHES "^test_")
      continue()
    endif()
    get_target_property(links ${target} LINK_LIBRARIES)
    if(links MATCHES "thermal_lidar_calibration_(ros|node|tools|synthetic_bag)(;|$)")
      list(APPEND ros_tests ${target})
    elseif(links MATCHES "thermal_lidar_calibration_(app|detection|detection_tool)(;|$)")
      list(APPEND detection_tests ${target})
    elseif(links MATCHES "thermal_lidar_calibration_")
      list(APPEND ros_free_tests ${target})
    endif()
  endforeach()
endforeach()
tlc_precompile(HEADERS ${TLC_PCH_ROS_FREE} <gtest/gtest.h> TARGETS ${ros_free_tests})
tlc_precompile(HEADERS ${TLC_PCH_ROS_FREE} <gtest/gtest.h> TARGETS ${detection_tests})
tlc_precompile(HEADERS ${TLC_PCH_ROS_FREE} ${TLC_PCH_ROS} <gtest/gtest.h> TARGETS ${ros_tests})
