#include "somasim/body_schema/hypothesis_scorer.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <numbers>

#include "somasim/body_schema/oriented_edges.hpp"
#include "somasim/error.hpp"
#include "somasim/render/robot_scene.hpp"

namespace somasim::body_schema {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Appends `part` posed by `origin` (link <- geometry) to `mesh`.
void append(render::TriangleMesh& mesh, const render::TriangleMesh& part,
            const Eigen::Isometry3d& origin) {
  const Eigen::Isometry3f o = origin.cast<float>();
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (std::size_t i = 0; i < part.positions.size(); ++i) {
    mesh.positions.push_back(o * part.positions[i]);
    mesh.normals.push_back(o.linear() * part.normals[i]);
  }
  for (std::uint32_t index : part.indices) mesh.indices.push_back(base + index);
}

// The renderer's meshes: the arm's, then the occluder's.
std::vector<render::TriangleMesh> all_meshes(const ArmHypothesisModel& arm,
                                             const ArmHypothesisModel& occluder) {
  std::vector<render::TriangleMesh> meshes = arm.meshes;
  meshes.insert(meshes.end(), occluder.meshes.begin(), occluder.meshes.end());
  return meshes;
}

}  // namespace

ArmHypothesisModel arm_hypothesis_model(const robot::RobotModel& model,
                                        const std::vector<std::string>& link_names, int segments,
                                        bool per_primitive) {
  if (link_names.empty() || link_names.size() > render::kMaxMeshesPerHypothesis)
    throw InputError(fmt::format("expected 1 to {} hypothesis links, got {}",
                                 render::kMaxMeshesPerHypothesis, link_names.size()));
  ArmHypothesisModel arm;
  for (const std::string& name : link_names) {
    const int link = model.link_index(name);  // InputError for an unknown name
    const robot::Link& l = model.link(link);
    if (l.collision.empty())
      throw InputError(fmt::format("link '{}' has no collision geometry to draw", name));
    render::TriangleMesh mesh;
    for (const robot::Geometry& g : l.collision) {
      append(mesh, render::geometry_mesh(g, segments), g.origin);
      if (!per_primitive) continue;
      arm.meshes.push_back(std::move(mesh));
      arm.mesh_link.push_back(arm.links.size());
      mesh = {};
    }
    if (!per_primitive) {
      arm.meshes.push_back(std::move(mesh));
      arm.mesh_link.push_back(arm.links.size());
    }
    arm.links.push_back(link);
  }
  if (arm.meshes.size() > render::kMaxMeshesPerHypothesis)
    throw InputError(fmt::format(
        "the hypothesis links ({}) have {} collision primitives, at most "
        "{} can be drawn one by one",
        fmt::join(link_names, " "), arm.meshes.size(), render::kMaxMeshesPerHypothesis));
  return arm;
}

LikelihoodKind likelihood_kind_from_name(const std::string& name) {
  if (const auto kind = parse_enum<LikelihoodKind>(name)) return *kind;
  throw InputError(fmt::format("unknown likelihood '{}' (expected silhouette or edges)", name));
}

HypothesisScorer::HypothesisScorer(std::shared_ptr<const robot::RobotModel> model,
                                   const ArmHypothesisModel& arm, std::vector<int> offset_dofs,
                                   int workers, const ScorerOptions& options,
                                   render::RenderBackend backend,
                                   const ArmHypothesisModel& occluder)
    : model_(std::move(model)),
      links_(arm.links),
      mesh_link_(arm.mesh_link),
      offset_dofs_(std::move(offset_dofs)),
      occluder_links_(occluder.links),
      occluder_mesh_link_(occluder.mesh_link),
      occluder_offsets_rad_(Eigen::VectorXd::Zero(model_->num_dofs())),
      options_(options),
      renderer_(all_meshes(arm, occluder), workers, backend, options.rasterizer),
      data_(*model_),
      offsets_rad_(Eigen::VectorXd::Zero(model_->num_dofs())) {
  if (!occluder.meshes.empty() && options.rasterizer != render::Rasterizer::kSoftware)
    throw InputError("occluders need rasterizer: software");
  if (occluder_mesh_link_.size() != occluder.meshes.size())
    throw InputError(fmt::format("hypothesis scorer: {} occluder meshes but {} mesh links",
                                 occluder.meshes.size(), occluder_mesh_link_.size()));
  if (options.inner_contours && options.kind != LikelihoodKind::kEdges)
    throw InputError("edge_inner_contours needs likelihood: edges");
  if (options.inner_contours && options.rasterizer != render::Rasterizer::kSoftware)
    throw InputError("edge_inner_contours needs rasterizer: software");
  if (options.crease_contours && !options.inner_contours)
    throw InputError("edge_crease_contours needs edge_inner_contours");
  if (mesh_link_.size() != arm.meshes.size())
    throw InputError(fmt::format("hypothesis scorer: {} meshes but {} mesh links",
                                 arm.meshes.size(), mesh_link_.size()));
  for (std::size_t m = 0; m < arm.meshes.size(); ++m) batch_.meshes.push_back(m);
  batch_.occluders.resize(occluder.meshes.size());
  for (std::size_t o = 0; o < occluder.meshes.size(); ++o)
    batch_.occluders[o].mesh = arm.meshes.size() + o;
}

