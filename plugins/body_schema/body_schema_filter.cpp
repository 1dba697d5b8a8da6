#include "body_schema_filter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "sample_stats.hpp"
#include "somasim/atomic_file.hpp"
#include "somasim/body_schema/pose_error.hpp"
#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/joint_text.hpp"
#include "somasim/robot/kinematics.hpp"

namespace somasim::plugins {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

}  // namespace

template <class V>
void BodySchemaFilter::Config::visit(V& v) {
  v.block(robot);
  v.field("chain", chain).doc("the arm's chain in the robot model");
  v.field("joints", joints)
      .doc("joints whose offsets are estimated (all in `chain`), one particle row each");
  v.field("links", links)
      .doc("links drawn as hypotheses (their collision geometry: the internal model)");
  v.field("occluder_links", occluder_links)
      .doc(
          "links of another body part (the other hand) drawn in front of every hypothesis as "
          "occluders: the hypothesis' contour they hide is not charged, posed by the encoders "
          "and the offsets of the input occluder_estimate (unwired: the nominal model); "
          "[] = none; needs rasterizer: software");
  v.field("palm_frame", palm_frame).doc("frame whose pose is estimated");
  v.field("cameras", cameras)
      .doc(
          "1 or 2 cameras, fed by the inputs left_eye_rgb and right_eye_rgb; the first "
          "is the frame of the estimated palm pose");
  v.field("particles", particles)
      .range(1, kMaxParticles)
      .doc("M (the estimate's KDE costs M² kernel evaluations per frame)");
  v.field("schedule", schedule)
      .one_of(body_schema::noise_schedule_names())
      .doc("noise schedule preset (somasim/body_schema/noise_schedule.hpp)");
  v.field("sigma_floor_deg", sigma_floor_deg)
      .at_least(0.0)
      .unit("deg")
      .doc(
          "floor of σ_s instead of the schedule's (0: the preset's, e.g. 0.08 for paper); a "
          "higher floor keeps the particles moving (plugins/body_schema/README.md)");
  v.field("jump_fraction", jump_fraction)
      .range(0.0, 1.0)
      .doc(
          "share of particles that take a wider step N(0, max(σ_s, jump_sigma_deg)²) at each "
          "prediction (mixture proposal against early lock-in onto a wrong mode; not in the "
          "paper, 0 = off; see plugins/body_schema/README.md)");
  v.field("jump_sigma_deg", jump_sigma_deg)
      .at_least(0.0)
      .unit("deg")
      .doc("σ of a jump (with jump_fraction > 0)");
  v.block(kde);
  v.block(scorer);
  v.field("canny", canny).size(2).doc("Canny thresholds");
  v.field("hand_hsv_low", hand_hsv_low)
      .size(3)
      .doc("hand colour segmentation: lower HSV bound (OpenCV: H 0-179, S and V 0-255)");
  v.field("hand_hsv_high", hand_hsv_high).size(3).doc("upper HSV bound");
  v.field("proxy_resolution", proxy_resolution)
      .range(3, 256)
      .doc("segments around the hypotheses' curved primitives (low-poly internal model)");
  v.field("distribute", distribute)
      .doc(
          "mpi: under `mpirun -n K somasim run`, every rank renders and scores its share of the "
          "particles (of every compared filter too) and the likelihoods are gathered, outputs "
          "byte-identical to one process (README 'MPI'); without an MPI launch one process scores "
          "them all. none: every rank scores all particles");
  v.field("render_threads", render_threads)
      .range(1, 64)
      .doc("render workers; the estimate's KDE uses as many threads (same estimate for any count)");
  v.field("backend", backend).doc("OpenGL back end of the hypothesis renderer");
  v.field("image_noise", image_noise)
      .at_least(0.0)
      .doc("σ of Gaussian noise added to every RGB channel before the observation [grey levels]");
  v.field("on_no_match", on_no_match)
      .doc(
          "when every particle's likelihood is 0: keep the particles and multiply σ_s by "
          "reinflate_factor, or stop the run");
  v.field("reinflate_factor", reinflate_factor).at_least(1.0).doc("see on_no_match");
  v.field("ensemble", ensemble)
      .range(1, 8)
      .doc(
          "independent filters of `particles` particles each (own random streams) on the same "
          "images; the estimate published each frame is the one whose likelihood on that "
          "frame's images is highest (metric ensemble_switches). Where the images leave two "
          "modes, each filter settles in one and the frame decides between them; 1 = one filter");
  v.field("compare_particles", compare_particles)
      .max_size(16)
      .doc(
          "sizes M of further filters run on the same images for the particle study "
          "(metrics particles_<M>_*, figures/body_schema_particles.png); [] = none");
  v.field("evaluate_frame", evaluate_frame)
      .at_least(0)
      .doc(
          "phase frame at which each filter's estimation error is recorded for the "
          "particles_<M>_* metrics (needs phase and true_link_poses)");
  v.field("true_offsets_deg", true_offsets_deg)
      .map_as_text()
      .doc("the truth ('joint: deg, ...'), for the CSV's offset errors; empty = unknown");
  v.field("csv", csv).doc("per-frame CSV in the run folder ('' = none)");
}

