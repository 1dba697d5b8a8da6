// bullet_world: kinematics of the multibody, resting contact, motors, self-collision, objects,
// meshes, determinism.
#include <gtest/gtest.h>

#include <cmath>

#include "bullet_world.hpp"
#include "self_collision_filter.hpp"
#include "somasim/robot/inverse_kinematics.hpp"
#include "somasim/robot/kinematic_chain.hpp"
#include "somasim/robot/kinematics.hpp"
#include "world_test_support.hpp"

using somasim::Contacts;
using somasim::JointCommand;
using somasim::JointState;
using somasim::LinkPoses;
using somasim::ObjectSpawns;
using somasim::ObjectStates;
using somasim::testing::Harness;
using namespace world_test;

namespace {

// Largest position [m] and rotation [rad] error of the world's link poses against the model.
std::pair<double, double> link_pose_error(const somasim::robot::RobotModel& model,
                                          const Eigen::VectorXd& q, const LinkPoses& poses) {
  somasim::robot::RobotData data(model);
  somasim::robot::forward_kinematics(model, data, q);
  double dp = 0, dr = 0;
  for (int i = 0; i < model.num_links(); ++i) {
    const Eigen::Isometry3d& a = poses.poses.at(i);
    const Eigen::Isometry3d& b = data.link_poses[i];
    dp = std::max(dp, (a.translation() - b.translation()).norm());
    dr = std::max(dr, Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle());
  }
  return {dp, dr};
}

bool has_contact(const Contacts& c, int link_a, int link_b) {
  for (const auto& p : c.points)
    if ((p.link_a == link_a && p.link_b == link_b) || (p.link_a == link_b && p.link_b == link_a))
      return true;
  return false;
}

}  // namespace

TEST(BulletWorld, LinkPosesMatchTheModelKinematicsAtTheInitialPosture) {
  const auto model = icub();
  for (const Eigen::VectorXd& q : {rest_posture(*model), palm_up_posture(*model)}) {
    Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q)));
    h.step(0);  // start(): the state at t = 0
    const auto& poses = h.output<LinkPoses>("world.link_poses");
    ASSERT_EQ(static_cast<int>(poses.poses.size()), model->num_links());
    auto [dp, dr] = link_pose_error(*model, q, poses);
    EXPECT_LT(dp, 1e-9);
    EXPECT_LT(dr, 1e-9);
    // Held by the motors under gravity: still within a millimetre after 0.2 s.
    h.step(200);
    std::tie(dp, dr) = link_pose_error(*model, q, poses);
    EXPECT_LT(dp, 1e-3);
    const auto& js = h.output<JointState>("world.joint_state");
    EXPECT_LT((js.position - q).cwiseAbs().maxCoeff(), 2e-3);
  }
}

TEST(BulletWorld, LinkPosesFollowTheJointsThroughTheWholeTree) {
  // Move every joint (velocity mode) and compare the reported poses with FK of the reported q.
  const auto model = icub();
  Harness h(world_yaml("gravity: [0, 0, 0]"));
  JointCommand& cmd = h.input<JointCommand>("cmd");
  cmd.mode.assign(model->num_dofs(), somasim::JointCommandMode::kVelocity);
  cmd.velocity = Eigen::VectorXd::Constant(model->num_dofs(), 0.5);
  h.step(300);
  const Eigen::VectorXd q = h.output<JointState>("world.joint_state").position;
  EXPECT_GT((q - rest_posture(*model)).norm(), 0.3);
  const auto [dp, dr] = link_pose_error(*model, q, h.output<LinkPoses>("world.link_poses"));
  EXPECT_LT(dp, 1e-9);
  EXPECT_LT(dr, 1e-9);
}

