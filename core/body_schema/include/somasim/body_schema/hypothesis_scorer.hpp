#pragma once
/// @file
/// Scores body-schema particles against camera observations: every particle's offsets are
/// added to the encoder readings, the arm links of the internal model are posed by forward
/// kinematics and drawn as a hypothesis batch (somasim/render/hypothesis_batch.hpp) in every
/// camera, and each hypothesis gets the product over the cameras of its likelihood
/// (likelihood.hpp).
///
/// The internal model: each hypothesis link is drawn with its collision geometry (the model's
/// own simple shapes, not the visual meshes the cameras see), tessellated with `segments`
/// around curved primitives and merged into one mesh per link in the link frame.
///
/// Frames and units: joint values [rad] in model dof order; particles [deg] (one row per offset
/// joint); cameras posed in the root frame; observations full-size images of each camera.
#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "somasim/body_schema/likelihood.hpp"
#include "somasim/name_table.hpp"
#include "somasim/render/hypothesis_batch.hpp"
#include "somasim/robot/kinematics.hpp"
#include "somasim/robot/robot_model.hpp"

namespace somasim::body_schema {

/// The links of the internal model drawn as hypotheses and their meshes (link frame).
struct ArmHypothesisModel {
  std::vector<int> links;  ///< model link indices
  /// One per link (its collision geometry, merged) or, per primitive, one per collision
  /// primitive of each link in order.
  std::vector<render::TriangleMesh> meshes;
  std::vector<std::size_t> mesh_link;  ///< per mesh: the index in `links` of its link
};
/// `per_primitive`: a mesh per collision primitive (for inner contours, where one primitive
/// occludes another) instead of one per link. Throws InputError "unknown link 'X' (links:
/// ...)" and "link 'X' has no collision geometry to draw", and for more than
/// render::kMaxMeshesPerHypothesis meshes.
ArmHypothesisModel arm_hypothesis_model(const robot::RobotModel& model,
                                        const std::vector<std::string>& link_names, int segments,
                                        bool per_primitive = false);

enum class LikelihoodKind : std::uint8_t { kSilhouette, kEdges };
inline constexpr NamedValue<LikelihoodKind> kLikelihoodKindNames[] = {
    {LikelihoodKind::kSilhouette, "silhouette"}, {LikelihoodKind::kEdges, "edges"}};
/// "silhouette", "edges".
constexpr std::span<const NamedValue<LikelihoodKind>> name_table(LikelihoodKind) {
  return kLikelihoodKindNames;
}
/// "silhouette" or "edges"; InputError otherwise.
LikelihoodKind likelihood_kind_from_name(const std::string& name);

struct ScorerOptions {
  LikelihoodKind kind = LikelihoodKind::kSilhouette;
  SilhouetteForm form = SilhouetteForm::kJaccard;
  double power = 1.0;         ///< exponent k of the power form
  double edge_lambda = 0.01;  ///< λ of L = exp(−λ d̄) [1/px]
  int margin_px = 8;          ///< ROI margin (render/hypothesis_batch.hpp)
  int contour_width = 1;      ///< edges: width of the hypothesis contours [px]
  /// edges: cost of a perpendicular nearest edge [px] (oriented chamfer, oriented_edges.hpp,
  /// on CV_8UC2 observations from oriented_edge_map); 0: the plain chamfer distance.
  double edge_orientation_weight = 0.0;
  /// edges: also score the hypotheses' inner contours, where one collision primitive occludes
  /// another (render::HypothesisBatchOptions::inner_contours; the software rasterizer only).
  bool inner_contours = false;
  /// edges, with inner_contours: also the creases inside each primitive (a box's edges, a
  /// cylinder's rims; render::HypothesisBatchOptions::crease_contours).
  bool crease_contours = false;
  /// How the hypotheses' tiles are drawn: GL (exact) or the CPU rasterizer (no GL, equal but for
  /// rare edge pixels, several times faster; render/hypothesis_batch.hpp).
  render::Rasterizer rasterizer = render::Rasterizer::kGl;

