#include "perception/tags/tag_map_writer.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace aperture::perception {
namespace {

void EmitPose(YAML::Emitter& out, const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.rotation());
  const Eigen::Vector3d& p = T.translation();
  out << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "p_m" << YAML::Value << YAML::Flow
      << std::vector<double>{p.x(), p.y(), p.z()};
  out << YAML::Key << "q_xyzw" << YAML::Value << YAML::Flow
      << std::vector<double>{q.x(), q.y(), q.z(), q.w()};
  out << YAML::EndMap;
}

}  // namespace

void WriteTagMapYaml(const std::string& path, const std::vector<MappedTag>& tags,
                     const TagMapParams& params) {
  YAML::Emitter out;
  out.SetDoublePrecision(12);  // significant digits: sub-micrometre over a field
  out << YAML::BeginMap;
  out << YAML::Key << "origin_id" << YAML::Value << params.origin_id;
  out << YAML::Key << "tags" << YAML::Value << YAML::BeginSeq;
  for (const MappedTag& tag : tags) {
    out << YAML::BeginMap;
    out << YAML::Key << "family" << YAML::Value << tag.family;
    out << YAML::Key << "id" << YAML::Value << tag.id;
    out << YAML::Key << "size_m" << YAML::Value << tag.size_m;
    out << YAML::Key << "T_WT" << YAML::Value;
    EmitPose(out, tag.T_WT);
    if (tag.has_covariance) {
      std::vector<double> entries;
      for (int r = 0; r < 6; ++r) {
        for (int c = 0; c < 6; ++c) entries.push_back(tag.covariance(r, c));
      }
      out << YAML::Key << "covariance" << YAML::Value << YAML::Flow << entries;
    }
    out << YAML::Key << "T_WT_initial" << YAML::Value;
    EmitPose(out, tag.T_WT_initial);
    out << YAML::Key << "observations" << YAML::Value << tag.observations;
    out << YAML::Key << "rejected" << YAML::Value << tag.rejected;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  std::ofstream file(path);
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error("cannot write tag map '" + path + "'");
}

cv::Mat DrawTagMapTopView(const std::vector<MappedTag>& tags, const TopViewOptions& options) {
  Eigen::Vector2d low(0.0, 0.0), high(1.0, 1.0);
  for (const MappedTag& tag : tags) {
    low = low.cwiseMin(tag.T_WT.translation().head<2>());
    high = high.cwiseMax(tag.T_WT.translation().head<2>());
  }
  low.array() -= options.margin_m;
  high.array() += options.margin_m;
  const double s = options.pixels_per_m;
  const int width = static_cast<int>(std::ceil((high.x() - low.x()) * s));
  const int height = static_cast<int>(std::ceil((high.y() - low.y()) * s));
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  // Looking down -z_W with x_W to the right and y_W up.
  auto to_px = [&](const Eigen::Vector3d& p_W) {
    return cv::Point2d((p_W.x() - low.x()) * s, (high.y() - p_W.y()) * s);
  };
  for (double x = std::ceil(low.x()); x <= high.x(); x += 1.0) {
    cv::line(image, to_px({x, low.y(), 0}), to_px({x, high.y(), 0}), cv::Scalar(225, 225, 225));
  }
  for (double y = std::ceil(low.y()); y <= high.y(); y += 1.0) {
    cv::line(image, to_px({low.x(), y, 0}), to_px({high.x(), y, 0}), cv::Scalar(225, 225, 225));
  }
  cv::arrowedLine(image, to_px({0, 0, 0}), to_px({1, 0, 0}), cv::Scalar(0, 0, 200), 1, cv::LINE_AA,
                  0, 0.05);
  cv::arrowedLine(image, to_px({0, 0, 0}), to_px({0, 1, 0}), cv::Scalar(0, 160, 0), 1, cv::LINE_AA,
                  0, 0.05);
  for (const MappedTag& tag : tags) {
    const cv::Point2d initial = to_px(tag.T_WT_initial.translation());
    cv::drawMarker(image, initial, cv::Scalar(160, 160, 160), cv::MARKER_CROSS, 8, 1);
    std::vector<cv::Point> outline;
    for (int k = 0; k < 4; ++k) {
      const double sx = (k == 1 || k == 2) ? 0.5 : -0.5;
      const double sy = (k >= 2) ? -0.5 : 0.5;
      const cv::Point2d px = to_px(tag.T_WT * Eigen::Vector3d(sx * tag.size_m, sy * tag.size_m, 0));
      outline.emplace_back(cvRound(px.x), cvRound(px.y));
    }
    cv::polylines(image, outline, true, cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
    const cv::Point2d centre = to_px(tag.T_WT.translation());
    cv::line(image, centre, to_px(tag.T_WT * Eigen::Vector3d(tag.size_m / 2, 0, 0)),
             cv::Scalar(0, 0, 220), 2, cv::LINE_AA);
    if (tag.has_covariance) {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(
          tag.covariance.topLeftCorner<2, 2>());
      const Eigen::Vector2d axes_px =
          options.ellipse_scale * eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt() * s;
      const Eigen::Vector2d major = eigen.eigenvectors().col(1);
      // Image y runs against y_W.
      const double angle_deg = std::atan2(-major.y(), major.x()) * 180.0 / M_PI;
      cv::ellipse(image, centre, cv::Size2d(std::max(axes_px.y(), 1.0), std::max(axes_px.x(), 1.0)),
                  angle_deg, 0, 360, cv::Scalar(200, 100, 0), 1, cv::LINE_AA);
    }
    cv::putText(image, std::to_string(tag.id), centre + cv::Point2d(6, -6),
                cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  return image;
}

void WriteTagMapTopView(const std::string& path, const std::vector<MappedTag>& tags,
                        const TopViewOptions& options) {
  if (!cv::imwrite(path, DrawTagMapTopView(tags, options)))
    throw std::runtime_error("cannot write tag map image '" + path + "'");
}

}  // namespace aperture::perception
