#include "sim/render/render_profile.h"

namespace aperture::sim {
namespace {

thread_local RenderProfile* current_render_profile = nullptr;

}  // namespace

RenderProfileScope::RenderProfileScope(RenderProfile* profile) : previous_(current_render_profile) {
  current_render_profile = profile;
}

RenderProfileScope::~RenderProfileScope() { current_render_profile = previous_; }

RenderProfile* RenderProfileScope::Current() { return current_render_profile; }

double* RenderStage(double RenderProfile::*stage) {
  RenderProfile* profile = current_render_profile;
  return profile != nullptr ? &(profile->*stage) : nullptr;
}

}  // namespace aperture::sim