  /// The options as configuration fields (somasim/config.hpp), for plugins that embed them:
  /// likelihood, silhouette_form, silhouette_power, edge_lambda, edge_orientation_weight,
  /// edge_inner_contours, edge_crease_contours, margin_px, contour_width, rasterizer.
  template <class V>
  void visit(V& v) {
    v.field("likelihood", kind)
        .doc(
            "silhouette: Jaccard index of colour-segmented and rendered hand masks; edges: "
            "mean distance-transform value under the rendered contours");
    v.field("silhouette_form", form)
        .doc("L = J (paper) or L = J^silhouette_power, per camera, multiplied over cameras");
    v.field("silhouette_power", power).at_least(0.0).doc("k of L = J^k");
    v.field("edge_lambda", edge_lambda)
        .unit("1/px")
        .at_least(0.0)
        .doc("λ of L = exp(−λ d̄): 0.01 in the paper's text, 25/255 = 0.098 in its code");
    v.field("edge_orientation_weight", edge_orientation_weight)
        .unit("px")
        .range(0.0, 255.0)
        .doc(
            "edges: oriented chamfer - each contour pixel also costs this much times the angle "
            "between its normal and the nearest observed edge's normal over 90 deg (a "
            "perpendicular edge counts as this many pixels farther); 0: the paper's plain "
            "chamfer distance");
    v.field("edge_inner_contours", inner_contours)
        .doc(
            "edges: the hypotheses drawn per collision primitive with a depth test, their "
            "contours including where one primitive occludes another (a thumb over the palm); "
            "needs rasterizer: software");
    v.field("edge_crease_contours", crease_contours)
        .doc(
            "edges, with edge_inner_contours: the contours also include each primitive's creases "
            "(the palm box's edges, the fingers' rims: faces meeting at 60 deg or more)");
    v.field("margin_px", margin_px).range(0, 1000).doc("ROI margin [px]");
    v.field("contour_width", contour_width).range(1, 2).doc("edges: [px]");
    v.field("rasterizer", rasterizer)
        .doc(
            "how the hypotheses are drawn: gl (OpenGL, the back end's) or software (on the CPU, "
            "no GL: the same tiles but for rare pixels whose centre lies on an edge, several "
            "times faster)");
  }
};

/// Timing of the last score() call [ms].
struct ScoreTiming {
  double kinematics_ms = 0.0;  ///< forward kinematics of every particle
  double render_ms = 0.0;      ///< the hypothesis batch (draw + read-back + tiles)
  double compare_ms = 0.0;     ///< likelihoods from the tiles
};

class HypothesisScorer {
 public:
  /// `offset_dofs`: model dof index of each particle row. `workers` render threads.
  /// `occluder`: links of another body part (the other hand) drawn in every hypothesis' tiles
  /// as occluders (render::Occluder), posed by the encoder values and set_occluder_offsets();
  /// empty: none. Throws InputError for inner contours without the edge likelihood or the
  /// software rasterizer, and for occluders without the software rasterizer.
  HypothesisScorer(std::shared_ptr<const robot::RobotModel> model, const ArmHypothesisModel& arm,
                   std::vector<int> offset_dofs, int workers, const ScorerOptions& options,
                   render::RenderBackend backend = render::RenderBackend::kOsmesa,
                   const ArmHypothesisModel& occluder = {});

  /// The offsets [rad] per model dof (the other arm's estimate) under which the occluder links
  /// are posed from now on; zero (the nominal model) until set. Throws InputError for a vector
  /// of the wrong size or with a non-finite entry.
  void set_occluder_offsets(const Eigen::VectorXd& offsets_rad);

  /// The pose (root <- link) of every hypothesis link for encoder values q plus `offsets_deg`.
  std::vector<Eigen::Isometry3d> link_poses(const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& offsets_deg);

  /// Likelihood of every particle (columns of `particles_deg`), the occluders posed by q and
  /// the occluder offsets. `observations[c]` is camera c's
  /// observed silhouette (CV_8U 0 / 255) or edge distance map (CV_8U [px]; CV_8UC2
  /// oriented_edge_map with an edge_orientation_weight), full image.
  /// Throws RunError (from the renderer) naming a camera none of whose hypotheses projects
  /// into its image.
  std::vector<double> score(const Eigen::VectorXd& q, const Eigen::MatrixXd& particles_deg,
                            const std::vector<render::Camera>& cameras,
                            const std::vector<cv::Mat>& observations);

  /// The rendered hypothesis batch of the last score() call (for figures and tests).
  const render::HypothesisBatchResult& last_batch() const { return last_; }
  const ScoreTiming& timing() const { return timing_; }
  const ScorerOptions& options() const { return options_; }

 private:
  void pose_occluders(const Eigen::VectorXd& q);

  std::shared_ptr<const robot::RobotModel> model_;
  std::vector<int> links_;
  std::vector<std::size_t> mesh_link_;
  std::vector<int> offset_dofs_;
  std::vector<int> occluder_links_;
  std::vector<std::size_t> occluder_mesh_link_;  // per occluder mesh: its index in occluder_links_
  Eigen::VectorXd occluder_offsets_rad_;         // per model dof
  ScorerOptions options_;
  render::HypothesisRenderer renderer_;
  robot::RobotData data_;
  Eigen::VectorXd offsets_rad_;
  render::HypothesisBatch batch_;
  render::HypothesisBatchResult last_;
  ScoreTiming timing_;
};

}  // namespace somasim::body_schema
