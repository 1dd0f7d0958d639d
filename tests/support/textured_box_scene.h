#pragma once
// Test support: a value-noise textured ground plane and a 0.5 x 2 x 2 m textured box centred at
// (4, 0, 1) m in W, in front of a vehicle at the origin looking along x: edges and texture for the
// renderer's supersampling and noise to work on.
#include <Eigen/Geometry>

#include "sim/scene/scene.h"
#include "sim/scene/textures.h"

namespace aperture::test_support {

inline sim::Scene TexturedBoxScene() {
  sim::Scene scene;
  sim::ProceduralTextureParams texture;
  scene.AddObject(
      {"ground", sim::GroundPlane{}, sim::Material{sim::MakeValueNoiseTexture(texture)}});
  Eigen::Isometry3d T_WO = Eigen::Isometry3d::Identity();
  T_WO.translation() = Eigen::Vector3d(4.0, 0.0, 1.0);
  scene.AddObject({"box", sim::Box{Eigen::Vector3d(0.5, 2.0, 2.0)},
                   sim::Material{sim::MakeValueNoiseTexture(texture)}, T_WO});
  return scene;
}

}  // namespace aperture::test_support
