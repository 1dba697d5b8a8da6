#pragma once
// One OpenGL context per thread, shared by the rendering nodes (camera, spectator) that run on
// it and released with the last of them; the first node on a thread chooses the back end.
#include <memory>

#include "somasim/render/context.hpp"

namespace somasim::plugins {

/// This thread's context, made with `backend` if there is none yet (`created` says so).
std::shared_ptr<render::RenderContext> thread_render_context(render::RenderBackend backend,
                                                             bool& created);

}  // namespace somasim::plugins