TEST(BulletWorld, ADroppedBallComesToRestOnAPalmHeldFlat) {
  const auto model = icub();
  const Eigen::VectorXd q = palm_up_posture(*model);
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q);
  const auto palm = model->frame_ref("r_palm_skin");
  const Eigen::Isometry3d palm_pose = somasim::robot::frame_pose(data, palm);
  ASSERT_GT(palm_pose.linear().col(2).z(), 0.999);  // palm normal up
  const double r = 0.015;
  const Eigen::Vector3d start = palm_pose.translation() + Eigen::Vector3d(0, 0, r + 0.05);

  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q)));
  h.input<ObjectSpawns>("spawns").recent = {sphere(1, "ball", r, start)};
  h.step(2000);
  const auto& objects = h.output<ObjectStates>("world.objects");
  ASSERT_EQ(objects.names.size(), 1u);
  ASSERT_TRUE(objects.present[0]);
  const Eigen::Vector3d p = objects.poses[0].translation();
  const auto& poses = h.output<LinkPoses>("world.link_poses");
  const Eigen::Isometry3d palm_now = poses.poses[palm.link] * palm.pose;
  const Eigen::Vector3d in_palm = palm_now.inverse() * p;
  EXPECT_NEAR(in_palm.z(), r, 1e-3);                   // resting on the palm surface
  EXPECT_LT(in_palm.head<2>().norm(), 0.02);           // not rolled away
  EXPECT_LT(objects.linear_velocity[0].norm(), 1e-3);  // at rest
  // The palm carries the ball's weight.
  const auto& contacts = h.output<Contacts>("world.contacts");
  const int hand = model->link_index("r_hand");
  double force = 0;
  for (const auto& c : contacts.points) {
    if (c.link_a != hand || c.object_b != 0) continue;
    force += c.normal_force;
    EXPECT_NEAR(c.normal.z(), -1.0, 1e-2);  // from the ball (b) towards the hand (a)
    EXPECT_NEAR((poses.poses[hand] * c.point_in_a - c.point).norm(), 0.0, 1e-9);
  }
  EXPECT_NEAR(force, 0.05 * 9.81, 0.05);
  h.finish();
  EXPECT_EQ(h.metric("world", "steps"), 2000);
  EXPECT_EQ(h.metric("world", "objects_spawned"), 1);
  EXPECT_GT(h.metric("world", "contact_points").get<int>(), 0);
}

TEST(BulletWorld, JointMotorsTrackAStepTargetWithinTheDocumentedSettlingTime) {
  const auto model = icub();
  const Eigen::VectorXd q0 = rest_posture(*model);
  for (const auto& [joint, step_deg] :
       std::vector<std::pair<std::string, double>>{{"r_elbow", 30},
                                                   {"r_shoulder_pitch", -28},
                                                   {"l_shoulder_roll", 25},
                                                   {"torso_yaw", 20},
                                                   {"r_wrist_prosup", -28}}) {
    Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0)));
    const int dof = model->dof_index(joint);
    JointCommand cmd = hold(q0);
    cmd.position[dof] += step_deg * M_PI / 180.0;
    h.input<JointCommand>("cmd") = cmd;
    const double step = step_deg * M_PI / 180.0;
    double settled_at = -1;
    for (int k = 1; k <= 1000; ++k) {
      h.step();
      const double err =
          cmd.position[dof] - h.output<JointState>("world.joint_state").position[dof];
      if (std::abs(err) > 0.02 * std::abs(step))
        settled_at = -1;
      else if (settled_at < 0)
        settled_at = k * 1e-3;
    }
    SCOPED_TRACE(joint);
    ASSERT_GT(settled_at, 0.0);
    EXPECT_LE(settled_at, somasim::bullet_world::kDefaultSettlingTime);
    std::printf("settling time %s (%.0f deg): %.3f s\n", joint.c_str(), step_deg, settled_at);
  }
}

TEST(BulletWorld, VelocityCommandsMoveJointsAndLimitsHold) {
  const auto model = icub();
  Harness h(world_yaml());
  const int elbow = model->dof_index("r_elbow");
  JointCommand cmd;
  cmd.mode.assign(model->num_dofs(), somasim::JointCommandMode::kNone);
  cmd.mode[elbow] = somasim::JointCommandMode::kVelocity;
  cmd.velocity = Eigen::VectorXd::Zero(model->num_dofs());
  cmd.velocity[elbow] = 1.0;
  h.input<JointCommand>("cmd") = cmd;
  h.step(200);
  const auto& js = h.output<JointState>("world.joint_state");
  EXPECT_NEAR(js.velocity[elbow], 1.0, 0.05);
  h.step(3000);  // far beyond the upper limit (106 deg) if nothing stopped it
  EXPECT_NEAR(js.position[elbow], model->upper_limits()[elbow], 0.01);
}

