#include "taxel_thrower.hpp"
#include "somasim/random_directions.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include "somasim/units.hpp"

namespace somasim::plugins {
namespace {
Eigen::Vector3d list3(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}
}  // namespace

template <class V>
void TaxelThrower::Config::visit(V& v) {
  v.field("throws", throws)
      .range(1, 10000000)
      .doc("number of objects thrown; the run stops after the last");
  v.field("taxel_position", taxel_position).size(3).unit("m").doc("taxel centre, root frame");
  v.field("taxel_normal", taxel_normal).size(3).doc("outward skin normal, root frame (normalised)");
  v.field("body_part", body_part).doc("name of the skin part in the outputs");
  v.field("start_distance_min", start_distance_min)
      .unit("m")
      .range(0, 10)
      .doc("closest start of a throw from the taxel");
  v.field("start_distance_max", start_distance_max)
      .unit("m")
      .range(0, 10)
      .doc("farthest start of a throw");
  v.field("start_cone_deg", start_cone_deg)
      .unit("deg")
      .range(0, 89)
      .doc("start directions within this angle of the normal (uniform over the solid angle)");
  v.field("landing_sigma", landing_sigma)
      .unit("m")
      .range(0, 1)
      .doc(
          "landing point: Gaussian around the taxel, per skin-plane axis (released data 1.8 cm; "
          "paper text 5 cm)");
  v.field("speed_min", speed_min).unit("m/s").range(1e-4, 10).doc("slowest throw");
  v.field("speed_max", speed_max).unit("m/s").range(1e-4, 10).doc("fastest throw");
  v.field("hit_radius", hit_radius)
      .unit("m")
      .range(0, 1)
      .doc("a landing point this close to the taxel centre touches it");
  v.field("object_radius", object_radius)
      .unit("m")
      .range(0, 1)
      .doc("radius of the thrown objects (the centre lands at this height)");
  v.field("position_noise", position_noise)
      .unit("m")
      .range(0, 1)
      .doc("perceived position noise, std per axis");
  v.field("velocity_noise", velocity_noise)
      .unit("m/s")
      .range(0, 10)
      .doc("perceived velocity noise, std per axis");
  v.field("offset", offset)
      .unit("m")
      .range(-1, 1)
      .doc("systematic error of the perceived position along the normal (Fig 3: -0.10)");
}

template <class V>
void TaxelThrower::Ports::visit(V& v) {
  v.port("stimulus", stimulus, "the stimulus as perceived (root frame)");
  v.port("truth", truth, "the true object state (root frame)");
  v.port("taxels", taxels, "the one taxel, as a skin part");
  v.port("contacts", contacts, "a contact event at each landing (taxel touched on hits)");
  v.port("distance", distance, "true distance of the object centre from the taxel centre [m]");
}

void TaxelThrower::Config::validate(ConfigChecks& checks) const {
  checks.require(list3(taxel_normal).norm() >= 1e-9, taxel_normal, "must not be the zero vector");
  checks.require(start_distance_max >= start_distance_min, start_distance_max,
                 "must not be less than start_distance_min");
  checks.require(speed_max >= speed_min, speed_max, "must not be less than speed_min");
}

PluginSpec TaxelThrower::spec() {
  return make_plugin_spec<Config, Ports>(
      "taxel_thrower",
      "Single-taxel Monte Carlo (Roncone et al. 2016, Figs 2-3): objects thrown at one "
      "taxel on a skin plane; perceived stimulus with noise and a systematic offset.");
}

void TaxelThrower::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  taxel_position_ = list3(config_.taxel_position);
  taxel_normal_ = list3(config_.taxel_normal);
  taxel_normal_.normalize();
  // Any orthonormal pair spanning the skin plane.
  tangent_u_ = taxel_normal_.unitOrthogonal();
  tangent_v_ = taxel_normal_.cross(tangent_u_);
  start_distance_min_ = config_.start_distance_min;
  start_distance_max_ = config_.start_distance_max;
  start_cone_rad_ = deg_to_rad(config_.start_cone_deg);
  landing_sigma_ = config_.landing_sigma;
  speed_min_ = config_.speed_min;
  speed_max_ = config_.speed_max;
  hit_radius_ = config_.hit_radius;
  radius_ = config_.object_radius;
  position_noise_ = config_.position_noise;
  velocity_noise_ = config_.velocity_noise;
  offset_ = config_.offset;
  perceived_ = &ports_.stimulus.get();
  truth_ = &ports_.truth.get();
  taxels_ = &ports_.taxels.get();
  contacts_ = &ports_.contacts.get();
  distance_ = &ports_.distance.get();
  SkinPart part;
  part.name = config_.body_part;
  part.link = "root";
  part.taxel_ids = {0};
  part.positions = part.positions_link = {taxel_position_};
  part.normals = part.normals_link = {taxel_normal_};
  taxels_->parts = {part};
}

