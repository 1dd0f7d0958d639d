# Every package here comes from Debian 12 (scripts/install-deps.sh installs them).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
# optflow comes from libopencv-contrib-dev (DeepFlow, DualTVL1, RLOF, PCAFlow, SparseToDense).
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs videoio calib3d features2d video
             optflow)
find_package(TBB REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(NLopt REQUIRED)
find_package(GTest REQUIRED)
find_package(benchmark REQUIRED)
# libvisp-dev 3.5 (visual servoing): imported targets per module; servo/ links them PRIVATE and
# its tests add visp_robot for the vpSimulatorCamera free-camera simulation.
find_package(VISP 3.5 REQUIRED COMPONENTS visp_core visp_visual_features visp_vs visp_robot)
set(APERTURE_VISP visp_vs visp_visual_features visp_core)
# libapriltag-dev ships a CMake config (target apriltag::apriltag, includes <apriltag/...>).
find_package(apriltag REQUIRED)

set(APERTURE_OPENCV_CORE opencv_core opencv_imgproc opencv_imgcodecs)
set(APERTURE_OPENCV_ALL opencv_core opencv_imgproc opencv_imgcodecs opencv_videoio opencv_calib3d
    opencv_features2d opencv_video opencv_optflow)
# yaml-cpp 0.7 on Debian exports the plain target name `yaml-cpp`.

# libopengv-dev ships no CMake config: wrap the library in an imported target.
find_path(OPENGV_INCLUDE_DIR opengv/absolute_pose/methods.hpp REQUIRED)
find_library(OPENGV_LIBRARY opengv REQUIRED)
if(NOT TARGET opengv::opengv)
  add_library(opengv::opengv UNKNOWN IMPORTED)
  set_target_properties(opengv::opengv PROPERTIES IMPORTED_LOCATION "${OPENGV_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${OPENGV_INCLUDE_DIR}")
endif()