TEST(BulletWorld, AdjacentLinksAreFilteredArmsAndHandBodyPairsAreNot) {
  const auto model = icub();
  somasim::bullet_world::SelfCollisionFilter filter(*model);
  auto adjacent = [&](const char* a, const char* b) {
    return filter.adjacent(model->link_index(a), model->link_index(b));
  };
  EXPECT_TRUE(adjacent("r_upper_arm", "r_forearm"));  // through the elbow's frame link
  EXPECT_TRUE(adjacent("r_forearm", "r_hand"));
  EXPECT_TRUE(adjacent("chest", "head"));
  EXPECT_TRUE(adjacent("root_link", "chest"));
  EXPECT_TRUE(adjacent("chest", "l_upper_arm"));
  EXPECT_FALSE(adjacent("r_hand", "l_forearm"));
  EXPECT_FALSE(adjacent("r_hand", "chest"));
  EXPECT_FALSE(adjacent("r_hand", "r_upper_arm"));
  EXPECT_FALSE(adjacent("l_hand", "head"));
  EXPECT_FALSE(adjacent("r_forearm", "l_forearm"));
}

TEST(BulletWorld, NoContactsBetweenLinksAtRest) {
  const auto model = icub();
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, rest_posture(*model))));
  h.step(500);
  EXPECT_TRUE(h.output<Contacts>("world.contacts").points.empty());
  h.finish();
  EXPECT_EQ(h.metric("world", "contact_points"), 0);
}

TEST(BulletWorld, MovingTheRightHandIntoTheLeftForearmMakesContactsBetweenThem) {
  const auto model = icub();
  // Left forearm across the front of the body; right hand reaching to it.
  const Eigen::VectorXd q0 = with_joints_deg(*model, rest_posture(*model),
                                             {{"l_shoulder_pitch", -40},
                                              {"l_shoulder_roll", 30},
                                              {"l_shoulder_yaw", 20},
                                              {"l_elbow", 90}});
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q0);
  const int l_forearm = model->link_index("l_forearm"), r_hand = model->link_index("r_hand");
  const Eigen::Vector3d target = data.link_poses[l_forearm] * Eigen::Vector3d(0, -0.07, 0);
  // The right arm alone (chest → palm) brings the palm to the forearm's axis (reachable within
  // a few mm): the hand presses on the forearm.
  const somasim::robot::KinematicChain chain(*model, "r_palm", "chest");
  const Eigen::Isometry3d chest = data.link_poses[model->link_index("chest")];
  Eigen::VectorXd qc(chain.num_dofs());
  chain.gather(q0, qc);
  somasim::robot::IkSolver ik(chain);
  EXPECT_LT(ik.solve_position(chest.inverse() * target, qc).position_error, 0.01);
  Eigen::VectorXd q1 = q0;
  for (int k = 0; k < chain.num_dofs(); ++k) q1[chain.dof_indices()[k]] = qc[k];

  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0)));
  h.step(100);
  EXPECT_FALSE(has_contact(h.output<Contacts>("world.contacts"), r_hand, l_forearm));
  h.input<JointCommand>("cmd") = hold(q1);
  bool touched = false;
  for (int k = 0; k < 1500 && !touched; ++k) {
    h.step();
    touched = has_contact(h.output<Contacts>("world.contacts"), r_hand, l_forearm);
  }
  EXPECT_TRUE(touched);
  for (const auto& c : h.output<Contacts>("world.contacts").points) {
    if (c.link_a >= 0 && c.link_b >= 0) {
      EXPECT_GE(c.normal_force, 0.0);
    }
  }
}

TEST(BulletWorld, KinematicObjectFollowsItsTrajectory) {
  Harness h(world_yaml());
  auto s =
      sphere(7, "probe", 0.02, Eigen::Vector3d(-0.8, -0.3, 0.2), somasim::ObjectMotion::kKinematic);
  s.linear_velocity = Eigen::Vector3d(0.1, 0.2, -0.05);
  h.input<ObjectSpawns>("spawns").recent = {s};
  const auto& objects = h.output<ObjectStates>("world.objects");
  for (int k = 1; k <= 500; ++k) {
    h.step();
    const Eigen::Vector3d expected = s.pose.translation() + k * 1e-3 * s.linear_velocity;
    ASSERT_LT((objects.poses[0].translation() - expected).norm(), 1e-9) << "step " << k;
  }
  EXPECT_LT((objects.linear_velocity[0] - s.linear_velocity).norm(), 1e-6);
  EXPECT_EQ(objects.names[0], "probe");
}