void BodySchemaFilter::Config::validate(ConfigChecks& checks) const {
  checks.require(!joints.empty(), joints, "expected at least one joint");
  for (auto it = joints.begin(); it != joints.end(); ++it)
    checks.require(std::find(joints.begin(), it, *it) == it, joints,
                   "joint '" + *it + "' is listed twice");
  checks.require(cameras.size() != 2 || cameras[0] != cameras[1], cameras,
                 "the two cameras are the same ('" + (cameras.empty() ? "" : cameras[0]) + "')");
  checks.require(!cameras.empty() && cameras.size() <= 2, cameras,
                 fmt::format("expected 1 or 2 camera names, got {}", cameras.size()));
  checks.require(!scorer.inner_contours || scorer.kind == body_schema::LikelihoodKind::kEdges,
                 scorer.inner_contours, "needs likelihood: edges");
  checks.require(!scorer.inner_contours || scorer.rasterizer == render::Rasterizer::kSoftware,
                 scorer.inner_contours, "needs rasterizer: software");
  checks.require(!scorer.crease_contours || scorer.inner_contours, scorer.crease_contours,
                 "needs edge_inner_contours: true");
  checks.require(occluder_links.empty() || scorer.rasterizer == render::Rasterizer::kSoftware,
                 occluder_links, "needs rasterizer: software");
  for (const std::string& link : occluder_links)
    checks.require(std::find(links.begin(), links.end(), link) == links.end(), occluder_links,
                   "link '" + link + "' is also a hypothesis link (links)");
  for (double m : compare_particles)
    checks.require(
        m >= 1.0 && m == std::floor(m) && m <= kMaxParticles, compare_particles,
        fmt::format("expected whole numbers of particles in [1, {}], got {}", kMaxParticles, m));
}

template <class V>
void BodySchemaFilter::Ports::visit(V& v) {
  v.port("joint_state", joint_state, "encoder readings θ (world.joint_state)");
  v.port("left_eye_rgb", left_eye_rgb, "rgb8 image of the first camera");
  v.port("right_eye_rgb", right_eye_rgb, "rgb8 image of the second camera");
  v.port("phase", phase,
         "the reach_controller's phase: observe in the open and closed loop, restart "
         "with every movement; unwired = observe every step");
  v.port("true_link_poses", true_link_poses, "the world's link poses, for the CSV's pose errors");
  v.port("occluder_estimate", occluder_estimate,
         "the other arm's filter estimate (delayed): its offsets pose the occluder_links");
  v.port("estimate", estimate, "β̂ and the estimated palm pose (left-eye frame)");
}

PluginSpec BodySchemaFilter::spec() {
  return make_plugin_spec<Config, Ports>(
      "body_schema_filter",
      "Online body-schema adaptation (Vicente et al. 2016): a particle filter over the "
      "arm's joint offsets scores rendered hypotheses of the hand ('mental images') "
      "against the eye images (colour silhouettes or edges) and estimates the offsets "
      "and the palm pose in the left-eye frame.");
}