void HypothesisScorer::set_occluder_offsets(const Eigen::VectorXd& offsets_rad) {
  if (offsets_rad.size() != model_->num_dofs() || !offsets_rad.allFinite())
    throw InputError(fmt::format(
        "hypothesis scorer: occluder offsets: expected {} finite values (one per dof), got {}",
        model_->num_dofs(), offsets_rad.size()));
  occluder_offsets_rad_ = offsets_rad;
}

void HypothesisScorer::pose_occluders(const Eigen::VectorXd& q) {
  if (batch_.occluders.empty()) return;
  robot::forward_kinematics(*model_, data_, q, occluder_offsets_rad_);
  for (std::size_t o = 0; o < batch_.occluders.size(); ++o)
    batch_.occluders[o].pose = data_.link_poses[occluder_links_[occluder_mesh_link_[o]]];
}

std::vector<Eigen::Isometry3d> HypothesisScorer::link_poses(const Eigen::VectorXd& q,
                                                            const Eigen::VectorXd& offsets_deg) {
  for (std::size_t j = 0; j < offset_dofs_.size(); ++j)
    offsets_rad_[offset_dofs_[j]] =
        offsets_deg[static_cast<Eigen::Index>(j)] * std::numbers::pi / 180.0;
  robot::forward_kinematics(*model_, data_, q, offsets_rad_);
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(links_.size());
  for (int link : links_) poses.push_back(data_.link_poses[link]);
  return poses;
}

std::vector<double> HypothesisScorer::score(const Eigen::VectorXd& q,
                                            const Eigen::MatrixXd& particles_deg,
                                            const std::vector<render::Camera>& cameras,
                                            const std::vector<cv::Mat>& observations) {
  if (observations.size() != cameras.size())
    throw InputError(fmt::format("hypothesis scorer: {} cameras but {} observations",
                                 cameras.size(), observations.size()));
  auto t0 = Clock::now();
  pose_occluders(q);
  const auto m_count = static_cast<std::size_t>(particles_deg.cols());
  batch_.hypotheses.resize(m_count);
  for (std::size_t m = 0; m < m_count; ++m) {
    const std::vector<Eigen::Isometry3d> links =
        link_poses(q, particles_deg.col(static_cast<Eigen::Index>(m)));
    render::Hypothesis& poses = batch_.hypotheses[m];
    poses.resize(mesh_link_.size());
    for (std::size_t k = 0; k < mesh_link_.size(); ++k) poses[k] = links[mesh_link_[k]];
  }
  batch_.cameras = cameras;
  timing_.kinematics_ms = ms_since(t0);

  t0 = Clock::now();
  render::HypothesisBatchOptions render_options;
  render_options.margin_px = options_.margin_px;
  render_options.contour = options_.kind == LikelihoodKind::kEdges;
  render_options.contour_width = options_.contour_width;
  render_options.inner_contours = options_.inner_contours;
  render_options.crease_contours = options_.crease_contours;
  last_ = renderer_.render(batch_, render_options);
  timing_.render_ms = ms_since(t0);

  t0 = Clock::now();
  std::vector<double> likelihoods(m_count, 1.0);
  for (std::size_t c = 0; c < cameras.size(); ++c) {
    const render::CameraTiles& tiles = last_.cameras[c];
    if (options_.kind == LikelihoodKind::kSilhouette) {
      const MaskObservation obs = cut_to_roi(observations[c], tiles.roi);
      for (std::size_t m = 0; m < m_count; ++m)
        likelihoods[m] *=
            silhouette_likelihood(jaccard(obs, tiles.tiles[m]), options_.form, options_.power);
    } else {
      const cv::Mat distance = observations[c](tiles.roi);
      const double weight = options_.edge_orientation_weight;
      for (std::size_t m = 0; m < m_count; ++m)
        likelihoods[m] *= edge_likelihood(
            weight > 0 ? mean_oriented_chamfer_distance(distance, tiles.tiles[m], weight)
                       : mean_chamfer_distance(distance, tiles.tiles[m]),
            options_.edge_lambda);
    }
  }
  timing_.compare_ms = ms_since(t0);
  return likelihoods;
}

}  // namespace somasim::body_schema
