// aperture.run: the front ends of `aperture run` over a frame source, results back as NumPy arrays
// instead of an output folder (the same registry, configuration layering and frame sources).
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>

#include "config/config_tree.h"
#include "perception/graph/builtin_front_ends.h"
#include "perception/graph/front_end_registry.h"
#include "perception/graph/serial_executor.h"
#include "perception/graph/source_run.h"
#include "perception/io/open_frame_source.h"
#include "python/bindings.h"

namespace aperture::python {
namespace py = pybind11;

namespace {

struct PoseStream {
  std::vector<double> t_s;
  std::vector<Eigen::Matrix4d> T;
};

struct RunRecord {
  std::string source_description;
  std::vector<double> t_s, index;
  std::map<std::string, std::vector<double>> metrics;
  std::map<std::string, PoseStream> poses;
  std::vector<perception::SkippedFrame> skipped;
};

RunRecord RunFrontEnds(const std::string& source_spec, const std::vector<std::string>& front_ends,
                       const std::string& calibration_path,
                       const std::vector<std::string>& config_files,
                       const std::vector<std::string>& set_items,
                       const perception::FrameSourceOptions& source_options, int max_frames) {
  const config::ConfigTree tree = config::ConfigTree::FromCommandLine("", config_files, set_items);
  perception::FrontEndResources resources;
  if (!calibration_path.empty()) {
    resources.calibration = perception::LoadCameraCalibration(calibration_path);
  }
  perception::FrontEndRegistry registry;
  perception::RegisterBuiltinFrontEnds(registry);
  config::ParamReader root = tree.Reader();
  perception::FrameGraph graph = registry.BuildGraph(front_ends, root, resources);
  root.RejectUnknownKeys();
  std::unique_ptr<perception::FrameSource> source =
      perception::OpenFrameSource(source_spec, source_options);
  perception::SerialExecutor executor(graph);

  RunRecord record;
  record.source_description = source->Describe();
  perception::RunSource(
      *source, graph, executor, resources, max_frames,
      [&](const perception::Frame& frame, const perception::FrameSlots& slots) {
        record.t_s.push_back(frame.t_s);
        record.index.push_back(frame.index);
        for (const auto& [name, value] : graph.CollectMetrics(slots)) {
          record.metrics[name].push_back(value);
        }
        for (const perception::PoseObservation& pose : graph.CollectPoses(slots)) {
          PoseStream& stream = record.poses[pose.stream];  // what <stream>.csv of `aperture run`
          stream.t_s.push_back(frame.t_s);
          stream.T.push_back(pose.T_fixed_moving().matrix());
        }
      });
  record.skipped = source->SkippedFrames();
  return record;
}

py::array_t<double> Array(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

py::dict ToDict(const RunRecord& record) {
  py::dict metrics, poses;
  for (const auto& [name, values] : record.metrics) metrics[py::str(name)] = Array(values);
  for (const auto& [name, stream] : record.poses) {
    py::array_t<double> T(
        {static_cast<py::ssize_t>(stream.T.size()), py::ssize_t(4), py::ssize_t(4)});
    auto view = T.mutable_unchecked<3>();
    for (size_t k = 0; k < stream.T.size(); ++k) {
      for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) view(k, r, c) = stream.T[k](r, c);
      }
    }
    poses[py::str(name)] = py::dict(py::arg("t_s") = Array(stream.t_s), py::arg("T") = T);
  }
  py::list skipped;
  for (const perception::SkippedFrame& skip : record.skipped) {
    skipped.append(py::make_tuple(skip.item, skip.reason));
  }
  return py::dict(py::arg("source") = record.source_description,
                  py::arg("frames") = record.t_s.size(), py::arg("t_s") = Array(record.t_s),
                  py::arg("index") = Array(record.index), py::arg("metrics") = metrics,
                  py::arg("poses") = poses, py::arg("skipped") = skipped);
}

}  // namespace

void BindRun(py::module_& m) {
  m.def(
      "run",
      [](const std::string& source, const std::vector<std::string>& frontends,
         const std::string& calib, const std::vector<std::string>& config,
         const std::vector<std::string>& set, double fps, bool color, bool skip_bad_frames,
         int max_frames) {
        perception::FrameSourceOptions options;
        options.fps = fps;
        options.color_mode = color ? perception::ColorMode::kColor : perception::ColorMode::kGray;
        options.skip_bad_frames = skip_bad_frames;
        RunRecord record;
        {
          py::gil_scoped_release release;
          record = RunFrontEnds(source, frontends, calib, config, set, options, max_frames);
        }
        return ToDict(record);
      },
      py::arg("source"), py::arg("frontends") = std::vector<std::string>{"image_quality"},
      py::arg("calib") = "", py::arg("config") = std::vector<std::string>{},
      py::arg("set") = std::vector<std::string>{}, py::arg("fps") = 0.0, py::arg("color") = false,
      py::arg("skip_bad_frames") = false, py::arg("max_frames") = 0,
      R"doc(Runs front ends over a source, like `aperture run` without the output folder.

source: image folder, video file or camera:N; frontends: names (aperture.front_ends());
calib: calibration file; config: YAML files; set: ["key=value", ...] overrides.
Returns {"source", "frames", "t_s", "index", "metrics": {"<node>.<metric>": array},
"poses": {stream: {"t_s": array, "T": array (K, 4, 4)}} (T as in <stream>.csv: T_XC for a
fixed target such as the gap, T_CX for a fixed camera), "skipped": [(item, reason)]}.
Raises ValueError for bad arguments (unknown front end or key, missing calibration) and
RuntimeError for unreadable input.)doc");

  m.def(
      "front_ends",
      [] {
        perception::FrontEndRegistry registry;
        perception::RegisterBuiltinFrontEnds(registry);
        return registry.Names();
      },
      "Names of the front ends aperture.run knows.");
}

}  // namespace aperture::python