TEST(BulletWorld, ObjectsAreRemovedAfterTheirLifetimeAndWhenTheyFallAway) {
  Harness h(world_yaml("world_radius: 2"));
  auto a = sphere(1, "short", 0.02, Eigen::Vector3d(-1, 0, 0.5));
  a.remove_after_s = 0.1;
  auto b = sphere(2, "faller", 0.02, Eigen::Vector3d(-1, 0.5, 0.5));
  h.input<ObjectSpawns>("spawns").recent = {a, b};
  const auto& objects = h.output<ObjectStates>("world.objects");
  h.step(150);
  ASSERT_EQ(objects.present.size(), 2u);
  EXPECT_FALSE(objects.present[0]);
  EXPECT_TRUE(objects.present[1]);
  h.step(800);  // falls 2 m in about 0.64 s
  EXPECT_FALSE(objects.present[1]);
  h.finish();
  EXPECT_EQ(h.metric("world", "objects_out_of_bounds"), 1);
}

TEST(BulletWorld, ObjectsNamedForWithdrawalAreRemovedAtOnce) {
  Harness h(world_yaml());
  auto a =
      sphere(1, "held", 0.02, Eigen::Vector3d(-0.8, -0.3, 0.2), somasim::ObjectMotion::kKinematic);
  auto b =
      sphere(2, "other", 0.02, Eigen::Vector3d(-0.8, 0.3, 0.2), somasim::ObjectMotion::kKinematic);
  auto& spawns = h.input<ObjectSpawns>("spawns");
  spawns.recent = {a, b};
  const auto& objects = h.output<ObjectStates>("world.objects");
  h.step(10);
  ASSERT_TRUE(objects.present[0]);
  spawns.withdraw = {"held", "never_spawned"};
  h.step();
  EXPECT_FALSE(objects.present[0]);
  EXPECT_TRUE(objects.present[1]);
  h.step(5);  // still listed: nothing more happens
  EXPECT_TRUE(objects.present[1]);
  h.finish();
  EXPECT_EQ(h.metric("world", "objects_withdrawn"), 1);
}

TEST(BulletWorld, SceneObjectsIncludingMeshesStandAndCarry) {
  // A 20 cm cube mesh as a static table, a dynamic mesh box on it and a ball on the table.
  const TempFile mesh("cube.obj",
                      "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                      "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                      "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                      "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
  const std::string m = mesh.str();
  const TempFile scene(
      "scene.yaml",
      "objects:\n"
      "  - {name: table, shape: mesh, file: " +
          m +
          ", scale: 0.1, motion: static,"
          " xyz: [-0.6, 0, 0]}\n"
          "  - {name: block, shape: mesh, file: " +
          m +
          ", scale: [0.02, 0.02, 0.02],"
          " mass: 0.1, xyz: [-0.55, 0.05, 0.13]}\n"
          "  - {name: ball, shape: sphere, radius: 0.02, xyz: [-0.65, -0.05, 0.15]}\n"
          "  - {name: can, shape: cylinder, radius: 0.02, length: 0.06, motion: static,"
          " xyz: [-0.6, 0.6, 0]}\n"
          "  - {name: crate, shape: box, size: [0.1, 0.1, 0.1], motion: static,"
          " xyz: [-0.6, -0.6, 0]}\n");
  Harness h(world_yaml("scene: " + scene.str()));
  h.step(1500);
  const auto& o = h.output<ObjectStates>("world.objects");
  ASSERT_EQ(o.names, (std::vector<std::string>{"table", "block", "ball", "can", "crate"}));
  EXPECT_NEAR(o.poses[0].translation().z(), 0.0, 1e-12);
  EXPECT_NEAR(o.poses[1].translation().z(), 0.12, 2e-3);  // block (2 cm half size) on the table
  EXPECT_NEAR(o.poses[2].translation().z(), 0.12, 2e-3);  // ball (2 cm radius) on the table
  EXPECT_LT(o.linear_velocity[2].norm(), 1e-3);
  // Bounding radii are conservative (Bullet's bounding sphere of the shape's box).
  EXPECT_GE(o.radius[3], std::sqrt(0.02 * 0.02 + 0.03 * 0.03));
  EXPECT_LT(o.radius[3], std::sqrt(0.02 * 0.02 + 0.03 * 0.03) + 0.01);
  // The shapes travel with the objects, so that others than the physics can draw them.
  using somasim::ObjectShape;
  EXPECT_EQ(o.shape,
            (std::vector<ObjectShape>{ObjectShape::kMesh, ObjectShape::kMesh, ObjectShape::kSphere,
                                      ObjectShape::kCylinder, ObjectShape::kBox}));
  EXPECT_EQ(o.mesh[0], m);
  EXPECT_EQ(o.mesh[2], "");
  EXPECT_EQ(o.size[1], Eigen::Vector3d(0.02, 0.02, 0.02));
  EXPECT_EQ(o.size[2].x(), 0.02);                               // sphere: radius
  EXPECT_EQ(o.size[3].head<2>(), Eigen::Vector2d(0.02, 0.03));  // cylinder: radius, half height
  EXPECT_EQ(o.size[4], Eigen::Vector3d(0.05, 0.05, 0.05));      // box: half extents
  h.finish();
  EXPECT_EQ(h.metric("world", "objects_spawned"), 5);
}

TEST(BulletWorld, SameInputsGiveIdenticalOutputs) {
  const auto model = icub();
  const Eigen::VectorXd q = palm_up_posture(*model);
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q);
  const Eigen::Vector3d palm =
      somasim::robot::frame_pose(data, model->frame_ref("r_palm_skin")).translation();
  auto run = [&] {
    Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q)));
    std::vector<double> trace;
    for (int k = 0; k < 600; ++k) {
      if (k % 100 == 0) {
        auto s = sphere(k, "ball" + std::to_string(k), 0.012,
                        palm + Eigen::Vector3d(0.0001 * k, 0.0, 0.05));
        h.input<ObjectSpawns>("spawns").recent.push_back(s);
        h.input<JointCommand>("cmd") =
            hold(with_joints_deg(*model, q, {{"r_wrist_pitch", -k / 60.0}}));
      }
      h.step();
      for (double v : h.output<JointState>("world.joint_state").position) trace.push_back(v);
      for (const auto& p : h.output<ObjectStates>("world.objects").poses)
        for (double v : p.matrix().reshaped()) trace.push_back(v);
      for (const auto& c : h.output<Contacts>("world.contacts").points) {
        trace.push_back(c.normal_force);
        for (double v : c.point) trace.push_back(v);
      }
    }
    return trace;
  };
  const auto a = run();
  const auto b = run();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(a == b);
}