void BodySchemaFilter::configure_joints(NodeContext& ctx) {
  const std::string chain_name = config_.chain;
  const robot::ChainInfo* chain = model_->find_chain(chain_name);
  if (chain == nullptr)
    config_error(ctx, config_, config_.chain,
                 fmt::format("no chain '{}' in robot '{}'", chain_name, model_->name()));
  for (const std::string& j : config_.joints) {
    if (std::find(chain->joints.begin(), chain->joints.end(), j) == chain->joints.end())
      config_error(ctx, config_, config_.joints,
                   fmt::format("joint '{}' is not in the arm chain '{}' (joints: {})", j,
                               chain_name, fmt::join(chain->joints, ", ")));
    offset_dofs_.push_back(model_->dof_index(j));
  }
  try {
    model_->frame_ref(config_.palm_frame);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.palm_frame, e.what());
  }
  const std::string truth = config_.true_offsets_deg;
  if (!truth.empty()) {
    try {
      true_offsets_ = robot::parse_joint_offsets(*model_, truth);
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.true_offsets_deg, e.what());
    }
    // An offset the filter does not estimate could never be found: a mistake in the config.
    for (int d = 0; d < model_->num_dofs(); ++d)
      if (true_offsets_[d] != 0.0 &&
          std::find(offset_dofs_.begin(), offset_dofs_.end(), d) == offset_dofs_.end())
        config_error(
            ctx, config_, config_.true_offsets_deg,
            fmt::format("joint '{}' has a true offset but is not among the estimated "
                        "joints ({})",
                        model_->joint(model_->dof_joint(d)).name, fmt::join(config_.joints, ", ")));
  }
}

void BodySchemaFilter::configure_scorer(NodeContext& ctx) {
  body_schema::ArmHypothesisModel arm;
  try {
    arm = body_schema::arm_hypothesis_model(*model_, config_.links, config_.proxy_resolution,
                                            config_.scorer.inner_contours);
  } catch (const InputError& e) {
    config_error(ctx, config_, config_.links, e.what());
  }

  body_schema::ArmHypothesisModel occluder;
  if (!config_.occluder_links.empty()) {
    try {
      occluder = body_schema::arm_hypothesis_model(*model_, config_.occluder_links,
                                                   config_.proxy_resolution);
    } catch (const InputError& e) {
      config_error(ctx, config_, config_.occluder_links, e.what());
    }
  }
  scorer_ = std::make_unique<body_schema::HypothesisScorer>(
      model_, arm, offset_dofs_, config_.render_threads, config_.scorer, config_.backend, occluder);
}

void BodySchemaFilter::configure(NodeContext& ctx) {
  config_ = read_config<Config>(ctx);
  bind_ports(ctx, ports_);
  model_ = robot::experiment_robot(ctx, config_.robot);
  configure_joints(ctx);
  for (const std::string& c : config_.cameras)
    if (model_->find_camera(c) < 0)
      config_error(ctx, config_, config_.cameras,
                   fmt::format("camera '{}' is not in robot '{}'", c, model_->name()));
  if (config_.cameras.size() == 2 && !ports_.right_eye_rgb.wired())
    config_error(ctx, config_, config_.cameras, "two cameras need the input right_eye_rgb wired");

  const body_schema::KdeOptions& kde = config_.kde;
  body_schema::NoiseSchedule schedule = body_schema::noise_schedule_preset(config_.schedule);
  if (const double floor = config_.sigma_floor_deg; floor > 0.0) {
    if (floor > schedule.max_sigma_deg)
      config_error(ctx, config_, config_.sigma_floor_deg,
                   fmt::format("{} deg is above the schedule's ceiling of {} deg", floor,
                               schedule.max_sigma_deg));
    schedule.min_sigma_deg = floor;
  }
  schedule.jump_fraction = config_.jump_fraction;
  schedule.jump_sigma_deg = config_.jump_sigma_deg;
  filter_ = std::make_unique<body_schema::OffsetParticleFilter>(
      static_cast<int>(offset_dofs_.size()), config_.particles, schedule, ctx.rng()(), kde);
  filter_->set_estimate_threads(config_.render_threads);
  for (int k = 1; k < config_.ensemble; ++k) {
    others_.push_back(std::make_unique<body_schema::OffsetParticleFilter>(
        static_cast<int>(offset_dofs_.size()), config_.particles, schedule, ctx.rng()(), kde));
    others_.back()->set_estimate_threads(config_.render_threads);
  }

  const auto low = config_.hand_hsv_low;
  const auto high = config_.hand_hsv_high;
  hand_colour_.low = cv::Scalar(low[0], low[1], low[2]);
  hand_colour_.high = cv::Scalar(high[0], high[1], high[2]);
  const auto canny = config_.canny;
  canny_low_ = canny[0];
  canny_high_ = canny[1];
  stop_when_lost_ = config_.on_no_match == OnNoMatch::kStop;
  csv_name_ = config_.csv.name;
  if (!csv_name_.empty()) csv_path_ = config_.csv.path;

  configure_scorer(ctx);
  const robot::ChainInfo* chain = model_->find_chain(config_.chain);
  eye_hand_ = std::make_unique<body_schema::EyeHand>(model_, config_.cameras[0], config_.palm_frame,
                                                     model_->link(chain->base_link).name);
  std::vector<int> sizes;
  for (double m : config_.compare_particles) sizes.push_back(static_cast<int>(m));  // validated
  if (!sizes.empty())
    comparison_ =
        std::make_unique<ParticleComparison>(sizes, static_cast<int>(offset_dofs_.size()), schedule,
                                             kde, ctx.rng()(), config_.reinflate_factor);
  main_record_.particles = filter_->size();
  configure_ranks(ctx, sizes);

  joint_state_ = &ports_.joint_state.get();
  images_.push_back(&ports_.left_eye_rgb.get());
  if (config_.cameras.size() == 2) images_.push_back(ports_.right_eye_rgb.get());
  phase_ = ports_.phase.get();
  true_poses_ = ports_.true_link_poses.get();
  occluder_estimate_ = ports_.occluder_estimate.get();
  if (occluder_estimate_ != nullptr && config_.occluder_links.empty())
    config_error(ctx, config_, config_.occluder_links,
                 "the input occluder_estimate is wired but no occluder_links are drawn");
  estimate_ = &ports_.estimate.get();
  estimate_->offsets = Eigen::VectorXd::Zero(model_->num_dofs());

  columns_ = {"time [s]", "movement", "frame"};
  for (const std::string& j : config_.joints) columns_.push_back(fmt::format("beta_{} [deg]", j));
  for (const char* c : {"sigma_s [deg]", "best likelihood", "mean likelihood", "ess", "resampled"})
    columns_.emplace_back(c);
  if (true_offsets_.size() > 0) columns_.emplace_back("offset error max [deg]");
  if (true_poses_ != nullptr)
    for (const char* c : {"estimation error [mm]", "estimation error [deg]", "nominal error [mm]",
                          "nominal error [deg]"})
      columns_.emplace_back(c);
  ctx.log().info("body_schema_filter: M = {}, {} joints, links {}, {} likelihood, schedule {}",
                 filter_->size(), config_.joints.size(), fmt::join(config_.links, " "),
                 enum_name(config_.scorer.kind), config_.schedule);
}

