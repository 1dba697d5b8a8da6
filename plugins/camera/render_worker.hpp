#pragma once
// A thread of its own with its own OpenGL context, running render jobs one at a time in the
// order they were handed over: a node renders there while the simulation goes on, and collects
// the result a step later.
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

#include "somasim/render/context.hpp"

namespace somasim::plugins {

class RenderWorker {
 public:
  using Job = std::function<void(render::RenderContext&)>;

  /// Starts the thread and makes its context with `backend`; throws that context's error.
  explicit RenderWorker(render::RenderBackend backend);
  /// Runs the jobs handed over, then ends the context and the thread (errors are dropped).
  ~RenderWorker();
  RenderWorker(const RenderWorker&) = delete;
  RenderWorker& operator=(const RenderWorker&) = delete;
  RenderWorker(RenderWorker&&) = delete;
  RenderWorker& operator=(RenderWorker&&) = delete;

  /// Hands `job` over and returns at once. A job's exception ends no thread: the next wait()
  /// throws it (later jobs are dropped until then).
  void submit(Job job);
  /// Returns when every job handed over has run; throws the first job's exception, once.
  void wait();

 private:
  void loop(render::RenderBackend backend);

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  bool running_job_ = false;
  bool stopping_ = false;
  bool started_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace somasim::plugins
