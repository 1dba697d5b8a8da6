#pragma once
// taxel_thrower: the single-taxel Monte Carlo of Roncone et al. 2016 (Fig 2, Fig 3).
//
// One taxel sits at `taxel_position` with outward normal `taxel_normal` on an infinite skin
// plane (root frame). Objects are "thrown" one after the other: each starts at a distance in
// [start_distance_min, start_distance_max] within `start_cone_deg` of the normal, and flies in a
// straight line at a constant speed drawn from [speed_min, speed_max] to a landing point on the
// skin plane drawn from a Gaussian of `landing_sigma` per axis around the taxel. Landing
// within `hit_radius` of the taxel centre is a hit (the taxel is touched); elsewhere the part
// is touched but not the taxel (a negative example). The stimulus the robot perceives is the
// truth plus Gaussian position and velocity noise and a systematic offset along the normal.
#include <random>

#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/port_types.hpp"
#include "somasim/pps/ports.hpp"
#include "somasim/skin/ports.hpp"

namespace somasim::plugins {

class TaxelThrower : public Plugin {
 public:
  struct Config {
    int throws = 500;
    std::vector<double> taxel_position{0, 0, 0};  // [m]
    std::vector<double> taxel_normal{0, 0, 1};
    std::string body_part = "taxel";
    double start_distance_min = 0.25;  // [m]
    double start_distance_max = 0.30;  // [m]
    double start_cone_deg = 45.0;      // [deg]
    double landing_sigma = 0.018;      // [m]
    double speed_min = 0.05;           // [m/s]
    double speed_max = 0.07;           // [m/s]
    double hit_radius = 0.02;          // [m]
    double object_radius = 0.0;        // [m]
    double position_noise = 0.0;       // [m]
    double velocity_noise = 0.0;       // [m/s]
    double offset = 0.0;               // [m]
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    Out<pps::Stimulus> stimulus;
    Out<pps::Stimulus> truth;
    Out<SkinTaxels> taxels;
    Out<ContactEvents> contacts;
    Out<double> distance;
    template <class V>
    void visit(V& v);
  };
  static PluginSpec spec();
  void configure(NodeContext& ctx) override;
  void start(NodeContext& ctx) override;
  void step(NodeContext& ctx) override;
  void finish(NodeContext& ctx) override;

 private:
  Config config_;
  Ports ports_;
  struct Throw {
    Eigen::Vector3d start, landing, velocity;  // root frame [m], [m/s]
    double t0 = 0.0, duration = 0.0;           // [s]
    bool hit = false;
  };
  Throw draw_throw(std::mt19937_64& rng, double t0);
  void perceive(std::mt19937_64& rng, const Eigen::Vector3d& position,
                const Eigen::Vector3d& velocity);
  void emit_contact(double t);

  // parameters
  Eigen::Vector3d taxel_position_, taxel_normal_, tangent_u_, tangent_v_;
  double start_distance_min_ = 0, start_distance_max_ = 0, start_cone_rad_ = 0;
  double landing_sigma_ = 0, speed_min_ = 0, speed_max_ = 0, hit_radius_ = 0;
  double position_noise_ = 0, velocity_noise_ = 0, offset_ = 0, radius_ = 0;
  // ports
  pps::Stimulus* perceived_ = nullptr;
  pps::Stimulus* truth_ = nullptr;
  SkinTaxels* taxels_ = nullptr;
  ContactEvents* contacts_ = nullptr;
  double* distance_ = nullptr;
  // state
  Throw current_;
  int thrown_ = 0, hits_ = 0;
  std::uint64_t next_event_id_ = 1;
  std::size_t samples_ = 0;
  double contact_d_sum_ = 0.0;  // perceived D at contact, summed over hits
  bool done_ = false;
};

}  // namespace somasim::plugins
