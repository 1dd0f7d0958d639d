#pragma once
// The flight seen from above (x_W, y_W) and from the side (x_W, z_W) for report.html: the
// ground-truth path with the scene's objects drawn as outlines (the convex hull of each object's
// shape projected onto the view plane), so a reader sees where the vehicle went relative to the
// gap, the trees or the tags.
#include <string>
#include <vector>

#include "control/quad_state.h"
#include "output/html_report.h"
#include "sim/scene/scene.h"

namespace aperture::apps {

// Adds a "Path" section with both views. Objects named in `skipped` (e.g. the ones riding on the
// vehicle), ground planes and LEDs (no extent) are left out.
void AddPathViews(const std::vector<control::QuadState>& trajectory, const sim::Scene& scene,
                  const std::vector<std::string>& skipped, output::HtmlReport* report);

}  // namespace aperture::apps
