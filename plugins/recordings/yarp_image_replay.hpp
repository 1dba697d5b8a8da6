#pragma once
// yarp_image_replay: images recorded by yarpdatadumper (info.log 'Type: Image', one image file
// per data.log line, e.g. /icub/cam/left) replayed on an RGB image port at their recorded
// times. At each step the latest image due is read (PPM, PNG, JPEG: whatever OpenCV reads);
// images overtaken by a later one before the node stepped are counted as skipped.
#include <memory>
#include <string>

#include "replay_log.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/render/ports.hpp"

namespace somasim::plugins {

class YarpImageReplay : public Plugin {
 public:
  struct Config {
    ReplayLogParams log;
    std::string camera;
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    Out<RgbImage> image;
    template <class V>
    void visit(V& v);
  };

  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  Config config_;
  Ports ports_;
  recordings::DatadumperLog log_;
  std::unique_ptr<recordings::ReplayCursor> cursor_;
  std::int64_t skipped_ = 0;
  int width_ = 0, height_ = 0;  // of the first image; later ones must match
};

}  // namespace somasim::plugins
