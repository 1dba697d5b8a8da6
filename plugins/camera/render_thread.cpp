#include "render_thread.hpp"

namespace somasim::plugins {

std::shared_ptr<render::RenderContext> thread_render_context(render::RenderBackend backend,
                                                             bool& created) {
  thread_local std::weak_ptr<render::RenderContext> shared;
  std::shared_ptr<render::RenderContext> context = shared.lock();
  created = !context;
  if (!context) {
    context = render::make_render_context(backend);
    shared = context;
  }
  return context;
}

}  // namespace somasim::plugins