// ---- Locked joints (folded into rigid bodies) ----

TEST(BulletWorldLocked, ContactsOnAFoldedLinkNameItAndPosesMatchTheKinematics) {
  // The wrist locked: r_hand (palm and fingers) is folded into the r_forearm body. A ball
  // dropped on the palm still touches link 'r_hand', which carries its weight.
  const auto model = icub();
  const Eigen::VectorXd q = palm_up_posture(*model);
  somasim::robot::RobotData data(*model);
  somasim::robot::forward_kinematics(*model, data, q);
  const auto palm = model->frame_ref("r_palm_skin");
  const double r = 0.015;
  const Eigen::Vector3d start =
      somasim::robot::frame_pose(data, palm).translation() + Eigen::Vector3d(0, 0, r + 0.05);
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q) +
                       ", locked_joints: 'r_wrist_pitch, r_wrist_yaw'"));
  h.step(0);
  auto [dp, dr] = link_pose_error(*model, q, h.output<LinkPoses>("world.link_poses"));
  EXPECT_LT(dp, 1e-9);
  EXPECT_LT(dr, 1e-9);
  h.input<ObjectSpawns>("spawns").recent = {sphere(1, "ball", r, start)};
  h.step(1500);
  const Eigen::VectorXd q_now = h.output<JointState>("world.joint_state").position;
  for (const char* locked : {"r_wrist_pitch", "r_wrist_yaw"})  // q up to the posture's 1e-12 deg
    EXPECT_NEAR(q_now[model->dof_index(locked)], q[model->dof_index(locked)], 1e-12);
  std::tie(dp, dr) = link_pose_error(*model, q_now, h.output<LinkPoses>("world.link_poses"));
  EXPECT_LT(dp, 1e-9);  // folded links follow their body exactly
  EXPECT_LT(dr, 1e-9);
  const int hand = model->link_index("r_hand");
  double force = 0;
  int on_hand = 0, on_others = 0;
  for (const auto& c : h.output<Contacts>("world.contacts").points) {
    if (c.object_b != 0) continue;
    (c.link_a == hand ? on_hand : on_others)++;
    if (c.link_a == hand) force += c.normal_force;
  }
  EXPECT_GT(on_hand, 0);
  EXPECT_EQ(on_others, 0);
  EXPECT_NEAR(force, 0.05 * 9.81, 0.05);
}

