// Camera model costs: projection with Jacobian and iterative unprojection, per model.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "perception/camera/camera_factory.h"

namespace aperture::perception {
namespace {

std::unique_ptr<CameraModel> MakeCamera(int index) {
  switch (index) {
    case 0:
      return CreateCameraModel("pinhole", 752, 480,
                               Eigen::Vector4d(458.654, 457.296, 367.215, 248.375),
                               Eigen::VectorXd());
    case 1:  // EuRoC cam0
      return CreateCameraModel(
          "radtan", 752, 480, Eigen::Vector4d(458.654, 457.296, 367.215, 248.375),
          Eigen::Vector4d(-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05));
    default:  // 180 deg fisheye
      return CreateCameraModel("equidistant", 752, 480, Eigen::Vector4d(140.0, 140.0, 375.5, 239.5),
                               Eigen::Vector4d(-0.02, 0.003, 0.0, 0.0));
  }
}

// 1024 random in-image pixels (fixed seed).
std::vector<Eigen::Vector2d> Pixels(const CameraModel& camera) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, camera.width() - 1.0),
      v(0.0, camera.height() - 1.0);
  std::vector<Eigen::Vector2d> pixels(1024);
  for (auto& px : pixels) px = Eigen::Vector2d(u(rng), v(rng));
  return pixels;
}

void BM_ProjectWithJacobian(benchmark::State& state) {
  const auto camera = MakeCamera(static_cast<int>(state.range(0)));
  std::vector<Eigen::Vector3d> points;
  for (const auto& px : Pixels(*camera)) points.push_back(2.0 * camera->Unproject(px));
  size_t i = 0;
  Eigen::Vector2d px;
  Eigen::Matrix<double, 2, 3> J;
  for (auto _ : state) {
    benchmark::DoNotOptimize(camera->Project(points[i++ & 1023], &px, &J));
    benchmark::DoNotOptimize(J);
  }
  state.SetLabel(camera->model_name());
}

void BM_Unproject(benchmark::State& state) {
  const auto camera = MakeCamera(static_cast<int>(state.range(0)));
  const std::vector<Eigen::Vector2d> pixels = Pixels(*camera);
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(camera->Unproject(pixels[i++ & 1023]));
  state.SetLabel(camera->model_name());
}

BENCHMARK(BM_ProjectWithJacobian)->DenseRange(0, 2);
BENCHMARK(BM_Unproject)->DenseRange(0, 2);

}  // namespace
}  // namespace aperture::perception
