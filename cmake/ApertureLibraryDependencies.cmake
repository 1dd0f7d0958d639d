# What the aperture libraries link (every package from Debian 12; scripts/install-deps.sh installs
# them). Included by the build (cmake/ApertureDependencies.cmake) and, installed next to it, by
# apertureConfig.cmake, so a consumer's find_package(aperture) finds the same packages: there
# through find_dependency (a missing package makes aperture NOT_FOUND with its name).
if(CMAKE_FIND_PACKAGE_NAME STREQUAL "aperture")
  include(CMakeFindDependencyMacro)
  macro(aperture_find_package)
    find_dependency(${ARGN})
  endmacro()
else()
  macro(aperture_find_package)
    find_package(${ARGN} REQUIRED)
  endmacro()
endif()

aperture_find_package(Eigen3 3.4 NO_MODULE)
# optflow and ximgproc come from libopencv-contrib-dev (DeepFlow, DualTVL1, RLOF, PCAFlow,
# SparseToDense; the fast global smoother of TS²P's edge-aware flow refinement).
aperture_find_package(OpenCV 4 COMPONENTS core imgproc imgcodecs videoio calib3d features2d video
                      optflow ximgproc)
aperture_find_package(TBB)
aperture_find_package(yaml-cpp)
aperture_find_package(nlohmann_json 3)
aperture_find_package(NLopt)
# libvisp-dev 3.5 (visual servoing): imported targets per module; servo/ links them PRIVATE (a
# consumer of the installed servo library links them too) and the servo tests add visp_robot for
# the vpSimulatorCamera free-camera simulation.
aperture_find_package(VISP 3.5 COMPONENTS visp_core visp_visual_features visp_vs visp_robot
                      visp_detection)
# visp_detection: vpDetectorAprilTag (servo/visp_tag_detector.cc).
set(APERTURE_VISP visp_vs visp_visual_features visp_detection visp_core)
# libapriltag-dev ships a CMake config (target apriltag::apriltag, includes <apriltag/...>).
aperture_find_package(apriltag)
# libceres-dev: the tag map's pose graph (perception/tags/tag_map.cc).
aperture_find_package(Ceres)
# libembree-dev (Embree 3.13): the renderer's optional Embree back end (sim/render/embree_scene.h,
# RayBackend::kEmbree; docs/results/speed.md). APERTURE_EMBREE is ON when Embree is found; OFF,
# the back end is left out and asking for it throws. aperture_sim links it privately, so a
# consumer of a build with it finds it too (apertureConfig.cmake sets APERTURE_EMBREE).
if(CMAKE_FIND_PACKAGE_NAME STREQUAL "aperture")
  if(APERTURE_EMBREE)
    find_dependency(embree 3)
  endif()
else()
  find_package(embree 3 QUIET)
  option(APERTURE_EMBREE "Build the renderer's Embree back end (libembree-dev)" ${embree_FOUND})
  if(APERTURE_EMBREE)
    find_package(embree 3 REQUIRED)
  endif()
endif()

# yaml-cpp 0.7 on Debian exports the plain target name `yaml-cpp`.
set(APERTURE_OPENCV_CORE opencv_core opencv_imgproc opencv_imgcodecs)
set(APERTURE_OPENCV_ALL opencv_core opencv_imgproc opencv_imgcodecs opencv_videoio opencv_calib3d
    opencv_features2d opencv_video opencv_optflow opencv_ximgproc)

# libopengv-dev ships no CMake config: wrap the library in an imported target.
find_path(OPENGV_INCLUDE_DIR opengv/absolute_pose/methods.hpp REQUIRED)
find_library(OPENGV_LIBRARY opengv REQUIRED)
if(NOT TARGET opengv::opengv)
  add_library(opengv::opengv UNKNOWN IMPORTED)
  set_target_properties(opengv::opengv PROPERTIES IMPORTED_LOCATION "${OPENGV_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${OPENGV_INCLUDE_DIR}")
endif()

# ROS1 bags (librosbag-storage-dev, libsensor-msgs-dev): Debian ships catkin configs that expect a
# catkin workspace, so wrap the libraries in one imported target. rosbag/bag.h includes
# pluginlib, class_loader, rcpputils, rcutils and ament_index_cpp headers, which Debian nests one
# level deeper (/usr/include/<name>/<name>/...).
if(NOT TARGET aperture_ros::rosbag)
  find_path(ROSBAG_INCLUDE_DIR rosbag/bag.h REQUIRED)
  find_path(SENSOR_MSGS_INCLUDE_DIR sensor_msgs/Image.h REQUIRED)
  set(rosbag_include_dirs ${ROSBAG_INCLUDE_DIR} ${SENSOR_MSGS_INCLUDE_DIR})
  foreach(header pluginlib/class_loader.hpp class_loader/class_loader.hpp
                 rcpputils/shared_library.hpp rcutils/allocator.h
                 ament_index_cpp/get_package_prefix.hpp)
    get_filename_component(name ${header} DIRECTORY)
    find_path(ROSBAG_${name}_INCLUDE_DIR ${header} PATH_SUFFIXES ${name} REQUIRED)
    list(APPEND rosbag_include_dirs ${ROSBAG_${name}_INCLUDE_DIR})
  endforeach()
  set(rosbag_libraries)
  foreach(name rosbag_storage roscpp_serialization rostime cpp_common console_bridge
               boost_filesystem)
    find_library(ROSBAG_${name}_LIBRARY ${name} REQUIRED)
    list(APPEND rosbag_libraries ${ROSBAG_${name}_LIBRARY})
  endforeach()
  add_library(aperture_ros::rosbag INTERFACE IMPORTED)
  list(REMOVE_DUPLICATES rosbag_include_dirs)
  set_target_properties(aperture_ros::rosbag PROPERTIES
                        INTERFACE_INCLUDE_DIRECTORIES "${rosbag_include_dirs}"
                        INTERFACE_LINK_LIBRARIES "${rosbag_libraries}")
endif()

# liblinear-dev (the linear SVM of seed 003's monocular depth) ships no CMake config: wrap it in an
# imported target (perception links it PRIVATE, for mono_depth_trainer.cc only).
find_path(LIBLINEAR_INCLUDE_DIR linear.h REQUIRED)
find_library(LIBLINEAR_LIBRARY linear REQUIRED)
if(NOT TARGET liblinear::liblinear)
  add_library(liblinear::liblinear UNKNOWN IMPORTED)
  set_target_properties(liblinear::liblinear PROPERTIES IMPORTED_LOCATION "${LIBLINEAR_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${LIBLINEAR_INCLUDE_DIR}")
endif()

# libpcl-dev: Euclidean clustering of seed 003's waypoint selection (planning/mono_nav only; its
# headers are heavy, so only that .cc includes them and planning links it privately).
# PCLConfig also looks for VTK (optional, for components we do not use), and Debian's VTK config
# fails without MPI targets: keep VTK out of that search.
set(CMAKE_DISABLE_FIND_PACKAGE_VTK TRUE)
aperture_find_package(PCL 1.13 COMPONENTS common search segmentation kdtree)
unset(CMAKE_DISABLE_FIND_PACKAGE_VTK)