TEST(BulletWorldLocked, AllLockedRobotIsStaticGeometryThatCarriesABallOnTheForearm) {
  const auto model = icub();
  // The left forearm held horizontal (its axis is the link's y axis): search the elbow.
  Eigen::VectorXd q = with_joints_deg(*model, rest_posture(*model),
                                      {{"l_shoulder_pitch", -40}, {"l_shoulder_roll", 40}});
  const int l_forearm = model->link_index("l_forearm"), elbow = model->dof_index("l_elbow");
  somasim::robot::RobotData data(*model);
  double best = 1e9, best_elbow = 0;
  for (double e = model->lower_limits()[elbow]; e <= model->upper_limits()[elbow]; e += 1e-4) {
    q[elbow] = e;
    somasim::robot::forward_kinematics(*model, data, q);
    const double tilt = std::abs(data.link_poses[l_forearm].linear()(2, 1));
    if (tilt < best) best = tilt, best_elbow = e;
  }
  q[elbow] = best_elbow;
  ASSERT_LT(best, 1e-3);
  somasim::robot::forward_kinematics(*model, data, q);
  // Drop a ball on top of the forearm, from above a point of its axis.
  const Eigen::Vector3d axis_point = data.link_poses[l_forearm] * Eigen::Vector3d(0, -0.07, 0);
  const double r = 0.015;
  Harness h(
      world_yaml("initial_posture_deg: " + posture_param(*model, q) + ", locked_joints: all"));
  h.input<ObjectSpawns>("spawns").recent = {
      sphere(1, "ball", r, axis_point + Eigen::Vector3d(0, 0, 0.08))};
  const auto& contacts = h.output<Contacts>("world.contacts");
  h.step(1500);
  double force = 0;
  int on_forearm = 0;
  for (const auto& c : contacts.points) {
    EXPECT_EQ(c.object_b, 0);
    EXPECT_EQ(c.link_a, l_forearm);
    if (c.link_a != l_forearm) continue;
    ++on_forearm;
    force += c.normal_force;
    EXPECT_NEAR(c.normal.z(), -1.0, 1e-2);
  }
  EXPECT_GT(on_forearm, 0);
  EXPECT_NEAR(force, 0.05 * 9.81, 0.02);
  const auto& objects = h.output<ObjectStates>("world.objects");
  EXPECT_LT(objects.linear_velocity[0].norm(), 1e-3);
  // Constant joint state and poses equal to the kinematics.
  const auto& js = h.output<JointState>("world.joint_state");
  EXPECT_LT((js.position - q).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(js.velocity.norm(), 0.0);
  const auto [dp, dr] = link_pose_error(*model, q, h.output<LinkPoses>("world.link_poses"));
  EXPECT_LT(dp, 1e-9);
  EXPECT_LT(dr, 1e-9);
}

TEST(BulletWorld, MiscalibratedEncodersReadRealMinusOffsetAndCommandsAreEncoderValues) {
  const auto model = icub();
  const Eigen::VectorXd q0 = rest_posture(*model);
  Harness h(world_yaml("initial_posture_deg: " + posture_param(*model, q0) +
                       ", encoder_offsets_deg: 'r_elbow: 5, r_wrist_pitch: -7'"));
  const int elbow = model->dof_index("r_elbow"), wrist = model->dof_index("r_wrist_pitch");
  const double rad = M_PI / 180.0;
  // The initial posture is real: the encoders read it minus the offsets.
  h.input<JointCommand>("cmd") = hold(q0 - Eigen::VectorXd::Unit(q0.size(), elbow) * 5 * rad +
                                      Eigen::VectorXd::Unit(q0.size(), wrist) * 7 * rad);
  h.step();
  const JointState& js = h.output<JointState>("world.joint_state");
  EXPECT_NEAR(js.position[elbow], q0[elbow] - 5 * rad, 1e-3);
  EXPECT_NEAR(js.position[wrist], q0[wrist] + 7 * rad, 1e-3);
  // An encoder target of 40 deg at the elbow drives the real joint to 45 deg.
  JointCommand cmd = h.input<JointCommand>("cmd");
  cmd.position[elbow] = 40 * rad;
  h.input<JointCommand>("cmd") = cmd;
  for (int k = 0; k < 1500; ++k) h.step();
  EXPECT_NEAR(h.output<JointState>("world.joint_state").position[elbow], 40 * rad, 2e-3);
  Eigen::VectorXd real = h.output<JointState>("world.joint_state").position;
  real[elbow] += 5 * rad;
  real[wrist] -= 7 * rad;
  const auto [dp, dr] = link_pose_error(*model, real, h.output<LinkPoses>("world.link_poses"));
  EXPECT_LT(dp, 1e-4);
  EXPECT_LT(dr, 1e-3);
}
