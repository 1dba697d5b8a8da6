#include "render_worker.hpp"

#include <utility>

namespace somasim::plugins {

RenderWorker::RenderWorker(render::RenderBackend backend)
    : thread_([this, backend] { loop(backend); }) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return started_; });
  if (error_) {
    std::exception_ptr error = std::exchange(error_, nullptr);
    lock.unlock();
    thread_.join();
    std::rethrow_exception(error);
  }
}

RenderWorker::~RenderWorker() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void RenderWorker::submit(Job job) {
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back(std::move(job));
  }
  changed_.notify_all();
}

void RenderWorker::wait() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return jobs_.empty() && !running_job_; });
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void RenderWorker::loop(render::RenderBackend backend) {
  std::unique_ptr<render::RenderContext> context;
  try {
    context = render::make_render_context(backend);
  } catch (...) {
    std::lock_guard lock(mutex_);
    error_ = std::current_exception();
    started_ = true;
    changed_.notify_all();
    return;
  }
  {
    std::lock_guard lock(mutex_);
    started_ = true;
  }
  changed_.notify_all();
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return !jobs_.empty() || stopping_; });
      if (jobs_.empty()) break;  // stopping, every job run
      job = std::move(jobs_.front());
      jobs_.pop_front();
      running_job_ = true;
      if (error_) job = nullptr;  // after a failure, drop jobs until wait() reports it
    }
    std::exception_ptr failure;
    if (job) {
      try {
        job(*context);
      } catch (...) {
        failure = std::current_exception();
      }
    }
    {
      std::lock_guard lock(mutex_);
      running_job_ = false;
      if (failure && !error_) error_ = failure;
    }
    changed_.notify_all();
  }
  context.reset();  // on the thread that made it current
}

}  // namespace somasim::plugins
