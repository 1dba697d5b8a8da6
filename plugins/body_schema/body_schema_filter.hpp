#pragma once
// body_schema_filter: online estimation of the arm's joint offsets β from the eye images by
// mental simulation (Vicente et al. 2016; ../../core/body_schema). See README.md.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "particle_comparison.hpp"
#include "somasim/body_schema/eye_hand.hpp"
#include "somasim/body_schema/hypothesis_scorer.hpp"
#include "somasim/body_schema/observation.hpp"
#include "somasim/body_schema/oriented_edges.hpp"
#include "somasim/body_schema/particle_filter.hpp"
#include "somasim/body_schema/particle_ranks.hpp"
#include "somasim/body_schema/ports.hpp"
#include "somasim/config.hpp"
#include "somasim/plugin.hpp"
#include "somasim/plugin_ports.hpp"
#include "somasim/render/ports.hpp"
#include "somasim/robot/experiment_robot.hpp"
#include "somasim/robot/ports.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::plugins {

/// Where the particles are scored: every rank scores all, or MPI ranks share them.
enum class ParticleDistribution : std::uint8_t { kNone, kMpi };
/// "none", "mpi".
inline constexpr NamedValue<ParticleDistribution> kParticleDistributionNames[] = {
    {ParticleDistribution::kNone, "none"}, {ParticleDistribution::kMpi, "mpi"}};
constexpr std::span<const NamedValue<ParticleDistribution>> name_table(ParticleDistribution) {
  return kParticleDistributionNames;
}

/// What the filter does when every particle's likelihood is 0.
enum class OnNoMatch : std::uint8_t { kReinflate, kStop };
/// "reinflate", "stop".
inline constexpr NamedValue<OnNoMatch> kOnNoMatchNames[] = {{OnNoMatch::kReinflate, "reinflate"},
                                                            {OnNoMatch::kStop, "stop"}};
constexpr std::span<const NamedValue<OnNoMatch>> name_table(OnNoMatch) {
  return kOnNoMatchNames;
}

class BodySchemaFilter : public Plugin {
 public:
  /// The most particles a filter may have: the KDE of the estimate is O(M²) per frame
  /// (4·10⁸ kernel evaluations at this bound), so more would run for hours or exhaust memory.
  static constexpr int kMaxParticles = 20000;
  struct Config {
    robot::RobotParam robot;
    std::string chain = "right_arm";
    std::vector<std::string> joints{"r_shoulder_pitch", "r_shoulder_roll", "r_shoulder_yaw",
                                    "r_elbow",          "r_wrist_prosup",  "r_wrist_pitch",
                                    "r_wrist_yaw"};
    std::vector<std::string> links{"r_hand"};
    std::vector<std::string> occluder_links;
    std::string palm_frame = "r_palm";
    std::vector<std::string> cameras{"left_eye", "right_eye"};
    int particles = 200;
    int ensemble = 1;
    std::string schedule = "paper";
    double sigma_floor_deg = 0.0;  // [deg]
    double jump_fraction = 0.0;
    double jump_sigma_deg = 1.5;  // [deg]
    body_schema::KdeOptions kde;  // kde_sigma_deg, kde_alpha
    // likelihood, silhouette_form, silhouette_power, edge_lambda, edge_orientation_weight,
    // margin_px, contour_width
    body_schema::ScorerOptions scorer;
    std::vector<double> canny{65, 195};
    std::vector<double> hand_hsv_low{0, 40, 60};
    std::vector<double> hand_hsv_high{30, 255, 255};
    int proxy_resolution = 8;
    ParticleDistribution distribute = ParticleDistribution::kNone;
    int render_threads = 2;
    render::RenderBackend backend = render::RenderBackend::kOsmesa;
    double image_noise = 0.0;
    OnNoMatch on_no_match = OnNoMatch::kReinflate;
    double reinflate_factor = 2.0;
    std::vector<double> compare_particles;
    int evaluate_frame = 120;
    std::string true_offsets_deg;
    OutputFile csv{"body_schema_filter.csv", {}};
    template <class V>
    void visit(V& v);
    void validate(ConfigChecks& checks) const;  // cross-field checks
  };
  struct Ports {
    In<JointState> joint_state;
    In<RgbImage> left_eye_rgb;
    OptionalIn<RgbImage> right_eye_rgb;
    OptionalIn<ReachPhase> phase;
    OptionalIn<LinkPoses> true_link_poses;
    OptionalIn<BodySchemaEstimate> occluder_estimate;
    Out<BodySchemaEstimate> estimate;
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
  void configure_joints(NodeContext& ctx);
  void configure_scorer(NodeContext& ctx);
  void configure_ranks(NodeContext& ctx, const std::vector<int>& compared_sizes);
  /// Likelihoods of all `particles`; with ranks_, this rank scores its share and gathers the rest.
  std::vector<double> score(const Eigen::VectorXd& q, const Eigen::MatrixXd& particles,
                            const std::vector<render::Camera>& cameras,
                            const std::vector<cv::Mat>& observations);
  std::vector<cv::Mat> observe(NodeContext& ctx);
  void on_no_match(NodeContext& ctx, const body_schema::FilterUpdate& update);
  /// Of the ensemble's members, the one whose estimate explains this frame's images best.
  std::size_t best_member(const Eigen::VectorXd& q, const std::vector<render::Camera>& cameras,
                          const std::vector<cv::Mat>& observations);
  /// The ensemble member whose estimate is published (the main filter without an ensemble).
  const body_schema::OffsetParticleFilter& published() const;
  void publish(NodeContext& ctx, const body_schema::FilterUpdate& update);
  void write_csv() const;
  void evaluate(const Eigen::VectorXd& q);
  /// Scores the true offsets and the estimate on this frame's images (at evaluate_frame): is
  /// the estimate's error the likelihood's (the truth explains the images less well) or the
  /// filter's (the truth explains them better but was not found)?
  void score_truth(const Eigen::VectorXd& q, const std::vector<render::Camera>& cameras,
                   const std::vector<cv::Mat>& observations);