TaxelThrower::Throw TaxelThrower::draw_throw(std::mt19937_64& rng, double t0) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Throw th;
  const Eigen::Vector3d dir = sample_direction_in_cone(taxel_normal_, start_cone_rad_, rng);
  const double dist = start_distance_min_ + unit(rng) * (start_distance_max_ - start_distance_min_);
  // One draw per statement (argument evaluation order is unspecified: results would differ
  // between compilers); this is the order g++ drew them in, which the published runs used.
  const double land_y = landing_sigma_ * gauss(rng);
  const double land_x = landing_sigma_ * gauss(rng);
  const Eigen::Vector2d land(land_x, land_y);
  const double speed = speed_min_ + unit(rng) * (speed_max_ - speed_min_);
  th.start = taxel_position_ + dist * dir;
  // The object's centre lands one radius above the plane: its surface touches the skin.
  th.landing =
      taxel_position_ + land.x() * tangent_u_ + land.y() * tangent_v_ + radius_ * taxel_normal_;
  const Eigen::Vector3d path = th.landing - th.start;
  th.duration = path.norm() / speed;
  th.velocity = path / th.duration;
  th.t0 = t0;
  th.hit = land.norm() <= hit_radius_;
  return th;
}

void TaxelThrower::start(NodeContext& ctx) {
  current_ = draw_throw(ctx.rng(), ctx.time_s());
}

void TaxelThrower::perceive(std::mt19937_64& rng, const Eigen::Vector3d& position,
                            const Eigen::Vector3d& velocity) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  truth_->present = true;
  truth_->position = position;
  truth_->velocity = velocity;
  truth_->radius = radius_;
  *perceived_ = *truth_;
  perceived_->position += offset_ * taxel_normal_;
  if (position_noise_ > 0)
    for (int i = 0; i < 3; ++i) perceived_->position[i] += position_noise_ * gauss(rng);
  if (velocity_noise_ > 0)
    for (int i = 0; i < 3; ++i) perceived_->velocity[i] += velocity_noise_ * gauss(rng);
  *distance_ = (position - taxel_position_).norm();
  ++samples_;
}

void TaxelThrower::emit_contact(double t) {
  ContactEvent e;
  e.id = next_event_id_++;
  e.time_s = t;
  e.body_part = config_.body_part;
  if (current_.hit) e.touched_taxels = {0};
  // Keep a short history so that slower consumers still see every event.
  while (!contacts_->recent.empty() && contacts_->recent.front().time_s < t - 1.0)
    contacts_->recent.erase(contacts_->recent.begin());
  contacts_->recent.push_back(std::move(e));
}

void TaxelThrower::step(NodeContext& ctx) {
  if (done_) return;
  const double t = ctx.time_s();
  const double elapsed = t - current_.t0;
  if (elapsed + 1e-12 < current_.duration) {
    perceive(ctx.rng(), current_.start + elapsed * current_.velocity, current_.velocity);
    return;
  }
  // Landing: the last sample is at the contact point, then the contact event.
  perceive(ctx.rng(), current_.landing, current_.velocity);
  emit_contact(t);
  ++thrown_;
  if (current_.hit) {
    ++hits_;
    // Perceived D at contact: signed distance of the perceived surface point from the taxel.
    const Eigen::Vector3d p = perceived_->position - radius_ * taxel_normal_ - taxel_position_;
    const double pz = p.dot(taxel_normal_);
    contact_d_sum_ += (pz < 0 ? -1.0 : 1.0) * p.norm();
  }
  ctx.report_progress(thrown_, config_.throws, "throws");
  if (thrown_ >= config_.throws) {
    done_ = true;
    ctx.request_stop(std::to_string(thrown_) + " throws done");
    return;
  }
  // The next object starts at the next sample.
  current_ = draw_throw(ctx.rng(), t + ctx.period_s());
}

void TaxelThrower::finish(NodeContext& ctx) {
  ctx.report_metric("throws", thrown_);
  ctx.report_metric("hits", hits_);
  ctx.report_metric("hit_rate", thrown_ ? static_cast<double>(hits_) / thrown_ : 0.0);
  ctx.report_metric("stimulus_samples", samples_);
  ctx.report_metric("contact_distance_m",
                    hits_ ? nlohmann::json(contact_d_sum_ / hits_) : nlohmann::json());
}

}  // namespace somasim::plugins
