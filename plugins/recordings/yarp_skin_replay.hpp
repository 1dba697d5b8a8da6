#pragma once
// yarp_skin_replay: the iCub skin's contact lists recorded by yarpdatadumper (port
// /skinManager/skin_events:o) replayed as skin contact events at their recorded times.
//
// Each data.log line is a contact list (recordings/skin_contact_list.hpp); every contact on a
// mapped skin part with at least `min_taxels` taxels touches that part. A part's touch becomes
// one event when the part was untouched for `new_event_after_s` before it (the skin's contact
// episodes; 0: every line's contact is an event), with the taxels, centre of pressure and
// normal of that first line. With a layout file for the part (the iCub's positions files
// read as layouts), taxel ids become the virtual taxels (modules) they belong to.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "replay_log.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/recordings/skin_contact_list.hpp"
#include "somasim/skin/ports.hpp"
#include "somasim/skin/skin_layout.hpp"

namespace somasim::plugins {

class YarpSkinReplay : public Plugin {
 public:
  struct Config {
    ReplayLogParams log;
    std::vector<std::string> parts;
    std::vector<std::string> layout_files;
    int min_taxels = 1;
    double new_event_after_s = 0.1;  // [s]
    double keep_events_s = 5.0;      // [s]
    template <class V>
    void visit(V& v);
  };
  struct Ports {
    Out<ContactEvents> events;
    template <class V>
    void visit(V& v);
  };

  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  struct PartState {
    double last_touch_s = -1e300;  // sim time of the last line with a contact on the part
    std::int64_t contacts = 0, events = 0, unknown_taxels = 0;
  };
  void read_part_map(NodeContext& ctx);
  void read_layouts(NodeContext& ctx);
  void decode(NodeContext& ctx);
  void emit(double t, const std::string& part, const recordings::SkinContactRecord& c);

  Config config_;
  Ports ports_;
  recordings::DatadumperLog log_;
  std::vector<std::vector<recordings::SkinContactRecord>> contacts_;  // per log entry
  std::unique_ptr<recordings::ReplayCursor> cursor_;
  std::map<int, std::string> part_of_skin_part_;     // iCub SkinPart id -> body part
  std::map<std::string, skin::SkinLayout> layouts_;  // body part -> layout
  std::map<std::string, PartState> parts_;
  std::map<int, std::int64_t> unmapped_contacts_;  // iCub SkinPart id -> contacts left out
  std::int64_t small_contacts_ = 0;
  std::uint64_t next_event_id_ = 1;
};

}  // namespace somasim::plugins