void BodySchemaFilter::configure_ranks(NodeContext& ctx, const std::vector<int>& compared_sizes) {
  distribute_ = config_.distribute == ParticleDistribution::kMpi;
  if (!body_schema::ParticleRanks::mpi_running()) return;
  if (!distribute_) {
    ctx.log().info(
        "body_schema_filter: under MPI with distribute: none: every rank scores all {} "
        "particles",
        filter_->size());
    return;
  }
  ranks_ =
      std::make_unique<body_schema::ParticleRanks>();  // collective: every rank configures alike
  auto check = [&](const auto& key, int particles) {
    if (ranks_->size() > particles)
      config_error(ctx, config_, key,
                   fmt::format("distribute: mpi over {} ranks needs at least one particle "
                               "per rank, but this filter has {} particles (launch at "
                               "most {} ranks, or use more particles)",
                               ranks_->size(), particles, particles));
  };
  check(config_.particles, filter_->size());
  for (int m : compared_sizes) check(config_.compare_particles, m);
  const body_schema::ParticleShare mine = ranks_->share(filter_->size());
  ctx.log().info(
      "body_schema_filter: distribute: mpi over {} ranks; rank {} scores particles {} "
      "to {}",
      ranks_->size(), ranks_->rank(), mine.begin, mine.begin + mine.count - 1);
}

std::vector<double> BodySchemaFilter::score(const Eigen::VectorXd& q,
                                            const Eigen::MatrixXd& particles,
                                            const std::vector<render::Camera>& cameras,
                                            const std::vector<cv::Mat>& observations) {
  if (!ranks_) return scorer_->score(q, particles, cameras, observations);
  const auto m = static_cast<int>(particles.cols());
  const body_schema::ParticleShare mine = ranks_->share(m);
  const std::vector<double> local =
      scorer_->score(q, particles.middleCols(mine.begin, mine.count), cameras, observations);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<double> all = ranks_->gather(local, m);
  gather_ms_.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  return all;
}

