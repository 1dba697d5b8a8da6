#include "taxel_thrower.hpp"
#include "somasim/random_directions.hpp"

#include <cmath>

#include <Eigen/Geometry>
#include "somasim/units.hpp"

namespace somasim::plugins {
namespace {
Eigen::Vector3d list3(const NodeContext& ctx, const char* name) {
  const auto v = ctx.param<std::vector<double>>(name);
  return {v[0], v[1], v[2]};
}
}  // namespace

PluginSpec TaxelThrower::spec() {
  PluginSpec s("taxel_thrower",
               "Single-taxel Monte Carlo (Roncone et al. 2016, Figs 2-3): objects thrown at one "
               "taxel on a skin plane; perceived stimulus with noise and a systematic offset.");
  s.add_int("throws")
      .defaults(std::int64_t{500})
      .range(1, 10000000)
      .describe("number of objects thrown; the run stops after the last");
  s.add_list("taxel_position")
      .size(3)
      .unit_is("m")
      .defaults(std::vector<double>{0, 0, 0})
      .describe("taxel centre, root frame");
  s.add_list("taxel_normal")
      .size(3)
      .defaults(std::vector<double>{0, 0, 1})
      .describe("outward skin normal, root frame (normalised)");
  s.add_string("body_part")
      .defaults(std::string("taxel"))
      .describe("name of the skin part in the outputs");
  s.add_double("start_distance_min")
      .unit_is("m")
      .defaults(0.25)
      .range(0, 10)
      .describe("closest start of a throw from the taxel");
  s.add_double("start_distance_max")
      .unit_is("m")
      .defaults(0.30)
      .range(0, 10)
      .describe("farthest start of a throw");
  s.add_double("start_cone_deg")
      .unit_is("deg")
      .defaults(45.0)
      .range(0, 89)
      .describe("start directions within this angle of the normal (uniform over the solid angle)");
  s.add_double("landing_sigma")
      .unit_is("m")
      .defaults(0.018)
      .range(0, 1)
      .describe(
          "landing point: Gaussian around the taxel, per skin-plane axis (released data 1.8 cm; "
          "paper text 5 cm)");
  s.add_double("speed_min").unit_is("m/s").defaults(0.05).range(1e-4, 10).describe("slowest throw");
  s.add_double("speed_max").unit_is("m/s").defaults(0.07).range(1e-4, 10).describe("fastest throw");
  s.add_double("hit_radius")
      .unit_is("m")
      .defaults(0.02)
      .range(0, 1)
      .describe("a landing point this close to the taxel centre touches it");
  s.add_double("object_radius")
      .unit_is("m")
      .defaults(0.0)
      .range(0, 1)
      .describe("radius of the thrown objects (the centre lands at this height)");
  s.add_double("position_noise")
      .unit_is("m")
      .defaults(0.0)
      .range(0, 1)
      .describe("perceived position noise, std per axis");
  s.add_double("velocity_noise")
      .unit_is("m/s")
      .defaults(0.0)
      .range(0, 10)
      .describe("perceived velocity noise, std per axis");
  s.add_double("offset").unit_is("m").defaults(0.0).range(-1, 1).describe(
      "systematic error of the perceived position along the normal (Fig 3: -0.10)");
  s.output<pps::Stimulus>("stimulus", "the stimulus as perceived (root frame)");
  s.output<pps::Stimulus>("truth", "the true object state (root frame)");
  s.output<SkinTaxels>("taxels", "the one taxel, as a skin part");
  s.output<ContactEvents>("contacts", "a contact event at each landing (taxel touched on hits)");
  s.output<double>("distance", "true distance of the object centre from the taxel centre [m]");
  return s;
}

void TaxelThrower::configure(NodeContext& ctx) {
  throws_ = ctx.param<int>("throws");
  taxel_position_ = list3(ctx, "taxel_position");
  taxel_normal_ = list3(ctx, "taxel_normal");
  if (taxel_normal_.norm() < 1e-9) ctx.param_error("taxel_normal", "must not be the zero vector");
  taxel_normal_.normalize();
  // Any orthonormal pair spanning the skin plane.
  tangent_u_ = taxel_normal_.unitOrthogonal();
  tangent_v_ = taxel_normal_.cross(tangent_u_);
  body_part_ = ctx.param<std::string>("body_part");
  start_distance_min_ = ctx.param<double>("start_distance_min");
  start_distance_max_ = ctx.param<double>("start_distance_max");
  if (start_distance_max_ < start_distance_min_)
    ctx.param_error("start_distance_max", "must not be less than start_distance_min");
  start_cone_rad_ = deg_to_rad(ctx.param<double>("start_cone_deg"));
  landing_sigma_ = ctx.param<double>("landing_sigma");
  speed_min_ = ctx.param<double>("speed_min");
  speed_max_ = ctx.param<double>("speed_max");
  if (speed_max_ < speed_min_) ctx.param_error("speed_max", "must not be less than speed_min");
  hit_radius_ = ctx.param<double>("hit_radius");
  radius_ = ctx.param<double>("object_radius");
  position_noise_ = ctx.param<double>("position_noise");
  velocity_noise_ = ctx.param<double>("velocity_noise");
  offset_ = ctx.param<double>("offset");
  perceived_ = &ctx.output<pps::Stimulus>("stimulus");
  truth_ = &ctx.output<pps::Stimulus>("truth");
  taxels_ = &ctx.output<SkinTaxels>("taxels");
  contacts_ = &ctx.output<ContactEvents>("contacts");
  distance_ = &ctx.output<double>("distance");
  SkinPart part;
  part.name = body_part_;
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
  e.body_part = body_part_;
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
  if (thrown_ >= throws_) {
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