  std::shared_ptr<const robot::RobotModel> model_;
  std::vector<int> offset_dofs_;
  std::unique_ptr<body_schema::OffsetParticleFilter> filter_;
  // The ensemble's further members (ensemble − 1 filters of as many particles) and the one
  // published: 0 the main filter, k others_[k − 1].
  std::vector<std::unique_ptr<body_schema::OffsetParticleFilter>> others_;
  std::size_t published_ = 0;
  std::int64_t member_switches_ = 0;  // frames on which the published member changed
  std::unique_ptr<body_schema::HypothesisScorer> scorer_;
  std::unique_ptr<body_schema::EyeHand> eye_hand_;
  std::unique_ptr<ParticleComparison> comparison_;
  std::unique_ptr<body_schema::ParticleRanks>
      ranks_;                      // distribute: mpi under mpirun; null otherwise
  bool distribute_ = false;        // distribute: mpi (one rank without MPI)
  std::vector<double> gather_ms_;  // MPI_Allgatherv wall time of each step [ms]
  SizeRecord main_record_;         // the main filter's errors at evaluate_frame and step times
  body_schema::HsvRange hand_colour_;
  double canny_low_ = 65.0, canny_high_ = 195.0;
  bool stop_when_lost_ = false;
  Eigen::VectorXd true_offsets_;  // [rad] per dof; empty when not given

  const JointState* joint_state_ = nullptr;
  std::vector<const Image*> images_;
  const ReachPhase* phase_ = nullptr;
  const LinkPoses* true_poses_ = nullptr;
  const BodySchemaEstimate* occluder_estimate_ = nullptr;
  BodySchemaEstimate* estimate_ = nullptr;

  int movement_ = -1;
  std::uint64_t frames_ = 0;
  std::int64_t lost_frames_ = 0;
  std::vector<double> render_ms_;
  // At evaluate_frame of each movement: the likelihood of the true offsets and of the estimate.
  std::vector<double> truth_likelihood_, estimate_likelihood_;
  std::string csv_name_;
  std::filesystem::path csv_path_;
  std::vector<std::vector<double>> rows_;
  std::vector<std::string> columns_;
};

}  // namespace somasim::plugins