std::vector<cv::Mat> BodySchemaFilter::observe(NodeContext& ctx) {
  std::vector<cv::Mat> out;
  for (std::size_t c = 0; c < images_.size(); ++c) {
    const Image& image = *images_[c];
    const robot::Camera& cam =
        model_->cameras()[static_cast<std::size_t>(model_->find_camera(config_.cameras[c]))];
    if (image.frame == 0 || image.encoding != ImageEncoding::kRgb8)
      throw RunError(fmt::format(
          "body_schema_filter: no rgb8 image of camera '{}' at t = {:.3f} s (wire a camera "
          "node's {}_rgb output running at least as often as this node, earlier in the graph)",
          config_.cameras[c], ctx.time_s(), c == 0 ? "left_eye" : "right_eye"));
    if (image.data.cols != cam.width || image.data.rows != cam.height)
      throw RunError(
          fmt::format("body_schema_filter: camera '{}' is {}x{} in the robot model "
                      "but its image is {}x{}",
                      config_.cameras[c], cam.width, cam.height, image.data.cols, image.data.rows));
    cv::Mat rgb = image.data;
    if (config_.image_noise > 0.0) {
      cv::Mat noise(rgb.size(), CV_32FC3);
      std::normal_distribution<float> gauss(0.0f, static_cast<float>(config_.image_noise));
      for (auto it = noise.begin<cv::Vec3f>(); it != noise.end<cv::Vec3f>(); ++it)
        *it = cv::Vec3f(gauss(ctx.rng()), gauss(ctx.rng()), gauss(ctx.rng()));
      cv::Mat noisy;
      rgb.convertTo(noisy, CV_32FC3);
      noisy += noise;
      noisy.convertTo(rgb, CV_8UC3);  // rounds and saturates
    }
    if (scorer_->options().kind == body_schema::LikelihoodKind::kSilhouette)
      out.push_back(body_schema::segment_colour(rgb, hand_colour_));
    else if (scorer_->options().edge_orientation_weight > 0)
      out.push_back(body_schema::oriented_edge_map(rgb, canny_low_, canny_high_));
    else
      out.push_back(body_schema::edge_distance_map(rgb, canny_low_, canny_high_));
  }
  return out;
}

void BodySchemaFilter::step(NodeContext& ctx) {
  if (phase_ != nullptr) {
    if (phase_->stage != ReachStage::kOpenLoop && phase_->stage != ReachStage::kClosedLoop) return;
    if (phase_->movement != movement_) {
      movement_ = phase_->movement;
      filter_->reset();
      for (auto& other : others_) other->reset();
      if (comparison_) comparison_->reset();
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<cv::Mat> observations = observe(ctx);
  robot::RobotData data(*model_);
  robot::forward_kinematics(*model_, data, joint_state_->position);
  std::vector<render::Camera> cameras;
  for (const std::string& c : config_.cameras)
    cameras.push_back(render::camera_for(*model_, c, data.link_poses));

  if (occluder_estimate_ != nullptr && occluder_estimate_->offsets.size() == model_->num_dofs())
    scorer_->set_occluder_offsets(occluder_estimate_->offsets);
  filter_->predict();
  std::vector<double> likelihoods;
  try {
    likelihoods = score(joint_state_->position, filter_->particles(), cameras, observations);
  } catch (const RunError& e) {
    throw RunError(
        fmt::format("body_schema_filter: movement {}: the hypothesis links ({}) are "
                    "not visible: {}",
                    movement_, fmt::join(config_.links, " "), e.what()));
  }
  render_ms_.push_back(scorer_->timing().render_ms);  // the main filter's batch
  body_schema::FilterUpdate update = filter_->update(likelihoods);
  if (!(update.best_likelihood > 0.0)) on_no_match(ctx, update);
  std::vector<body_schema::FilterUpdate> other_updates;
  for (auto& other : others_) {
    other->predict();
    other_updates.push_back(
        other->update(score(joint_state_->position, other->particles(), cameras, observations)));
    if (!(other_updates.back().best_likelihood > 0.0))
      other->inflate_sigma(config_.reinflate_factor);
  }
  if (!others_.empty()) {
    const std::size_t best = best_member(joint_state_->position, cameras, observations);
    if (best != published_ && frames_ > 0) ++member_switches_;
    published_ = best;
    if (best > 0) update = other_updates[best - 1];
  }
  const double step_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  main_record_.step_ms.push_back(step_ms);
  if (comparison_)
    comparison_->step([&](const Eigen::MatrixXd& particles) {
      return score(joint_state_->position, particles, cameras, observations);
    });
  publish(ctx, update);
  if (phase_ != nullptr && phase_->frame == config_.evaluate_frame) {
    evaluate(joint_state_->position);
    if (true_offsets_.size() > 0) score_truth(joint_state_->position, cameras, observations);
  }
}

std::size_t BodySchemaFilter::best_member(const Eigen::VectorXd& q,
                                          const std::vector<render::Camera>& cameras,
                                          const std::vector<cv::Mat>& observations) {
  Eigen::MatrixXd estimates(filter_->dims(), static_cast<Eigen::Index>(others_.size() + 1));
  estimates.col(0) = filter_->estimate();
  for (std::size_t k = 0; k < others_.size(); ++k)
    estimates.col(static_cast<Eigen::Index>(k + 1)) = others_[k]->estimate();
  // Every rank scores these few alike (no share to gather).
  const std::vector<double> l = scorer_->score(q, estimates, cameras, observations);
  return static_cast<std::size_t>(std::max_element(l.begin(), l.end()) - l.begin());
}

const body_schema::OffsetParticleFilter& BodySchemaFilter::published() const {
  return published_ == 0 ? *filter_ : *others_[published_ - 1];
}

void BodySchemaFilter::score_truth(const Eigen::VectorXd& q,
                                   const std::vector<render::Camera>& cameras,
                                   const std::vector<cv::Mat>& observations) {
  Eigen::MatrixXd truth_and_estimate(filter_->dims(), 2);
  for (std::size_t j = 0; j < offset_dofs_.size(); ++j)
    truth_and_estimate(static_cast<Eigen::Index>(j), 0) =
        true_offsets_[offset_dofs_[j]] * kRadToDeg;
  truth_and_estimate.col(1) = published().estimate();
  const std::vector<double> l = score(q, truth_and_estimate, cameras, observations);
  truth_likelihood_.push_back(l[0]);
  estimate_likelihood_.push_back(l[1]);
}

void BodySchemaFilter::on_no_match(NodeContext& ctx, const body_schema::FilterUpdate&) {
  ++lost_frames_;
  const std::string what = fmt::format(
      "body_schema_filter: no particle explains the images at t = {:.3f} s (movement {}): every "
      "likelihood is 0 (is the hand in view and segmented? hand_hsv_low/high)",
      ctx.time_s(), movement_);
  if (stop_when_lost_) {
    ctx.log().error("{}; stopping the run (on_no_match: stop)", what);
    ctx.request_stop(what);
    return;
  }
  filter_->inflate_sigma(config_.reinflate_factor);
  if (lost_frames_ <= 5)
    ctx.log().warn("{}; particles kept, σ_s × {} = {:.3g} deg", what, config_.reinflate_factor,
                   filter_->sigma_deg());
}

void BodySchemaFilter::publish(NodeContext& ctx, const body_schema::FilterUpdate& u) {
  ++frames_;
  const Eigen::VectorXd& beta_deg = published().estimate();
  BodySchemaEstimate& e = *estimate_;
  e.frame = frames_;
  e.movement = movement_;
  e.offsets.setZero(model_->num_dofs());
  for (std::size_t j = 0; j < offset_dofs_.size(); ++j)
    e.offsets[offset_dofs_[j]] = beta_deg[static_cast<Eigen::Index>(j)] / kRadToDeg;
  const Eigen::VectorXd& q = joint_state_->position;
  e.palm_eye = eye_hand_->palm_eye(q, e.offsets);
  e.sigma_deg = u.sigma_deg;
  e.best_likelihood = u.best_likelihood;
  e.mean_likelihood = u.mean_likelihood;
  e.effective_sample_size = u.effective_sample_size;

  std::vector<double> row = {
      ctx.time_s(), static_cast<double>(movement_),
      static_cast<double>(phase_ ? phase_->frame : static_cast<int>(frames_))};
  for (Eigen::Index j = 0; j < beta_deg.size(); ++j) row.push_back(beta_deg[j]);
  row.insert(row.end(), {u.sigma_deg, u.best_likelihood, u.mean_likelihood, u.effective_sample_size,
                         u.resampled ? 1.0 : 0.0});
  if (true_offsets_.size() > 0) {
    double worst = 0.0;
    for (std::size_t j = 0; j < offset_dofs_.size(); ++j)
      worst = std::max(worst, std::abs(beta_deg[static_cast<Eigen::Index>(j)] -
                                       true_offsets_[offset_dofs_[j]] * kRadToDeg));
    row.push_back(worst);
  }
  if (true_poses_ != nullptr && !true_poses_->poses.empty()) {
    const Eigen::Isometry3d real = eye_hand_->palm_eye(true_poses_->poses);
    const Eigen::Isometry3d nominal = eye_hand_->palm_eye(q, Eigen::VectorXd::Zero(q.size()));
    row.insert(row.end(), {body_schema::position_error_mm(real, e.palm_eye),
                           body_schema::orientation_error_deg(real.linear(), e.palm_eye.linear()),
                           body_schema::position_error_mm(real, nominal),
                           body_schema::orientation_error_deg(real.linear(), nominal.linear())});
  }
  if (row.size() == columns_.size()) rows_.push_back(std::move(row));
}

void BodySchemaFilter::evaluate(const Eigen::VectorXd& q) {
  if (true_poses_ == nullptr || true_poses_->poses.empty()) return;
  const Eigen::Isometry3d real = eye_hand_->palm_eye(true_poses_->poses);
  auto error_of = [&](const Eigen::VectorXd& beta_deg) {
    Eigen::VectorXd offsets = Eigen::VectorXd::Zero(model_->num_dofs());
    for (std::size_t j = 0; j < offset_dofs_.size(); ++j)
      offsets[offset_dofs_[j]] = beta_deg[static_cast<Eigen::Index>(j)] / kRadToDeg;
    const Eigen::Isometry3d estimated = eye_hand_->palm_eye(q, offsets);
    return std::pair{body_schema::position_error_mm(real, estimated),
                     body_schema::orientation_error_deg(real.linear(), estimated.linear())};
  };
  const auto [mm, deg] = error_of(published().estimate());
  main_record_.error_mm.push_back(mm);
  main_record_.error_deg.push_back(deg);
  if (!comparison_) return;
  const std::vector<Eigen::VectorXd> estimates = comparison_->estimates();
  for (std::size_t k = 0; k < estimates.size(); ++k) {
    const auto [k_mm, k_deg] = error_of(estimates[k]);
    comparison_->record_error(k, k_mm, k_deg);
  }
}

void BodySchemaFilter::write_csv() const {
  if (csv_name_.empty()) return;
  std::string text = fmt::format("{}\n", fmt::join(columns_, ","));
  for (const auto& row : rows_) text += fmt::format("{}\n", fmt::join(row, ","));
  try {
    write_file_atomically(csv_path_, text);
  } catch (const std::runtime_error& e) {
    throw RunError(fmt::format("body_schema_filter: {}", e.what()));
  }
}

void BodySchemaFilter::finish(NodeContext& ctx) {
  ctx.report_metric("filter_frames", static_cast<std::int64_t>(frames_));
  ctx.report_metric("filter_particles", filter_ ? filter_->size() : 0);
  ctx.report_metric("filter_step_ms",
                    main_record_.step_ms.empty() ? 0.0 : median(main_record_.step_ms));
  ctx.report_metric("filter_render_ms", render_ms_.empty() ? 0.0 : median(render_ms_));
  ctx.report_metric("filter_frames_without_match", lost_frames_);
  if (!others_.empty()) ctx.report_metric("ensemble_switches", member_switches_);
  if (!truth_likelihood_.empty()) {
    std::int64_t outscored = 0;
    for (std::size_t k = 0; k < truth_likelihood_.size(); ++k)
      if (estimate_likelihood_[k] > truth_likelihood_[k]) ++outscored;
    ctx.report_metric("truth_likelihood", mean_sd(truth_likelihood_).mean);
    ctx.report_metric("estimate_likelihood", mean_sd(estimate_likelihood_).mean);
    ctx.report_metric("truth_outscored_movements", outscored);
  }
  if (distribute_)  // 0 with one rank
    ctx.report_metric("filter_gather_ms", gather_ms_.empty() ? 0.0 : median(gather_ms_));
  std::vector<SizeRecord> records = {main_record_};
  if (comparison_)
    records.insert(records.end(), comparison_->records().begin(), comparison_->records().end());
  const nlohmann::json sizes = particle_metrics(records);
  for (const auto& [key, value] : sizes.items()) ctx.report_metric(key, value);
  if (comparison_ && !main_record_.error_mm.empty())
    write_particle_figure(records, ctx.figure_path("body_schema_particles.png"));
  write_csv();
}

}  // namespace somasim::plugins
